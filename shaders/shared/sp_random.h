// Counter-based random numbers, identical in GLSL and C++: a pure function of
// (seed, step, ray index, counter), so results never depend on thread count,
// dispatch order or backend.
//
// Hash: pcg4d from Jarzynski & Olano, "Hash Functions for GPU Rendering",
// JCGT 9(3), 2020. Integer-only, so both languages agree bit for bit.
//
// Counter space of one ray:
//   | counter               | use                                      |
//   |-----------------------|------------------------------------------|
//   | 0 .. max_bounces      | interaction `counter` = interactions so  |
//   |                       | far (bounces + penetrations +            |
//   |                       | diffractions): .x reflect/penetrate,     |
//   |                       | .y turn at an edge, .z its angle         |
//   | 0x80000000 + try      | emission direction, rejection try `try`  |
#ifndef SP_RANDOM_H
#define SP_RANDOM_H

#include "sp_types.h"

// Rejection sampling of the unit ball accepts with probability pi/6 ~ 0.52;
// after 64 tries the chance of no acceptance is ~1e-20.
#define SP_DIRECTION_TRIES 64u
#define SP_DIRECTION_COUNTER_BASE 0x80000000u

SP_BEGIN_NAMESPACE

SP_INLINE uvec4 sp_pcg4d(uint a, uint b, uint c, uint d) {
  uint x = a * 1664525u + 1013904223u;
  uint y = b * 1664525u + 1013904223u;
  uint z = c * 1664525u + 1013904223u;
  uint w = d * 1664525u + 1013904223u;
  x += y * w;
  y += z * x;
  z += x * y;
  w += y * z;
  x ^= x >> 16u;
  y ^= y >> 16u;
  z ^= z >> 16u;
  w ^= w >> 16u;
  x += y * w;
  y += z * x;
  z += x * y;
  w += y * z;
  return uvec4(x, y, z, w);
}

// Maps 32 random bits to [0, 1) exactly (24-bit mantissa, no rounding).
SP_INLINE float sp_unit_float(uint bits) { return float(bits >> 8u) * (1.0f / 16777216.0f); }

// The decision variable u (docs/model.md#propagation) for a ray's interaction
// `interaction`.
SP_INLINE float sp_decision_random(uint seed, uint step, uint ray_index, uint interaction) {
  return sp_unit_float(sp_pcg4d(seed, step, ray_index, interaction).x);
}

// Uniform direction on the unit sphere by rejection from the cube [-1,1)^3.
// Uses only +, *, / and sqrt (no trig), which are correctly rounded on both
// backends, so the GPU and CPU draw bit-identical directions.
SP_INLINE vec3 sp_emission_direction(uint seed, uint step, uint ray_index) {
  for (uint i = 0u; i < SP_DIRECTION_TRIES; ++i) {
    uvec4 r = sp_pcg4d(seed, step, ray_index, SP_DIRECTION_COUNTER_BASE + i);
    SP_PRECISE float x = sp_unit_float(r.x) * 2.0f - 1.0f;
    SP_PRECISE float y = sp_unit_float(r.y) * 2.0f - 1.0f;
    SP_PRECISE float z = sp_unit_float(r.z) * 2.0f - 1.0f;
    SP_PRECISE float len2 = x * x + y * y + z * z;
    if (len2 > 1.0e-6f && len2 <= 1.0f) {
      SP_PRECISE float len = sqrt(len2);
      return vec3(x / len, y / len, z / len);
    }
  }
  return vec3(0.0f, 0.0f, 1.0f);
}

SP_END_NAMESPACE

#endif  // SP_RANDOM_H
