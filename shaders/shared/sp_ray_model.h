// The paper's ray model (docs/model.md#propagation) as pure functions over
// RayState, shared by GLSL and C++. Each wavefront iteration gives a live ray
// exactly one cast: Active rays cast forward, ResolvingPenetration rays query
// the matter behind their entry point (sp_matter.h). Paper: sections 4.2-4.4
// (docs/model.md#the-paper).
#ifndef SP_RAY_MODEL_H
#define SP_RAY_MODEL_H

#include "sp_connect.h"
#include "sp_diffraction.h"
#include "sp_matter.h"
#include "sp_random.h"
#include "sp_types.h"

SP_BEGIN_NAMESPACE

// A new ray of `source` (entry `source_slot` of the step's table) along
// `dir`, emitted into guide cell `emit_cell` (sp_guide.h sp_source_emission).
SP_INLINE RayState sp_emit_ray(StepSource source, uint source_slot, uint ray_index, vec3 dir, uint emit_cell) {
  RayState r;
  r.origin = source.position;
  r.energy = source.loudness;
  r.dir = dir;
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
  r.entry_triangle = SP_INVALID;
  r.diffractions = 0u;
  r.emit_cell = emit_cell;
  r.pad1 = 0u;
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

// The segment of a ResolvingPenetration ray's matter query: from p_in, faces
// a touch behind it (those of a solid touching the entry face) through W_max.
SP_INLINE float sp_matter_tmin() { return -SP_CONTACT_TOLERANCE; }

// Writes every field of `ind` in place; `sent` is the energy the spot sends
// towards the listener (sp_sent_energy), which the connect pass completes. (Not a returned struct: on the CPU the
// caller's indicator is where it stays, and a whole-struct copy of fields just
// stored one by one stalls on store-to-load forwarding.)
SP_INLINE void sp_make_indicator(SP_OUT(Indicator) ind, uint kind, RayState r, StepSource source, vec3 position,
                                 vec3 normal, SimParams p, float sent) {
  ind.position = position;
  ind.energy = r.energy;
  ind.normal = normal;
  SP_PRECISE float size = p.indicator_size * r.energy / r.loudness;
  ind.size = size;
  ind.color = source.color;
  ind.intensity = source.intensity;
  ind.dir = r.dir;
  ind.path_length = r.travelled;
  ind.kind = kind;
  ind.source_id = source.source_id;
  ind.bounces = r.bounces;
  ind.penetrations = r.penetrations;
  ind.diffractions = r.diffractions;
  ind.step = p.step;
  ind.ray_index = r.ray_index;
  ind.iteration = r.casts;
  ind.arrival = sp_arrival(position, p);
  ind.heard = sent;
  ind.emit_cell = r.emit_cell;
  ind.source_slot = r.source;
  ind.toward = 0.0f;
  ind.pad0 = 0u;
}

SP_INLINE vec3 sp_offset_point(vec3 p, vec3 dir, float distance) {
  SP_PRECISE vec3 q = p + dir * distance;
  return q;
}

// Resolves an Active ray's forward cast. `tri` is only read when
// found.triangle is valid; `layer` holds the acoustics of tri.layer and
// `edges` its exposed edges (read only when p.diffraction is on). Writes
// `ind` when the result has SP_OUTCOME_INDICATOR, and `sheet_exit` (the exit
// of a sheet crossed on the spot, after `ind`) when it has
// SP_OUTCOME_SHEET_EXIT.
SP_INLINE uint sp_resolve_active(SP_INOUT(RayState) r, CastResult found, BvhTriangle tri, TriangleEdges edges,
                                 LayerAcoustics layer, StepSource source, SimParams p, SP_OUT(Indicator) ind,
                                 SP_OUT(Indicator) sheet_exit) {
  r.casts += 1u;
  if (found.triangle == SP_INVALID) {
    r.state = SP_RAY_DEAD;
    return (found.flags & SP_CAST_CUT_SHORT) != 0u ? SP_OUTCOME_CUT_SHORT : 0u;
  }
  SP_PRECISE float travelled = r.travelled + found.t;
  SP_PRECISE float energy = r.energy - found.t * p.air_attenuation;
  r.travelled = travelled;
  r.energy = energy;
  uint outcome = SP_OUTCOME_HIT;
  if (r.energy <= p.min_energy) {
    r.state = SP_RAY_DEAD;
    return outcome;
  }
  // A ray in air meets fronts only; the back of a face means it is inside
  // matter (it leaked through a crack, or the winding disagrees with the
  // geometry). It must not go on as if in air: it is absorbed, unseen.
  bool sheet = layer.sheet_thickness > 0.0f;
  uint crossing = sp_crossing(tri.normal, r.dir);
  if (!sheet && crossing == SP_CROSSING_LEAVE) {
    r.state = SP_RAY_DEAD;
    return outcome | SP_OUTCOME_BACK_FACE;
  }
  vec3 position = sp_offset_point(r.origin, r.dir, found.t);
  vec3 normal = crossing == SP_CROSSING_LEAVE ? -tri.normal
                                              : tri.normal;  // towards the ray's side (a sheet's back is a front too)
  sp_make_indicator(ind, SP_INDICATOR_HIT, r, source, position, normal, p,
                    sp_sent_energy(SP_INDICATOR_HIT, r.energy, layer, p));
  outcome |= SP_OUTCOME_INDICATOR;
  // Diffractions count as interactions: they key the random numbers and
  // max_bounces bounds them (without diffraction the sum is the paper's).
  uint interactions = r.bounces + r.penetrations + r.diffractions;
  if (interactions >= p.max_bounces) {
    r.state = SP_RAY_DEAD;
    return outcome;
  }
  uvec4 random = sp_pcg4d(p.seed, p.step, r.ray_index, interactions);
  if (p.diffraction != 0u && edges.exposed != 0u) {
    bool absorbed;
    uint turned = sp_try_diffract(r, tri, edges, position, normal, crossing != SP_CROSSING_LEAVE, p, random, absorbed);
    if (turned != 0u || absorbed) return outcome | turned;
  }
  float u = sp_unit_float(random.x);  // == sp_decision_random(p.seed, p.step, r.ray_index, interactions)
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
  } else if (sheet) {
    // A sheet is crossed on the spot: its thickness lost, no matter query, and
    // no air loss across it.
    outcome |= SP_OUTCOME_PENETRATE;
    SP_PRECISE float crossed_energy = r.energy - layer.sheet_thickness * layer.attenuation;
    SP_PRECISE float crossed_travelled = r.travelled + layer.sheet_thickness;
    r.energy = crossed_energy;
    r.travelled = crossed_travelled;
    r.penetrations += 1u;
    if (r.energy <= p.min_energy) {
      r.state = SP_RAY_DEAD;
      return outcome;
    }
    sp_make_indicator(sheet_exit, SP_INDICATOR_EXIT, r, source, position, -normal, p, r.energy);
    outcome |= SP_OUTCOME_SHEET_EXIT;
    r.origin = sp_offset_point(position, r.dir, SP_EPSILON);
  } else {
    outcome |= SP_OUTCOME_PENETRATE;
    r.entry = position;
    r.entry_layer = tri.layer;
    r.entry_triangle = found.triangle;
    // No forward step (the paper's p_in + W_max d): the matter query starts
    // at r.entry, and the exit sets r.origin (sp_resolve_matter_exit).
    r.state = SP_RAY_RESOLVING;
  }
  return outcome;
}

// Resolves a ResolvingPenetration ray's matter query (sp_find_exit); `tri`
// is the exit face when found.triangle is valid.
SP_INLINE uint sp_resolve_matter_exit(SP_INOUT(RayState) r, CastResult found, BvhTriangle tri, StepSource source,
                                      SimParams p, SP_OUT(Indicator) ind) {
  r.casts += 1u;
  if (found.triangle == SP_INVALID) {  // no way out within W_max: absorbed
    r.state = SP_RAY_DEAD;
    return SP_OUTCOME_NO_WAY_OUT | ((found.flags & SP_CAST_CUT_SHORT) != 0u ? SP_OUTCOME_CUT_SHORT : 0u);
  }
  SP_PRECISE float energy = r.energy - found.matter_loss;
  SP_PRECISE float travelled = r.travelled + found.t;
  r.energy = energy;
  r.travelled = travelled;
  r.penetrations += 1u;
  if (r.energy <= p.min_energy) {
    r.state = SP_RAY_DEAD;
    return 0u;
  }
  vec3 position = sp_offset_point(r.entry, r.dir, found.t);
  // Towards where it leaves to: the exit face's front, unless only a
  // disagreeing winding let the ray out.
  vec3 normal = sp_crossing(tri.normal, r.dir) == SP_CROSSING_ENTER ? -tri.normal : tri.normal;
  sp_make_indicator(ind, SP_INDICATOR_EXIT, r, source, position, normal, p, r.energy);
  r.state = SP_RAY_ACTIVE;
  r.origin = sp_offset_point(position, r.dir, SP_EPSILON);
  return SP_OUTCOME_INDICATOR;
}

SP_END_NAMESPACE

#endif  // SP_RAY_MODEL_H
