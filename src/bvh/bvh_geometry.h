// Boxes in 4-wide vectors and per-triangle preparation for the BVH builder.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bvh/bvh.h"
#include "bvh/simd4.h"

namespace sp {

// One SSE/NEON register per box corner (simd4.h: Vec4, vmin = a < b ? a : b,
// vmax = a > b ? a : b). Lane 3 is always 0.
inline Vec4 to_vec4(glm::vec3 v) { return Vec4{v.x, v.y, v.z, 0.0f}; }
inline glm::vec3 to_vec3(Vec4 v) { return glm::vec3(v[0], v[1], v[2]); }

// Axis-aligned box; the default is empty (lo > hi), so the first grow() sets it.
struct Box {
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  Vec4 lo = {kInf, kInf, kInf, 0.0f};
  Vec4 hi = {-kInf, -kInf, -kInf, 0.0f};

  void grow(Vec4 p) {
    lo = vmin(lo, p);
    hi = vmax(hi, p);
  }
  void grow(Vec4 box_lo, Vec4 box_hi) {
    lo = vmin(lo, box_lo);
    hi = vmax(hi, box_hi);
  }
  void grow(const Box& b) { grow(b.lo, b.hi); }
};

// Half the surface area: the SAH only compares ratios. Requires a non-empty box.
inline float half_area(const Box& b) {
  const Vec4 d = b.hi - b.lo;
  const Vec4 p = d * shuffle_yzxw(d);  // dx dy, dy dz, dz dx, 0
  return p[0] + p[1] + p[2];
}

// (v1 - v0) x (v2 - v0) in double: products of floats are exact there, so it
// is zero only for truly zero-area triangles, and unlike a float cross product
// it neither cancels to zero on a thin sliver nor underflows in normalize().
inline glm::dvec3 triangle_cross(const glm::vec3* v) {
  return glm::cross(glm::dvec3(v[1]) - glm::dvec3(v[0]), glm::dvec3(v[2]) - glm::dvec3(v[0]));
}

inline bool is_degenerate(const glm::vec3* v) { return triangle_cross(v) == glm::dvec3(0.0); }

// The leaf-order record of input triangle `scene_index` with vertices v[0..2].
// A zero-area triangle is stored collapsed onto v[0]: three collinear but
// distinct vertices still project to a sliver of non-zero area after the
// watertight test's rounded shear, and would report hits with no normal to
// reflect about. Three equal vertices make u = v = w = 0 exactly, so det == 0.
// The normal is the unit cross product, or (0, 0, 0) for zero area.
inline BvhTriangle make_bvh_triangle(const glm::vec3* v, std::uint32_t layer, std::uint32_t scene_index,
                                     std::uint32_t solid) {
  const glm::dvec3 n = triangle_cross(v);
  if (n == glm::dvec3(0.0)) return BvhTriangle{v[0], layer, v[0], scene_index, v[0], solid, glm::vec3(0.0f), 0u};
  return BvhTriangle{v[0], layer, v[1], scene_index, v[2], solid, glm::vec3(n * (1.0 / glm::length(n))), 0u};
}

}  // namespace sp
