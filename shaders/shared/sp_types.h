// Struct layouts and limits shared by GLSL (std430) and C++.
// Every vec3 is paired with a 4-byte scalar so that std430 and C++ agree on
// offsets without padding rules; the C++ side checks this with static_asserts.
#ifndef SP_TYPES_H
#define SP_TYPES_H

#include "sp_lang.h"

// Deepest BVH the builder produces. Traversal keeps one stack entry per level,
// so a fixed stack of this size can never overflow.
#define SP_BVH_MAX_DEPTH 32
// Compute workgroup width on a GPU: a multiple of every common subgroup
// size (32/64). The simulation's kernels take their width as the
// specialization constant SP_SPEC_WORKGROUP_SIZE, and read it as
// SP_SPEC_GROUP_WIDTH (gpu::kernel_workgroup_size: a CPU device gets its
// subgroup width instead).
#define SP_WORKGROUP_SIZE 64
#define SP_SPEC_WORKGROUP_SIZE 0
#define SP_SPEC_GROUP_WIDTH 1  // the same width, as the kernels' code reads it
// The most spots a step may have for the connect pass to admit them itself
// (shaders/admission_passes.glsl; gpu::inline_admission_max).
#define SP_SPEC_ADMIT_INLINE_MAX 2
// Whether the walks read the tree from its uniform texel buffers (1) or
// its storage buffers (0): gpu::bvh_texels_usable.
#define SP_SPEC_BVH_TEXELS 3
// The most workgroups the connect pass runs, its subgroups then taking a
// spot a lane in turn until none is left (gpu::connect_groups_max).
#define SP_SPEC_CONNECT_GROUPS_MAX 4
// Whether resolve's rays may diffract (the config's diffraction.enabled):
// lavapipe runs every branch, so the code a config leaves off costs unless
// it is compiled out (GpuResources::resolve_diffracts).
#define SP_SPEC_DIFFRACTION 5
// Surface offset (metres) applied after reflections and exits, so a ray
// never re-hits the face it just left.
#define SP_EPSILON 1.0e-4f
// Faces closer than this along a ray (metres) are crossed together: where two
// solids touch, the leaving face of one and the entering face of the next
// lie at the same distance up to rounding, and that plane must never be taken
// for a way out of matter (docs/model.md#the-rules). 1 mm is far above the
// rounding of hit distances in a level a few hundred metres across and far
// below any gap that matters to sound.
#define SP_CONTACT_TOLERANCE 1.0e-3f
// Faces one matter query lists (the nearest ones within W_max of p_in; the
// two triangles of one surface met through their shared edge count once).
// Touching and overlapping solids put a handful of faces within W_max; a
// query that finds more and no way out among the listed ones counts as no
// way out (the ray is absorbed), which bounds the work per penetration. Kept small because
// a GPU holds the list per thread.
#define SP_MATTER_MAX_HITS 8
// Solids whose layers a penetrating ray remembers at once (overlapping
// solids lose at the largest attenuation among them). Deeper nesting is
// still counted; a fifth solid's layer is not remembered.
#define SP_MATTER_STACK 4
// The work one cast may do (docs/model.md#work-bounds), in triangles tested
// four at a time: each leaf the walk enters costs ceil(count / 4), the
// packets of the CPU's wide walk. A level's BVH separates its triangles, so
// a cast enters a handful of leaves: at most 14 on the shared OpenArena maps
// and the bundled level over 400,000 random rays, 1 in the median.
// Coincident or overlapping triangles (a quad repeated 100,000 times, long
// slivers whose boxes all overlap) defeat any tree, and a cast there would
// test every triangle: a stranger's 2 MB level stalls the game. A walk that
// would exceed this ends: the ray dies as on a miss, counted in the stats
// (casts_cut_short). Every walk, binary or wide, enters the same leaves in
// the same order (src/bvh/wide_bvh.h), so every backend cuts the same casts
// at the same leaf. About 1,000 triangle tests, a few microseconds.
#define SP_MAX_CAST_PACKETS 256u
// The packets of four triangles a leaf of `count` triangles costs.
#define SP_LEAF_PACKETS(count) (((count) + 3u) / 4u)
// "No hit" marker in HitInfo.triangle and BvhNode links.
#define SP_INVALID 0xFFFFFFFFu
// A distance larger than any scene; used instead of +inf, which GLSL lacks.
#define SP_FAR 1.0e30f

// Ray states (docs/model.md#propagation).
#define SP_RAY_DEAD 0u
#define SP_RAY_ACTIVE 1u
#define SP_RAY_RESOLVING 2u

// Indicator kinds (docs/model.md#indicators).
#define SP_INDICATOR_HIT 0u
#define SP_INDICATOR_EXIT 1u

// How a ray crosses a face (HitList::key's low two bits): its front faces
// the ray (entering), faces away (leaving), or the ray runs in its plane.
#define SP_CROSSING_NONE 0u
#define SP_CROSSING_ENTER 1u
#define SP_CROSSING_LEAVE 2u

// Outcome bits returned by the ray-model resolve functions; the caller turns
// them into per-layer statistics.
#define SP_OUTCOME_HIT 1u
#define SP_OUTCOME_INDICATOR 2u
#define SP_OUTCOME_REFLECT 4u
#define SP_OUTCOME_PENETRATE 8u
#define SP_OUTCOME_NO_WAY_OUT 16u
// An Active ray struck the back of a face: it was inside matter (a leak, or
// winding that disagrees with the geometry) and is absorbed.
#define SP_OUTCOME_BACK_FACE 32u
// A sheet was crossed on the spot: a second indicator (the exit) was written.
#define SP_OUTCOME_SHEET_EXIT 64u
// The ray turned round an exposed edge of the face it struck
// (docs/model.md#diffraction) instead of reflecting or penetrating.
#define SP_OUTCOME_DIFFRACT 128u
// The cast reached SP_MAX_CAST_PACKETS and ended: the ray died.
#define SP_OUTCOME_CUT_SHORT 256u

// SimParams::cues (docs/model.md#cues-for-the-player).
#define SP_CUES_LISTEN 1u  // every spot's way to the listener is cast: `heard`, `arrival`, `toward`
#define SP_CUES_GUIDE 2u   // a share of each source's rays follows its guide (sp_guide.h)

// CastResult::flags.
#define SP_CAST_CUT_SHORT 1u

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
SP_CHECK_LAYOUT(sizeof(BvhNode) == 32 && offsetof(BvhNode, left_or_first) == 12 && offsetof(BvhNode, bmax) == 16 && offsetof(BvhNode, count) == 28 && alignof(BvhNode) == 4);

// A triangle in BVH leaf order, 64 bytes. scene_index is its position in the
// scene's triangle soup (ties between equal hit distances go to the lowest).
// normal is the unit geometric normal of (v1 - v0) x (v2 - v0), precomputed on
// the CPU so both backends reflect about bit-identical normals; it points out
// of the triangle's solid (counter-clockwise winding is the front, as in glTF).
// solid numbers the connected piece of surface the triangle belongs to
// (src/bvh/mesh_topology.h): faces of one solid met at one distance are the
// same crossing, seen through an edge they share.
struct BvhTriangle {
  vec3 v0;
  uint layer;
  vec3 v1;
  uint scene_index;
  vec3 v2;
  uint solid;
  vec3 normal;
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(BvhTriangle) == 64 && offsetof(BvhTriangle, layer) == 12 && offsetof(BvhTriangle, v1) == 16 && offsetof(BvhTriangle, scene_index) == 28 && offsetof(BvhTriangle, v2) == 32 && offsetof(BvhTriangle, solid) == 44 && offsetof(BvhTriangle, normal) == 48);

// Acoustic properties of one layer (docs/model.md's symbols: rho_ref,
// alpha_layer).
struct LayerAcoustics {
  float reflect_probability;  // probability of reflecting, in [0, 1]
  float attenuation;          // energy lost per metre inside the material
  float sheet_thickness;      // > 0: the layer's faces are sheets this thick (metres); 0: faces of solids
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(LayerAcoustics) == 16 && offsetof(LayerAcoustics, sheet_thickness) == 8);

// Per-step parameters of the ray model.
struct SimParams {
  float min_energy;          // tau_min
  float air_attenuation;     // alpha_air, energy per metre
  float bounce_energy_loss;  // e_loss, fraction per reflection
  float max_wall_thickness;  // W_max, metres
  float indicator_size;      // metres at E == E0
  uint max_bounces;          // interactions (bounces + penetrations + diffractions) after which a ray dies
  uint seed;
  uint step;
  // Diffraction (docs/model.md#diffraction); diffraction == 0 leaves the
  // model exactly as without it.
  uint diffraction;         // 1: rays may turn at exposed edges
  float edge_cos_max;       // an exposed edge diffracts when cos(turn angle) <= this
  float diffraction_reach;  // metres from an edge within which a struck ray may turn
  float diffraction_width;  // 1 / (2k): the deflection width sigma(a) = min(pi/2, width / a)
  float diffraction_gain;   // fraction of its energy a diffracted ray keeps, in [0, 1]
  // Cues for the player (docs/model.md#cues-for-the-player).
  uint cues;          // SP_CUES_*
  float toward_cos;   // cos of the toward lobe's half-angle (cues.toward_angle)
  float guide_share;  // share of each source's rays drawn from its guide, in [0, 1]
  vec3 listener;      // where the player hears (and, first person, sees) from
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(SimParams) == 80 && offsetof(SimParams, diffraction) == 32 && offsetof(SimParams, diffraction_gain) == 48 && offsetof(SimParams, cues) == 52 && offsetof(SimParams, listener) == 64);

// The edges of one triangle that sound can bend round, in leaf order like
// BvhTriangle (src/bvh/diffraction_edges.h). Edge i runs from vertex i to
// vertex (i + 1) % 3. For an exposed edge, the surface turns there by the
// angle phi between this face's normal n and the far face's: the far face's
// normal is turn_cos[i] * n + turn_sin[i] * o, o being the unit vector in
// this face's plane, across the edge, pointing out of the triangle. A free
// boundary has phi = 180 degrees (turn_cos -1, turn_sin 0).
struct TriangleEdges {
  vec3 turn_cos;
  uint exposed;  // bit i: edge i is a free boundary or a convex edge that no other solid buries
  vec3 turn_sin;
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(TriangleEdges) == 32 && offsetof(TriangleEdges, exposed) == 12 && offsetof(TriangleEdges, turn_sin) == 16);

// A source as seen by one step (registry and distribution already done).
struct StepSource {
  vec3 position;
  float max_distance;  // D_max == R_max
  vec3 color;
  float loudness;   // E0
  float intensity;  // I = max(0, 1 - d_ls / R_max) at emission
  uint first_ray;   // this source's rays are [first_ray, first_ray + ray_count)
  uint ray_count;
  uint source_id;
};
SP_CHECK_LAYOUT(sizeof(StepSource) == 48 && offsetof(StepSource, color) == 16 && offsetof(StepSource, intensity) == 32 && offsetof(StepSource, source_id) == 44);

// One ray's state between wavefront iterations, 96 bytes.
struct RayState {
  vec3 origin;          // where the next forward cast starts
  float energy;         // E
  vec3 dir;             // unit direction
  float travelled;      // path length so far, metres
  vec3 entry;           // p_in while ResolvingPenetration
  uint entry_layer;     // layer of the entry face while ResolvingPenetration
  uint state;           // SP_RAY_*
  uint bounces;         // reflections so far
  uint penetrations;    // completed penetrations so far
  uint ray_index;       // index among the step's emitted rays (RNG key)
  uint source;          // index into the step's StepSource table
  uint casts;           // casts made so far == wavefront iteration index
  float max_distance;   // D_max of its source
  float loudness;       // E0 of its source
  uint entry_triangle;  // leaf-order index of the entry face while ResolvingPenetration
  uint diffractions;    // times the ray turned at an edge (docs/model.md#diffraction)
  uint emit_cell;       // the guide cell of its emission direction (sp_guide.h)
  uint pad1;
};
SP_CHECK_LAYOUT(sizeof(RayState) == 96 && offsetof(RayState, dir) == 16 && offsetof(RayState, entry) == 32 && offsetof(RayState, entry_layer) == 44 && offsetof(RayState, state) == 48 && offsetof(RayState, loudness) == 76 && offsetof(RayState, entry_triangle) == 80);

// One indicator, 96 bytes. iteration and ray_index give the canonical order
// (step, iteration, ray_index, kind) in which both backends list them.
struct Indicator {
  vec3 position;
  float energy;
  vec3 normal;  // facing the side the ray came from (hit) or leaves to (exit)
  float size;   // indicator_size * E / E0
  vec3 color;
  float intensity;
  vec3 dir;  // the ray's direction of travel: incoming (hit), outgoing (exit)
  float path_length;
  uint kind;  // SP_INDICATOR_*
  uint source_id;
  uint bounces;
  uint penetrations;
  uint diffractions;
  uint step;
  uint ray_index;
  uint iteration;
  // What reaches the player (docs/model.md#cues-for-the-player): the unit
  // direction from the listener to the spot, the way its sound arrives, and
  // the energy that arrives there along it (0: the listener does not hear
  // this spot: its surface faces away, the way is blocked, or too little is
  // left). While a step runs, `heard` holds the energy the spot sends
  // towards the listener before the way there is cast.
  vec3 arrival;
  float heard;
  uint emit_cell;    // the guide cell the ray was emitted into (sp_guide.h)
  uint source_slot;  // the source's entry in its step's source table
  float toward;      // in [0, 1]: how nearly `arrival` points at the source (1: on the line), 0 when not heard
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(Indicator) == 128 && offsetof(Indicator, normal) == 16 && offsetof(Indicator, color) == 32 && offsetof(Indicator, dir) == 48 && offsetof(Indicator, path_length) == 60 && offsetof(Indicator, kind) == 64 && offsetof(Indicator, iteration) == 92 && offsetof(Indicator, arrival) == 96 && offsetof(Indicator, heard) == 108 && offsetof(Indicator, emit_cell) == 112 && offsetof(Indicator, toward) == 120 && alignof(Indicator) == 4);

// Closest-hit query result; triangle is a leaf-order index or SP_INVALID.
// cut_short: 1 when the walk ended at SP_MAX_CAST_PACKETS (triangle is then
// SP_INVALID: the cast found nothing it may use).
struct HitInfo {
  float t;
  uint triangle;
  uint cut_short;
};
SP_CHECK_LAYOUT(sizeof(HitInfo) == 12);

// What one cast found, 16 bytes. Active ray: the closest hit (matter_loss 0).
// ResolvingPenetration ray: the exit face and its distance t from p_in, and
// the energy the stretches of matter before it take (sum of length *
// alpha_layer); triangle SP_INVALID when there is no way out within W_max.
struct CastResult {
  float t;
  uint triangle;
  float matter_loss;
  uint flags;  // SP_CAST_*
};
SP_CHECK_LAYOUT(sizeof(CastResult) == 16 && offsetof(CastResult, matter_loss) == 8);

// The nearest faces along a segment, sorted by (t, leaf order): what a
// matter query sees. count == SP_MATTER_MAX_HITS means there may be more
// beyond t[SP_MATTER_MAX_HITS - 1]. key = solid * 4 + crossing code
// (SP_CROSSING_*), so that the two triangles of one surface met through
// their shared edge, alike in both, take one entry. cut_short: 1 when the
// walk ended at SP_MAX_CAST_PACKETS; the list is then not to be used.
struct HitList {
  float t[SP_MATTER_MAX_HITS];
  uint triangle[SP_MATTER_MAX_HITS];
  uint key[SP_MATTER_MAX_HITS];
  uint count;
  uint cut_short;
};
SP_CHECK_LAYOUT(sizeof(HitList) == 4 * (3 * SP_MATTER_MAX_HITS + 2));

SP_END_NAMESPACE

#endif  // SP_TYPES_H
