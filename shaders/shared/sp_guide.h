// Rays guided to the player (docs/model.md#cues-for-the-player), shared by
// GLSL and C++. Each source keeps a guide: a histogram over emission
// directions of what its rays' heard spots were worth, decayed every step.
// A share of its rays (SimParams::guide_share) is drawn from that histogram,
// the rest uniformly over the sphere, so a source keeps exploring when the
// player moves. A guided ray carries the same energy as any other: the
// guide chooses which paths are traced, not what they carry.
//
// Directions are binned on the faces of a cube (SP_GUIDE_FACE_CELLS^2 cells
// a face): a cell and a direction inside it need only comparisons,
// divisions and a square root, which round alike on both backends (no
// trigonometry), so both draw the same guided rays bit for bit.
//
// Buffers: C++ passes `uint* guide` through SP_GUIDE_ARGS_DECL; GLSL
// declares a storage buffer of that name before including this file. Each
// source id owns SP_GUIDE_STRIDE words from guide_base(id): the decayed
// weights, their running sums (what a draw searches), and this step's
// pending weights, which the connect pass adds to and the next step's fold
// takes in.
#ifndef SP_GUIDE_H
#define SP_GUIDE_H

#include "sp_random.h"
#include "sp_types.h"

#define SP_GUIDE_FACE_CELLS 4u
#define SP_GUIDE_CELLS (6u * SP_GUIDE_FACE_CELLS * SP_GUIDE_FACE_CELLS)
#define SP_GUIDE_WEIGHTS 0u
#define SP_GUIDE_SUMS SP_GUIDE_CELLS
#define SP_GUIDE_PENDING (2u * SP_GUIDE_CELLS)
#define SP_GUIDE_STRIDE (3u * SP_GUIDE_CELLS)
// Each step keeps weight - weight / 2^SHIFT: a half-life of about 11 steps
// (0.18 s at 60 Hz), long enough to hold what a few steps found, short
// enough to follow a player who walks into another room.
#define SP_GUIDE_DECAY_SHIFT 4u
// A cell's weight never exceeds this, so the running sums of all cells
// stay below 2^32.
#define SP_GUIDE_WEIGHT_MAX 0x01000000u
// What one heard spot adds to its emission cell, at most.
#define SP_GUIDE_SPOT_WEIGHT 256.0f
// Counter of the guided draw in a ray's random stream (sp_random.h).
#define SP_GUIDE_COUNTER 0x7FFFFFFFu

#ifdef __cplusplus
#define SP_GUIDE_ARGS_DECL const uint *guide,
#define SP_GUIDE_ARGS_DECL_MUT uint *guide,
#define SP_GUIDE_ARGS guide,
#else
#define SP_GUIDE_ARGS_DECL
#define SP_GUIDE_ARGS_DECL_MUT
#define SP_GUIDE_ARGS
#endif

SP_BEGIN_NAMESPACE

SP_INLINE uint sp_guide_base(uint source_id) { return source_id * SP_GUIDE_STRIDE; }

// The face axis of `dir` (0, 1, 2: x, y, z; the first of equal ones) and the
// two coordinates on that face, each in [-1, 1].
SP_INLINE uint sp_guide_axis(vec3 dir) {
  vec3 a = abs(dir);
  if (a.x >= a.y && a.x >= a.z) return 0u;
  return a.y >= a.z ? 1u : 2u;
}

SP_INLINE uint sp_guide_face_coordinate(float s) {
  SP_PRECISE float scaled = (s + 1.0f) * (0.5f * float(SP_GUIDE_FACE_CELLS));
  return min(uint(max(scaled, 0.0f)), SP_GUIDE_FACE_CELLS - 1u);
}

// The guide cell of a direction (need not be of unit length, not zero).
SP_INLINE uint sp_guide_cell(vec3 dir) {
  uint axis = sp_guide_axis(dir);
  float major = axis == 0u ? dir.x : (axis == 1u ? dir.y : dir.z);
  float s = axis == 0u ? dir.y : dir.x;
  float t = axis == 2u ? dir.y : dir.z;
  SP_PRECISE float inv = 1.0f / abs(major);
  uint face = axis * 2u + (major < 0.0f ? 1u : 0u);
  uint u = sp_guide_face_coordinate(s * inv);
  uint v = sp_guide_face_coordinate(t * inv);
  return (face * SP_GUIDE_FACE_CELLS + v) * SP_GUIDE_FACE_CELLS + u;
}

// A unit direction inside `cell`, at fractions (fu, fv) in [0, 1) across it.
SP_INLINE vec3 sp_guide_cell_direction(uint cell, float fu, float fv) {
  uint u = cell % SP_GUIDE_FACE_CELLS;
  uint v = (cell / SP_GUIDE_FACE_CELLS) % SP_GUIDE_FACE_CELLS;
  uint face = cell / (SP_GUIDE_FACE_CELLS * SP_GUIDE_FACE_CELLS);
  SP_PRECISE float width = 2.0f / float(SP_GUIDE_FACE_CELLS);
  SP_PRECISE float s = (float(u) + fu) * width - 1.0f;
  SP_PRECISE float t = (float(v) + fv) * width - 1.0f;
  float major = (face & 1u) != 0u ? -1.0f : 1.0f;
  uint axis = face / 2u;
  vec3 d = axis == 0u ? vec3(major, s, t) : (axis == 1u ? vec3(s, major, t) : vec3(s, t, major));
  SP_PRECISE float len = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return vec3(d.x / len, d.y / len, d.z / len);
}

// Folds a step's pending weights into source `base`'s guide: weights decay,
// pending ones are added, their running sums rebuilt, pending cleared.
SP_INLINE void sp_guide_fold(SP_GUIDE_ARGS_DECL_MUT uint base) {
  uint sum = 0u;
  for (uint c = 0u; c < SP_GUIDE_CELLS; ++c) {
    uint w = guide[base + SP_GUIDE_WEIGHTS + c];
    w = w - (w >> SP_GUIDE_DECAY_SHIFT);
    w = min(w + min(guide[base + SP_GUIDE_PENDING + c], SP_GUIDE_WEIGHT_MAX), SP_GUIDE_WEIGHT_MAX);
    guide[base + SP_GUIDE_WEIGHTS + c] = w;
    guide[base + SP_GUIDE_PENDING + c] = 0u;
    sum += w;
    guide[base + SP_GUIDE_SUMS + c] = sum;
  }
}

SP_INLINE uint sp_guide_total(SP_GUIDE_ARGS_DECL uint base) {
  return guide[base + SP_GUIDE_SUMS + SP_GUIDE_CELLS - 1u];
}

// The cell whose running-sum interval holds `pick` (< total).
SP_INLINE uint sp_guide_pick(SP_GUIDE_ARGS_DECL uint base, uint pick) {
  uint lo = 0u;
  uint hi = SP_GUIDE_CELLS - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (guide[base + SP_GUIDE_SUMS + mid] > pick) hi = mid;
    else lo = mid + 1u;
  }
  return lo;
}

// How many of a source's `ray_count` rays follow its guide this step.
SP_INLINE uint sp_guided_rays(uint ray_count, float guide_share) {
  SP_PRECISE float guided = float(ray_count) * guide_share;
  return min(uint(guided), ray_count);
}

// The emission direction of ray `ray_index` (its source's rays are
// [first_ray, first_ray + ray_count)) and its guide cell: the first
// sp_guided_rays of the source from its guide when guiding is on and the
// guide holds anything, the rest uniform on the sphere.
SP_INLINE vec3 sp_source_emission(SP_GUIDE_ARGS_DECL StepSource source, uint ray_index, SimParams p,
                                  SP_OUT(uint) cell) {
  if ((p.cues & SP_CUES_GUIDE) != 0u &&
      ray_index - source.first_ray < sp_guided_rays(source.ray_count, p.guide_share)) {
    uint base = sp_guide_base(source.source_id);
    uint total = sp_guide_total(SP_GUIDE_ARGS base);
    if (total > 0u) {
      uvec4 r = sp_pcg4d(p.seed, p.step, ray_index, SP_GUIDE_COUNTER);
      cell = sp_guide_pick(SP_GUIDE_ARGS base, r.x % total);
      return sp_guide_cell_direction(cell, sp_unit_float(r.y), sp_unit_float(r.z));
    }
  }
  vec3 dir = sp_emission_direction(p.seed, p.step, ray_index);
  cell = sp_guide_cell(dir);
  return dir;
}

// What a heard spot adds to its ray's emission cell: its worth to the
// player, the energy that arrives relative to the source's loudness, more
// when it lies toward its source (Indicator::toward). At least 1, so that
// every path the player hears is remembered.
SP_INLINE uint sp_guide_spot_weight(float heard_relative, float toward) {
  SP_PRECISE float worth = min(max(heard_relative, 0.0f), 1.0f) * (0.25f + 0.75f * toward);
  return 1u + uint(worth * SP_GUIDE_SPOT_WEIGHT);
}

SP_END_NAMESPACE

#endif  // SP_GUIDE_H
