// Spots the player hears (docs/model.md#cues-for-the-player), shared by GLSL
// and C++: the next-event estimate of path tracing, one cast from each spot
// to the listener. A hit reflects towards the listener the share the ray
// model would reflect (rho_ref, then e_loss); an exit sends on what left the
// wall. Along the way the air takes alpha_air a metre, as along any ray. The
// spot is heard when its surface faces the listener, nothing lies between,
// and more than tau_min arrives. In first person the eye is at the listener,
// so a spot heard is also a spot the player can see.
#ifndef SP_CONNECT_H
#define SP_CONNECT_H

#include "sp_types.h"

SP_BEGIN_NAMESPACE

// The energy a spot sends towards the listener: for a hit, what a
// reflection would carry on, in expectation; for an exit, what left.
SP_INLINE float sp_sent_energy(uint kind, float energy, LayerAcoustics layer, SimParams p) {
  if (kind == SP_INDICATOR_EXIT) return energy;
  SP_PRECISE float sent = energy * layer.reflect_probability * (1.0f - p.bounce_energy_loss);
  return sent;
}

// The unit direction from the listener to `position`, the way a spot's
// sound arrives; zero when the spot is at the listener.
SP_INLINE vec3 sp_arrival(vec3 position, SimParams p) {
  SP_PRECISE vec3 d = position - p.listener;
  SP_PRECISE float len = sqrt(dot(d, d));
  if (len <= 0.0f) return vec3(0.0f, 0.0f, 0.0f);
  return vec3(d.x / len, d.y / len, d.z / len);
}

// The way between a spot and the listener: the segment from the listener to
// the spot pushed off its surface, as a reflected ray starts. It is cast
// from the listener's end: every spot's cast then starts in the same
// place, where a blocked way is most often blocked (the walls round the
// player), so it stops early and walks nodes the last cast left in cache.
struct Connection {
  vec3 origin;     // the listener
  float distance;  // to the spot
  vec3 dir;        // unit, from the listener to the spot
  uint candidate;  // 1: worth casting (faces the listener, enough energy)
};

SP_INLINE Connection sp_connection(Indicator ind, SimParams p) {
  Connection c;
  SP_PRECISE vec3 spot = ind.position + ind.normal * SP_EPSILON;
  c.origin = p.listener;
  SP_PRECISE vec3 to = spot - p.listener;
  SP_PRECISE float facing = -dot(ind.normal, to);
  c.candidate = 0u;
  c.distance = 0.0f;
  c.dir = vec3(0.0f, 0.0f, 1.0f);
  if ((p.cues & SP_CUES_LISTEN) == 0u || !(facing > 0.0f)) return c;  // most spots: no square root
  SP_PRECISE float len = sqrt(dot(to, to));
  SP_PRECISE float arriving = ind.heard - len * p.air_attenuation;
  if (!(len > 0.0f) || !(arriving > p.min_energy)) return c;
  c.distance = len;
  c.dir = vec3(to.x / len, to.y / len, to.z / len);
  c.candidate = 1u;
  return c;
}

// How nearly a spot's arrival points at its source as the listener sees
// it: 1 on the line from the listener to the source, falling linearly in
// the cosine to 0 at the lobe's half-angle (SimParams::toward_cos) and
// beyond. A source at the listener is toward everywhere.
SP_INLINE float sp_toward(vec3 arrival, vec3 source_position, SimParams p) {
  SP_PRECISE vec3 d = source_position - p.listener;
  SP_PRECISE float len = sqrt(dot(d, d));
  if (len <= 0.0f) return 1.0f;
  SP_PRECISE float c = (arrival.x * d.x + arrival.y * d.y + arrival.z * d.z) / len;
  if (p.toward_cos >= 1.0f) return c >= 1.0f ? 1.0f : 0.0f;
  SP_PRECISE float t = (c - p.toward_cos) / (1.0f - p.toward_cos);
  return min(max(t, 0.0f), 1.0f);
}

// Completes `ind` once its connection `c` was cast (`open`: nothing in the
// way) or skipped: the energy that arrives, or 0, and how nearly it points
// at `source`.
SP_INLINE void sp_finish_connection(SP_INOUT(Indicator) ind, Connection c, bool open, StepSource source, SimParams p) {
  if (c.candidate == 0u || !open) {
    ind.heard = 0.0f;
    ind.toward = 0.0f;
    return;
  }
  SP_PRECISE float arriving = ind.heard - c.distance * p.air_attenuation;
  ind.heard = arriving;
  ind.toward = sp_toward(ind.arrival, source.position, p);
}

// The energy heard relative to the source's loudness E0, from what the
// indicator keeps: size = indicator_size * E / E0, so E / E0 = size *
// inv_indicator_size, and heard / E0 = heard / E * E / E0. (An indicator's E
// exceeds tau_min >= 0, so it is never 0.)
SP_INLINE float sp_heard_relative(Indicator ind, float inv_indicator_size) {
  SP_PRECISE float relative = ind.size * inv_indicator_size;
  SP_PRECISE float heard = ind.heard / ind.energy * relative;
  return heard;
}

SP_END_NAMESPACE

#endif  // SP_CONNECT_H
