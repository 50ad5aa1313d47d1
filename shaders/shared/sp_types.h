// Struct layouts and limits shared by GLSL (std430) and C++.
// Every vec3 is paired with a 4-byte scalar so that std430 and C++ agree on
// offsets without padding rules; the C++ side checks this with static_asserts.
#ifndef SP_TYPES_H
#define SP_TYPES_H

#include "sp_lang.h"

// Deepest BVH the builder produces. Traversal keeps one stack entry per level,
// so a fixed stack of this size can never overflow.
#define SP_BVH_MAX_DEPTH 32
// Compute workgroup width: a multiple of every common subgroup size (32/64).
#define SP_WORKGROUP_SIZE 64
// Upper bound for max_bounces: the GPU records 2 * max_bounces + 2 wavefront
// iterations per step, so this bounds the command buffer size.
#define SP_MAX_BOUNCES_LIMIT 64
// Surface offset (metres) applied after reflections and exits, and the near
// limit of the backcast, so a ray never re-hits the face it just left.
#define SP_EPSILON 1.0e-4f
// "No hit" marker in HitInfo.triangle and BvhNode links.
#define SP_INVALID 0xFFFFFFFFu
// A distance larger than any scene; used instead of +inf, which GLSL lacks.
#define SP_FAR 1.0e30f

// Ray states (SPEC 1.3).
#define SP_RAY_DEAD 0u
#define SP_RAY_ACTIVE 1u
#define SP_RAY_RESOLVING 2u

// Indicator kinds (SPEC 1.4).
#define SP_INDICATOR_HIT 0u
#define SP_INDICATOR_EXIT 1u

// Outcome bits returned by the ray-model resolve functions; the caller turns
// them into per-layer statistics.
#define SP_OUTCOME_HIT 1u
#define SP_OUTCOME_INDICATOR 2u
#define SP_OUTCOME_REFLECT 4u
#define SP_OUTCOME_PENETRATE 8u
#define SP_OUTCOME_BACKCAST_MISS 16u

SP_BEGIN_NAMESPACE

// Flattened BVH node, 32 bytes. count == 0: interior node whose children are
// nodes[left_or_first] and nodes[left_or_first + 1] (always adjacent).
// count > 0: leaf holding triangles [left_or_first, left_or_first + count).
struct BvhNode {
  vec3 bmin;
  uint left_or_first;
  vec3 bmax;
  uint count;
};

// A triangle in BVH leaf order, 64 bytes. scene_index is its position in the
// scene's triangle soup (ties between equal hit distances go to the lowest).
// normal is the unit geometric normal of (v1 - v0) x (v2 - v0), precomputed on
// the CPU so both backends reflect about bit-identical normals.
struct BvhTriangle {
  vec3 v0;
  uint layer;
  vec3 v1;
  uint scene_index;
  vec3 v2;
  uint pad0;
  vec3 normal;
  uint pad1;
};

// Acoustic properties of one layer (paper: rho_ref, alpha_layer).
struct LayerAcoustics {
  float reflect_probability;  // probability of reflecting, in [0, 1]
  float attenuation;          // energy lost per metre inside the material
};

// Per-step parameters of the ray model.
struct SimParams {
  float min_energy;          // tau_min
  float air_attenuation;     // alpha_air, energy per metre
  float bounce_energy_loss;  // e_loss, fraction per reflection
  float max_wall_thickness;  // W_max, metres
  float indicator_size;      // metres at E == E0
  uint max_bounces;          // interactions after which a ray dies
  uint seed;
  uint step;
};

// A source as seen by one step (registry and distribution already done).
struct StepSource {
  vec3 position;
  float max_distance;  // D_max == R_max
  vec3 color;
  float loudness;      // E0
  float intensity;     // I = max(0, 1 - d_ls / R_max) at emission
  uint first_ray;      // this source's rays are [first_ray, first_ray + ray_count)
  uint ray_count;
  uint source_id;
};

// One ray's state between wavefront iterations, 80 bytes.
struct RayState {
  vec3 origin;        // where the next forward cast starts
  float energy;       // E
  vec3 dir;           // unit direction
  float travelled;    // path length so far, metres
  vec3 entry;         // p_in while ResolvingPenetration
  uint entry_layer;   // layer of the entry face while ResolvingPenetration
  uint state;         // SP_RAY_*
  uint bounces;       // reflections so far
  uint penetrations;  // completed penetrations so far
  uint ray_index;     // index among the step's emitted rays (RNG key)
  uint source;        // index into the step's StepSource table
  uint casts;         // casts made so far == wavefront iteration index
  float max_distance; // D_max of its source
  float loudness;     // E0 of its source
};

// One indicator, 80 bytes. iteration and ray_index give the canonical order
// (step, iteration, ray_index) in which both backends list indicators.
struct Indicator {
  vec3 position;
  float energy;
  vec3 normal;  // facing the side the ray came from (hit) or leaves to (exit)
  float size;   // indicator_size * E / E0
  vec3 color;
  float intensity;
  uint kind;    // SP_INDICATOR_*
  uint source_id;
  uint bounces;
  uint penetrations;
  float path_length;
  uint step;
  uint ray_index;
  uint iteration;
};

// Closest-hit query result; triangle is a leaf-order index or SP_INVALID.
struct HitInfo {
  float t;
  uint triangle;
};

SP_END_NAMESPACE

#endif  // SP_TYPES_H
