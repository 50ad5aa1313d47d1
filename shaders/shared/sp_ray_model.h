// The paper's ray model (SPEC 1.2-1.4) as pure functions over RayState,
// shared by GLSL and C++. Each wavefront iteration gives a live ray exactly
// one cast: Active rays cast forward, ResolvingPenetration rays backcast.
// Paper: "Diegetic Sound Visualization", sections 4.2-4.4.
#ifndef SP_RAY_MODEL_H
#define SP_RAY_MODEL_H

#include "sp_random.h"
#include "sp_types.h"

SP_BEGIN_NAMESPACE

SP_INLINE RayState sp_emit_ray(StepSource source, uint source_slot, uint ray_index, uint seed, uint step) {
  RayState r;
  r.origin = source.position;
  r.energy = source.loudness;
  r.dir = sp_emission_direction(seed, step, ray_index);
  r.travelled = 0.0f;
  r.entry = vec3(0.0f, 0.0f, 0.0f);
  r.entry_layer = 0u;
  r.state = SP_RAY_ACTIVE;
  r.bounces = 0u;
  r.penetrations = 0u;
  r.ray_index = ray_index;
  r.source = source_slot;
  r.casts = 0u;
  r.max_distance = source.max_distance;
  r.loudness = source.loudness;
  return r;
}

// Far limit of an Active ray's cast: min(D_max - travelled, (E - tau_min) / alpha_air).
SP_INLINE float sp_active_reach(RayState r, SimParams p) {
  SP_PRECISE float reach = r.max_distance - r.travelled;
  if (p.air_attenuation > 0.0f) {
    SP_PRECISE float energy_reach = (r.energy - p.min_energy) / p.air_attenuation;
    reach = min(reach, energy_reach);
  }
  return reach;
}

// Where an Active ray's cast starts, and where a ResolvingPenetration ray's
// backcast segment starts: the backcast searches (SP_EPSILON, W_max] from p_in
// for the exit face nearest to p_in (SPEC 1.3, not the paper's far-end hit).
SP_INLINE vec3 sp_cast_origin(RayState r) {
  return r.state == SP_RAY_RESOLVING ? r.entry : r.origin;
}
SP_INLINE float sp_cast_tmin(RayState r) {
  return r.state == SP_RAY_RESOLVING ? SP_EPSILON : 0.0f;
}
SP_INLINE float sp_cast_tmax(RayState r, SimParams p) {
  return r.state == SP_RAY_RESOLVING ? p.max_wall_thickness : sp_active_reach(r, p);
}

SP_INLINE Indicator sp_make_indicator(uint kind, RayState r, StepSource source, vec3 position, vec3 normal,
                                      SimParams p) {
  Indicator ind;
  ind.position = position;
  ind.energy = r.energy;
  ind.normal = normal;
  SP_PRECISE float size = p.indicator_size * r.energy / r.loudness;
  ind.size = size;
  ind.color = source.color;
  ind.intensity = source.intensity;
  ind.kind = kind;
  ind.source_id = source.source_id;
  ind.bounces = r.bounces;
  ind.penetrations = r.penetrations;
  ind.path_length = r.travelled;
  ind.step = p.step;
  ind.ray_index = r.ray_index;
  ind.iteration = r.casts;
  return ind;
}

SP_INLINE vec3 sp_offset_point(vec3 p, vec3 dir, float distance) {
  SP_PRECISE vec3 q = p + dir * distance;
  return q;
}

// Resolves an Active ray's forward cast. `tri` is only read when hit.triangle
// is valid; `layer` holds the acoustics of tri.layer. Writes `ind` when the
// result has SP_OUTCOME_INDICATOR.
SP_INLINE uint sp_resolve_active(SP_INOUT(RayState) r, HitInfo hit, BvhTriangle tri, LayerAcoustics layer,
                                 StepSource source, SimParams p, SP_OUT(Indicator) ind) {
  r.casts += 1u;
  if (hit.triangle == SP_INVALID) {
    r.state = SP_RAY_DEAD;
    return 0u;
  }
  SP_PRECISE float travelled = r.travelled + hit.t;
  SP_PRECISE float energy = r.energy - hit.t * p.air_attenuation;
  r.travelled = travelled;
  r.energy = energy;
  uint outcome = SP_OUTCOME_HIT;
  if (r.energy <= p.min_energy) {
    r.state = SP_RAY_DEAD;
    return outcome;
  }
  vec3 position = sp_offset_point(r.origin, r.dir, hit.t);
  vec3 normal = dot(tri.normal, r.dir) > 0.0f ? -tri.normal : tri.normal;  // towards the ray's side
  ind = sp_make_indicator(SP_INDICATOR_HIT, r, source, position, normal, p);
  outcome |= SP_OUTCOME_INDICATOR;
  uint interactions = r.bounces + r.penetrations;
  if (interactions >= p.max_bounces) {
    r.state = SP_RAY_DEAD;
    return outcome;
  }
  float u = sp_decision_random(p.seed, p.step, r.ray_index, interactions);
  if (u < layer.reflect_probability) {
    outcome |= SP_OUTCOME_REFLECT;
    SP_PRECISE float reflected_energy = r.energy * (1.0f - p.bounce_energy_loss);
    r.energy = reflected_energy;
    r.bounces += 1u;
    if (r.energy <= p.min_energy) {
      r.state = SP_RAY_DEAD;
      return outcome;
    }
    SP_PRECISE float d_n = dot(r.dir, normal);
    SP_PRECISE vec3 mirrored = r.dir - normal * (2.0f * d_n);
    SP_PRECISE float len = sqrt(dot(mirrored, mirrored));
    r.dir = mirrored / len;
    r.origin = sp_offset_point(position, normal, SP_EPSILON);
  } else {
    outcome |= SP_OUTCOME_PENETRATE;
    r.entry = position;
    r.entry_layer = tri.layer;
    r.origin = sp_offset_point(position, r.dir, p.max_wall_thickness);  // the forward step
    r.state = SP_RAY_RESOLVING;
  }
  return outcome;
}

// Resolves a ResolvingPenetration ray's backcast. `entry_layer` holds the
// acoustics of r.entry_layer; `tri` is the exit face when hit is valid.
SP_INLINE uint sp_resolve_backcast(SP_INOUT(RayState) r, HitInfo hit, BvhTriangle tri, LayerAcoustics entry_layer,
                                   StepSource source, SimParams p, SP_OUT(Indicator) ind) {
  r.casts += 1u;
  if (hit.triangle == SP_INVALID) {  // thicker than W_max: absorbed
    r.state = SP_RAY_DEAD;
    return SP_OUTCOME_BACKCAST_MISS;
  }
  float thickness = hit.t;  // == W_max - d_hit of the paper
  SP_PRECISE float energy = r.energy - thickness * entry_layer.attenuation;
  SP_PRECISE float travelled = r.travelled + thickness;
  r.energy = energy;
  r.travelled = travelled;
  r.penetrations += 1u;
  if (r.energy <= p.min_energy) {
    r.state = SP_RAY_DEAD;
    return 0u;
  }
  vec3 position = sp_offset_point(r.entry, r.dir, thickness);
  vec3 normal = dot(tri.normal, r.dir) < 0.0f ? -tri.normal : tri.normal;  // towards where it leaves to
  ind = sp_make_indicator(SP_INDICATOR_EXIT, r, source, position, normal, p);
  r.state = SP_RAY_ACTIVE;
  r.origin = sp_offset_point(position, r.dir, SP_EPSILON);
  return SP_OUTCOME_INDICATOR;
}

SP_END_NAMESPACE

#endif  // SP_RAY_MODEL_H
