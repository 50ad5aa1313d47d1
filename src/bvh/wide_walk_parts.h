// The parts the two wide trees and their walks share (wide_bvh.cpp's
// 4-wide ones and wide8_walk.cpp's 8-wide ones): the slot layout and
// packet count of the collapse, the ray's constants, the box margin, the
// collectors of hits, the triangle test on packets and the stack's pop.
// Internal to the bvh module; see wide_bvh.h for what the walks promise.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "bvh/wide_bvh.h"
#include "sp_traverse.h"

// Each file that walks gets its own copy (an unnamed namespace): as
// internal functions, the compiler inlines them as it did when they lived
// in wide_bvh.cpp alone. With external linkage the 4-wide walk compiled
// 512 bytes shorter and ran 10-15 % slower at 1M triangles in 7 of 8
// alternating runs on the benchmark VM (bench/RESULTS.md section 23).
namespace sp::wide_walk {
namespace {

// The slots of the 4-wide node that replaces binary interior node
// `binary`: slots 2g and 2g + 1 hold the children of child g of `binary`
// (g = 0: left), or child g itself in slot 2g when it is a leaf;
// SP_INVALID where unused. (An 8-wide node's slots 4g to 4g + 3 are these
// slots of its child g.)
inline void wide_slots(const Bvh& bvh, std::uint32_t binary, std::uint32_t (&slots)[kWideArity]) {
  for (std::uint32_t s = 0; s < kWideArity; ++s) slots[s] = SP_INVALID;
  for (std::uint32_t g = 0; g < 2u; ++g) {
    const std::uint32_t child = bvh.nodes[binary].left_or_first + g;
    const BvhNode& n = bvh.nodes[child];
    slots[2u * g] = n.count > 0u ? child : n.left_or_first;
    if (n.count == 0u) slots[2u * g + 1u] = n.left_or_first + 1u;
  }
}

// Whether slot entry `slot` (from wide_slots) leads to another wide node:
// it is used and a binary interior node.
inline bool is_interior_slot(const Bvh& bvh, std::uint32_t slot) {
  return slot != SP_INVALID && bvh.nodes[slot].count == 0u;
}

// The packets (TrianglePacket) a binary leaf's triangles fill.
inline std::uint32_t packets_of_leaf(const BvhNode& leaf) { return (leaf.count + kWideArity - 1u) / kWideArity; }

// sp_box_far_margin's scalings of a box's exit distance: a positive one
// and a negative one, behind the origin.
constexpr float kBoxMargin = SP_BOX_MARGIN;
constexpr float kBoxMarginBehind = SP_BOX_MARGIN_BEHIND;

// The walk is inlined whole into each entry point below, so that the
// AVX-512 one compiles all of it for AVX-512.
#if defined(_MSC_VER)
#define SP_ALWAYS_INLINE __forceinline
#else
#define SP_ALWAYS_INLINE __attribute__((always_inline)) inline
#endif

// The 8-wide walk (wide8_walk.cpp) for x86-64 CPUs with AVX-512 (F, VL,
// BW, DQ) and AVX2/BMI2, chosen at run time: 256-bit registers, and 32 of
// them for the ray's constants. Its lanes are the same IEEE operations as
// the baseline's bit for bit: no FMA is enabled, and -ffp-contract=off
// forbids forming one. GCC and Clang only; MSVC and the scalar build keep
// the baseline walk.
#if defined(SP_SIMD_SSE2) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SP_WIDE_AVX512 1
#define SP_TARGET_AVX512 __attribute__((target("avx2,bmi,bmi2,avx512f,avx512vl,avx512bw,avx512dq")))
#endif

// Per-ray constants, splatted across lanes.
struct WideRay {
  Vec4 origin[3];
  Vec4 inv_dir[3];
  Vec4 tmin;
  // Byte offsets in a WideNode of each axis's entry and exit planes' bounds.
  std::size_t entry_plane[3];
  std::size_t exit_plane[3];
  // Woop, in the permuted axes kx, ky, kz of sp_make_query.
  int k[3];
  Vec4 origin_k[3];
  Vec4 shear[3];
};

// Always inlined into walk(), so that sp_make_query's fields reach it in
// registers: called, it read them back from memory, 8 bytes at a time over
// pairs of 4-byte stores that the core cannot forward, and the stall was 9 %
// of a CPU step (perf, bench/RESULTS.md section 14).
SP_ALWAYS_INLINE WideRay make_wide_ray(const shader::RayQuery& q) {
  WideRay r;
  for (int a = 0; a < 3; ++a) {
    r.origin[a] = splat(q.origin[a]);
    r.inv_dir[a] = splat(q.inv_dir[a]);
    // With lo <= hi, (lo - o) * inv <= (hi - o) * inv exactly when inv > 0
    // (rounding is monotonic): choosing the plane by sign gives the min and
    // max of sp_intersect_box's t0, t1 without computing both.
    const auto lo = static_cast<std::size_t>(a) * sizeof(Vec4), hi = lo + 3u * sizeof(Vec4);
    const bool negative = q.inv_dir[a] < 0.0f;
    r.entry_plane[a] = negative ? hi : lo;
    r.exit_plane[a] = negative ? lo : hi;
  }
  r.tmin = splat(q.tmin);
  r.k[0] = q.kx;
  r.k[1] = q.ky;
  r.k[2] = q.kz;
  for (int i = 0; i < 3; ++i) {
    r.origin_k[i] = splat(q.origin[r.k[i]]);
    r.shear[i] = splat(q.shear[i]);
  }
  return r;
}

// sp_box_far_margin. kBehind: the ray's window starts behind its origin
// (tmin < 0, the matter query), where an exit distance may be negative.
// With tmin >= 0 a negative exit misses under either scaling (tnear >= 0),
// so the walks that start at the origin keep the one multiply.
// The larger of the two products is the one sp_box_far_margin picks by the
// sign (rounding is monotonic); the two multiplies run side by side, so
// the look-back adds one max to each node's chain rather than a compare
// and a blend. NaN lanes stay NaN.
template <bool kBehind>
SP_ALWAYS_INLINE Vec4 far_margin(Vec4 tfar) {
  if (!kBehind) return tfar * splat(kBoxMargin);
  return vmax(tfar * splat(kBoxMarginBehind), tfar * splat(kBoxMargin));
}
template <bool kBehind>
SP_ALWAYS_INLINE float far_margin(float tfar) {
  return tfar * (kBehind && tfar < 0.0f ? kBoxMarginBehind : kBoxMargin);
}

// Keeps the compiler from turning a branch into conditional moves
// (predicted_slot). MSVC has no inline assembly on x64; its build may merge
// the branches, which changes the speed, not the answer.
#if defined(__GNUC__) || defined(__clang__)
#define SP_KEEP_BRANCH() asm volatile("")
#else
#define SP_KEEP_BRANCH() ((void)0)
#endif

// What a walk collects. Its limit() is the farthest distance still worth
// visiting, which only ever shrinks; offer() takes a hit with t in
// (tmin, limit()]; enter_leaf(packets) counts the work of the leaves the
// walk enters and is false past SP_MAX_CAST_PACKETS, where the walk ends
// with the collector cut short, as the shared walks do (sp_traverse.h).
// The walks enter the same leaves in the same order as the binary one, so
// they stop at the same leaf.

// The best hit so far, with sp_closest_hit's acceptance rule.
struct Best {
  HitInfo hit;
  const BvhTriangle* triangles;
  float tmax;
  std::uint32_t packets;

  // No hit yet within tmax.
  static Best start(const Bvh& bvh, float tmax) {
    return Best{HitInfo{tmax, SP_INVALID, 0u}, bvh.triangles.data(), tmax, 0u};
  }

  bool enter_leaf(std::uint32_t leaf_packets) {
    packets += leaf_packets;
    if (packets <= SP_MAX_CAST_PACKETS) return true;
    hit = HitInfo{tmax, SP_INVALID, 1u};
    return false;
  }

  float limit() const { return hit.t; }
  std::uint32_t scene(std::uint32_t triangle) const {
    return triangle == SP_INVALID ? SP_INVALID : triangles[triangle].scene_index;
  }
  // The scene index is read only for an exact tie, where sp_better_hit
  // needs it.
  void offer(float t, std::uint32_t triangle) {
    if (t < hit.t || scene(triangle) < scene(hit.triangle)) hit = HitInfo{t, triangle, 0u};
  }
};

// Whether anything lies in (tmin, tmax], as sp_segment_blocked says: the
// closest-hit walk with nothing found yet, ended by the first hit. Its limit
// then drops below every box and triangle, so the walk leaves the leaf it
// is in and pops nothing more. A walk cut short counts as blocked. With no
// hit the limit stays tmax, so the walk enters the leaves the closest-hit
// walk (and the binary one) would, and is cut short where they are.
struct Blocker {
  float tmax;
  std::uint32_t packets;
  bool blocked;

  static Blocker start(float tmax) { return Blocker{tmax, 0u, false}; }

  bool enter_leaf(std::uint32_t leaf_packets) {
    packets += leaf_packets;
    if (packets <= SP_MAX_CAST_PACKETS) return true;
    blocked = true;
    return false;
  }

  float limit() const { return blocked ? -std::numeric_limits<float>::infinity() : tmax; }
  void offer(float, std::uint32_t) { blocked = true; }
};

// The nearest hits, with sp_nearest_hits' list, keys and limit.
struct Nearest {
  shader::HitList list;
  float tmax;
  glm::vec3 dir;
  const BvhTriangle* triangles;
  std::uint32_t packets;

  // An empty list, as sp_nearest_hits starts it.
  static Nearest start(const Bvh& bvh, glm::vec3 dir, float tmax) {
    Nearest nearest{{}, tmax, dir, bvh.triangles.data(), 0u};
    nearest.list.count = 0u;
    nearest.list.cut_short = 0u;
    nearest.list.t[SP_MATTER_MAX_HITS - 1u] = tmax;
    return nearest;
  }

  bool enter_leaf(std::uint32_t leaf_packets) {
    packets += leaf_packets;
    if (packets <= SP_MAX_CAST_PACKETS) return true;
    list.cut_short = 1u;
    return false;
  }

  float limit() const { return shader::sp_hit_list_limit(list.count, list.t[SP_MATTER_MAX_HITS - 1u], tmax); }
  void offer(float t, std::uint32_t triangle) {
    const BvhTriangle& tri = triangles[triangle];
    shader::sp_hit_list_offer(list, t, triangle, tri.solid * 4u + shader::sp_crossing(tri.normal, dir));
  }
};

// sp_intersect_triangle on `count` packets, then the acceptance window
// (tmin, limit] and the collector's rule. Every line mirrors the shared
// function operation for operation, so each lane's t is bit-identical to it.
template <class Collector>
SP_ALWAYS_INLINE void intersect_packets(const WideRay& r, const TrianglePacket* packets, std::uint32_t count,
                                        Collector& best) {
  const Vec4 zero = splat(0.0f);
  for (const TrianglePacket* p = packets; p != packets + count; ++p) {
    // a = v0 - origin, b = v1 - origin, c = v2 - origin, in the axes kx, ky, kz.
    Vec4 d[3][3];
    for (int vertex = 0; vertex < 3; ++vertex)
      for (int i = 0; i < 3; ++i) d[vertex][i] = p->v[vertex][r.k[i]] - r.origin_k[i];
    const Vec4 ax = d[0][0] - r.shear[0] * d[0][2];
    const Vec4 ay = d[0][1] - r.shear[1] * d[0][2];
    const Vec4 bx = d[1][0] - r.shear[0] * d[1][2];
    const Vec4 by = d[1][1] - r.shear[1] * d[1][2];
    const Vec4 cx = d[2][0] - r.shear[0] * d[2][2];
    const Vec4 cy = d[2][1] - r.shear[1] * d[2][2];
    const Vec4 u = cx * by - cy * bx;
    const Vec4 v = ax * cy - ay * cx;
    const Vec4 w = bx * ay - by * ax;
    const Int4 outside = ((u < zero) | (v < zero) | (w < zero)) & ((u > zero) | (v > zero) | (w > zero));
    const Vec4 det = u + v + w;
    const Vec4 az = r.shear[2] * d[0][2];
    const Vec4 bz = r.shear[2] * d[1][2];
    const Vec4 cz = r.shear[2] * d[2][2];
    const Vec4 t_scaled = u * az + v * bz + w * cz;
    const Vec4 t = t_scaled / det;  // lanes with det == 0 are masked below
    // t <= limit <= tmax stands for t <= tmax; the tie needs offer().
    const Int4 candidate =
        and_not(outside, (det != zero) & (t < splat(SP_FAR)) & (t > r.tmin) & (t <= splat(best.limit())));
    for (unsigned m = lane_mask(candidate); m != 0u; m &= m - 1u) {
      const auto lane = static_cast<unsigned>(std::countr_zero(m));
      if (t[lane] <= best.limit()) best.offer(t[lane], p->triangle[lane]);
    }
  }
}


// Pops the walk's stack of waiting slots (each with its box's entry
// distance `t`) down to the first one still worth entering with the best
// hit's limit, skipping those that a closer hit has since ruled out:
// re-testing a box with the new limit would give the same entry distance,
// and far_margin(min(exit, limit)) is below it exactly when
// far_margin(limit) is (far_margin is monotonic). Returns false when none
// is left; else stack[size] is the slot to enter.
template <bool kBehind, class Entry>
SP_ALWAYS_INLINE bool pop_live(const Entry* stack, std::uint32_t& size, float best_limit) {
  const float limit = far_margin<kBehind>(best_limit);
  for (;;) {
    if (size == 0u) return false;
    --size;
    if (stack[size].t <= limit) return true;
  }
}

}  // namespace
}  // namespace sp::wide_walk
