// Closest-hit queries on the CPU. The BVH path runs the 4-wide traversal of
// wide_bvh.cpp, or without a wide tree the one shared with the GPU
// (shaders/shared/sp_traverse.h); the brute-force path is the reference the
// tests compare them against.
#include <glm/glm.hpp>

#include "bvh/wide_bvh.h"
#include "bvh/bvh.h"
#include "sp_traverse.h"

namespace sp {

HitInfo closest_hit(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
  // The shared traversal reads nodes[0] unconditionally.
  if (bvh.nodes.empty()) return HitInfo{tmax, SP_INVALID, 0u};
  if (bvh.wide) return wide_closest_hit(*bvh.wide, bvh, origin, dir, tmin, tmax);
  return shader::sp_closest_hit(bvh.nodes.data(), bvh.triangles.data(), origin, dir, tmin, tmax);
}

shader::HitList nearest_hits(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
  shader::HitList list{};
  if (bvh.nodes.empty()) return list;
  if (bvh.wide) return wide_nearest_hits(*bvh.wide, bvh, origin, dir, tmin, tmax);
  shader::sp_nearest_hits(bvh.nodes.data(), bvh.triangles.data(), origin, dir, tmin, tmax, list);
  return list;
}

bool segment_blocked(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
  if (bvh.nodes.empty()) return false;
  if (bvh.wide) return wide_segment_blocked(*bvh.wide, origin, dir, tmin, tmax);
  return shader::sp_segment_blocked(bvh.nodes.data(), bvh.triangles.data(), origin, dir, tmin, tmax);
}

HitInfo closest_hit_brute_force(const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
  const shader::RayQuery q = shader::sp_make_query(origin, dir, tmin, tmax);
  // Same start state and acceptance rule as sp_closest_hit, so that only the
  // pruning differs between the two; except that a miss (SP_FAR) is never a
  // hit, even when tmax == SP_FAR.
  HitInfo best{tmax, SP_INVALID, 0u};
  std::uint32_t best_scene = SP_INVALID;
  for (std::size_t i = 0; i < bvh.triangles.size(); ++i) {
    const BvhTriangle& tri = bvh.triangles[i];
    float t = shader::sp_intersect_triangle(q, tri.v0, tri.v1, tri.v2);
    if (t < SP_FAR && t > q.tmin && t <= q.tmax && shader::sp_better_hit(t, tri.scene_index, best.t, best_scene)) {
      best.t = t;
      best.triangle = static_cast<std::uint32_t>(i);
      best_scene = tri.scene_index;
    }
  }
  return best;
}

}  // namespace sp
