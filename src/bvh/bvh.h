// Bounding volume hierarchy over a triangle soup: binned SAH build, flattened
// into the std430 layout of shaders/shared/sp_types.h that the GPU traverses
// unchanged, plus a CPU-only 4-wide copy that closest_hit traverses.
// Internal: a World keeps its Bvh in its opaque geometry (src/sim/world_geometry.h).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "bvh/large_array.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"

namespace sp {

using BvhNode = shader::BvhNode;
using BvhTriangle = shader::BvhTriangle;
using HitInfo = shader::HitInfo;

// BvhBuildSettings is public (soundpaint/simulation.h: make_world takes it).
static_assert(BvhBuildSettings{}.max_depth == SP_BVH_MAX_DEPTH);

// The CPU's 4-wide tree (src/bvh/wide_bvh.h); opaque outside the bvh module.
struct WideBvh;

struct Bvh {
  LargeArray<BvhNode> nodes;          // nodes[0] is the root; siblings adjacent
  LargeArray<BvhTriangle> triangles;  // in leaf order; scene_index maps back
  std::uint32_t depth = 0;            // levels, root included
  double build_ms = 0.0;              // wall time of build_bvh, the wide tree included
  // `nodes` collapsed into 4-wide SIMD nodes, with the triangles copied into
  // 4-triangle packets, for closest_hit on the CPU; built by build_bvh.
  // Immutable, so copies of a Bvh share it. Null (a tree made by hand) makes
  // closest_hit walk `nodes` as the GPU does; code that edits nodes or
  // triangles must reset it.
  std::shared_ptr<const WideBvh> wide;
  // Per triangle in leaf order: the edges sound bends round
  // (docs/model.md#diffraction). Empty unless diffraction is on: make_world
  // fills it then, and refit_bvh keeps it current.
  std::vector<shader::TriangleEdges> edges;

  std::size_t triangle_count() const { return triangles.size(); }
};

// Builds the BVH. `vertices` holds 3 per triangle; `layers` one per triangle;
// `solids` one per triangle, the piece of surface it belongs to, which the
// matter rules need (make_world computes it); without it (empty) every
// triangle is a piece alone, enough for queries that are not simulations.
// Degenerate (zero-area) triangles are kept (they never report hits).
// Cannot fail (but for std::bad_alloc): no triangles give an empty tree;
// with fewer layers than triangles only the first layers.size() triangles
// are built, and an empty `solids` is allowed; coordinates should be finite
// (load_scene checks), a non-finite one only makes its triangle unhittable.
Bvh build_bvh(std::span<const glm::vec3> vertices, std::span<const std::uint32_t> layers,
              std::span<const std::uint32_t> solids = {}, const BvhBuildSettings& settings = {});

// BVHs built in this process so far (rebuilds of moving parts included):
// what tests count to show that settings, backends and probes share one.
std::uint64_t bvh_builds();

// The queries below cannot fail: a ray that meets nothing (or an empty
// tree) reports SP_INVALID.
// Closest hit with distance in (tmin, tmax] along unit direction `dir`.
// Triangles are two-sided; ties go to the lowest scene index. Traverses
// `wide` when there is one, else `nodes`; either way the answer is the
// shared sp_closest_hit's (shaders/shared/sp_traverse.h), t bit for bit.
HitInfo closest_hit(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

// Whether a triangle lies at a distance in (tmin, tmax] along `dir`, or the
// walk ran out of work (SP_MAX_CAST_PACKETS): the shared sp_segment_blocked
// (shaders/shared/sp_traverse.h), the GPU's walk, which stops at the first
// triangle it meets. Traverses `wide` when there is one, with the same
// answer.
bool segment_blocked(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

// The nearest SP_MATTER_MAX_HITS hits with distance in (tmin, tmax], sorted
// by (t, leaf order): the matter query of a penetrating ray. The answer of
// the shared sp_nearest_hits (shaders/shared/sp_traverse.h), bit for bit.
shader::HitList nearest_hits(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

// The same query as closest_hit by testing every triangle; for tests and
// validation.
HitInfo closest_hit_brute_force(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

// Leaf-order entries whose contents changed, as sorted, disjoint, half-open
// index ranges [first, last); lets a GPU copy upload only what moved.
struct BvhIndexRange {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
};
struct BvhChanges {
  std::vector<BvhIndexRange> nodes;      // into Bvh::nodes
  std::vector<BvhIndexRange> triangles;  // into Bvh::triangles
  std::vector<BvhIndexRange> edges;      // into Bvh::edges (only while it is filled)
};

// Moves the triangles to `vertices` (3 per triangle, in scene order, i.e.
// indexed by BvhTriangle::scene_index, same count as at build) keeping the
// tree's topology, so that a moving mesh (an opening door) costs one linear
// pass instead of a rebuild: recomputes each triangle's corners and normal
// exactly as build_bvh does, then every node's bounds bottom-up (exact
// unions, as build_bvh makes them: no padding), then the wide copy, freshly
// allocated when there was one (copies of the Bvh keep the old one) and left
// null when there was none. Layers are kept. Exposed edges are found again
// when `edges` is filled.
// Returns what changed, by bitwise comparison of old and new entries; ranges
// at most 16 unchanged entries apart are merged into one. A bound equal as a
// float to the old one (+0 and -0) keeps its old bits, so unchanged vertices
// report no change whatever order build_bvh scanned them in.
// ErrorCode::InvalidArgument, leaving `bvh` untouched, when vertices.size()
// != 3 * triangle_count(), a vertex is not finite, or the tree is not shaped
// as build_bvh makes it (children after their parent, ranges inside the
// arrays, scene indices below triangle_count()).
Result<BvhChanges> refit_bvh(Bvh& bvh, std::span<const glm::vec3> vertices);

// Cannot fail. Surface-area-heuristic cost of the tree relative to its root box: sum over
// inner nodes of area(node) / area(root) * traversal_cost, plus sum over
// leaves of area(leaf) / area(root) * count. Refitting after large motions
// raises it; callers rebuild when it has grown too much. Being relative to
// the root, it compares trees over about the same root box: a motion that
// mostly grows the root (a mesh leaving the scene) can lower it. When the
// root's area is 0 (every triangle on one line or point), so is every
// node's, and each 0/0 counts as 1: the cost of visiting every node. 0 for
// an empty tree. By default priced as build_bvh builds, so that a refit tree
// compares with its build.
double bvh_sah_cost(const Bvh& bvh, float traversal_cost = BvhBuildSettings{}.traversal_cost);

}  // namespace sp
