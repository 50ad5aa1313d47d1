// The single-ray SIMD walk of the 4-wide BVH (built by wide_collapse.cpp),
// and the choice between it and the 8-wide one; see wide_bvh.h for the
// references and the node layout.
//
// Written with simd4.h's Vec4 and Int4 (one SSE2 register per Vec4 on
// x86, NEON on ARM, four scalar lanes elsewhere), as bvh_geometry.h is.
#include "bvh/wide_bvh.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <limits>

#include "bvh/wide8_walk.h"
#include "bvh/wide_walk_parts.h"
#include "sp_traverse.h"

namespace sp {
namespace {

using namespace wide_walk;

// A node pushes at most kWideArity - 1 siblings, and a path holds fewer wide
// nodes than the binary depth, so the stack cannot overflow.
constexpr std::uint32_t kStackSize = (kWideArity - 1u) * SP_BVH_MAX_DEPTH;

SP_ALWAYS_INLINE Vec4 plane(const WideNode& node, std::size_t offset) {
  return *reinterpret_cast<const Vec4*>(reinterpret_cast<const char*>(node.bounds) + offset);
}

// Distances of the four slots' entry planes on axis `a`.
SP_ALWAYS_INLINE Vec4 slab_entry(const WideRay& r, const WideNode& node, int a) {
  return (plane(node, r.entry_plane[a]) - r.origin[a]) * r.inv_dir[a];
}

// sp_intersect_box on the four slots with limit `tmax`: returns the lanes
// hit, with their entry distances in `tnear`. kParallel: the ray has
// direction components of magnitude <= 1e-20, the bits of `parallel`
// (RayQuery::parallel_axes). kBehind: as far_margin.
//
// The box-derived value is always the second operand of vmin/vmax, which
// return it when the comparison is unordered, so the NaN bounds of an
// unused slot reach tnear and tfar (see WideNode); far_margin keeps them
// NaN (a NaN times either factor, and vmax of two NaNs).
template <bool kParallel, bool kBehind>
SP_ALWAYS_INLINE unsigned intersect_boxes(const WideRay& r, std::uint32_t parallel, const WideNode& node, float tmax,
                                          Vec4& tnear) {
  Vec4 entry[3], exit[3];
  for (int a = 0; a < 3; ++a) {
    entry[a] = slab_entry(r, node, a);
    exit[a] = (plane(node, r.exit_plane[a]) - r.origin[a]) * r.inv_dir[a];
    if (kParallel && (parallel & (1u << a))) {  // a ray inside the slab never leaves it
      const Int4 inside = (node.bounds[a] <= r.origin[a]) & (r.origin[a] <= node.bounds[3 + a]);
      exit[a] = select(inside, splat(SP_FAR), exit[a]);
    }
  }
  // Two levels of min/max rather than a chain of three: a shorter latency
  // on the path to the next node's address.
  tnear = vmax(vmax(entry[0], entry[1]), vmax(r.tmin, entry[2]));
  const Vec4 tfar = vmin(vmin(exit[0], exit[1]), vmin(splat(tmax), exit[2]));
  return lane_mask(tnear <= far_margin<kBehind>(tfar));
}

// node.slot[lane] for the lane set in one-hot mask `lane_bit`, chosen by
// branches rather than read at a computed index. The branch predictor then
// guesses the next node, and the core starts loading it while this node's
// boxes are still being tested; an indexed read waits for the test, and in
// a tree that the caches hold that wait was the walk's longest
// (bench/RESULTS.md section 20). Where the guess is wrong the core discards
// the loads: the answer is the same either way.
SP_ALWAYS_INLINE WideSlot predicted_slot(const WideNode& node, unsigned lane_bit) {
  if (lane_bit == 1u) {
    SP_KEEP_BRANCH();
    return node.slot[0];
  }
  if (lane_bit == 2u) {
    SP_KEEP_BRANCH();
    return node.slot[1];
  }
  if (lane_bit == 4u) {
    SP_KEEP_BRANCH();
    return node.slot[2];
  }
  return node.slot[3];
}

// Which of slots 0-1 and 2-3 the binary traversal enters first when both
// hold hits: the children of the nearer of their two parents, the left on a
// tie. A parent's box is the union of its children's (build_bvh's bounds are
// exact) and rounding is monotonic, so its entry plane's distance is the
// smaller of its children's on each axis: sp_intersect_box's tnear for it,
// from the slots' entries. An unused slot 1 or 3 is the first operand of
// vmin and loses to the NaN-free slot 0 or 2.
SP_ALWAYS_INLINE std::uint32_t first_pair(const WideRay& r, const WideNode& node) {
  Vec4 parent = r.tmin;
  for (int a = 0; a < 3; ++a) {
    const Vec4 e = slab_entry(r, node, a);
    parent = vmax(parent, vmin(shuffle_yxwz(e), e));
  }
  return parent[0] <= parent[2] ? 0u : 2u;
}

// Starts loading what every slot of `node` leads to, hit or not, before its
// boxes are tested. In a tree larger than the core's own caches a wide node
// or packet is rarely there past the first levels, and the next address is
// known only after the box test; fetching all four while the test runs
// overlaps those misses with it and with each other. An unused slot
// prefetches the root: harmless.
SP_ALWAYS_INLINE void prefetch_slots(const WideNode& node, const WideNode* nodes, const TrianglePacket* packets) {
  static_assert(sizeof(WideNode) <= 2 * 64 && sizeof(TrianglePacket) <= 3 * 64);
  for (const WideSlot& slot : node.slot) {
    // A packet is 160 bytes (three lines at most), a node 128 (two).
    const char* p = slot.count == 0u ? reinterpret_cast<const char*>(nodes + slot.child)
                                     : reinterpret_cast<const char*>(packets + slot.child);
    prefetch(p);
    prefetch(p + 64);
    prefetch(p + 128);
  }
}

// The traversal proper. Entering slots in the order of the binary walk (see
// the file comment of wide_bvh.h) is what makes the answer identical to it.
template <bool kParallel, bool kPrefetch, bool kBehind, class Collector>
SP_ALWAYS_INLINE void traverse(const WideBvh& wide, const WideRay& ray, std::uint32_t parallel, Collector& best) {
  // A slot that waits, with the entry distance of its box.
  struct Entry {
    float t;
    WideSlot slot;
  };
  Entry stack[kStackSize];
  std::uint32_t size = 0;
  WideSlot item{0u, 0u};  // the root
  const WideNode* nodes = wide.nodes.data();
  const TrianglePacket* packets = wide.packets.data();

  for (;;) {
    if (item.count == 0u) {
      const WideNode& node = nodes[item.child];
      if (kPrefetch) prefetch_slots(node, nodes, packets);
      Vec4 tnear;
      const unsigned hits = intersect_boxes<kParallel, kBehind>(ray, parallel, node, best.limit(), tnear);
      if (hits != 0u) {
        if ((hits & (hits - 1u)) == 0u) {  // one hit, the common case
          item = predicted_slot(node, hits);
          continue;
        }
        // Push in reverse order of the binary walk, so that it pops in order:
        // the pair entered second, then the farther slot of the first.
        auto push = [&](std::uint32_t s) {
          assert(size < kStackSize);
          stack[size++] = Entry{tnear[s], node.slot[s]};
        };
        // The nearer slot of pair p (slots p, p + 1) when both are hit; ties go left.
        auto nearer = [&](std::uint32_t p) { return tnear[p] <= tnear[p + 1u] ? p : p + 1u; };
        const std::uint32_t first = (hits & 3u) == 0u ? 2u : (hits & 12u) == 0u ? 0u : first_pair(ray, node);
        const std::uint32_t second = first ^ 2u;
        const unsigned in_second = (hits >> second) & 3u;
        if (in_second == 3u) {
          const std::uint32_t s = nearer(second);
          push(s ^ 1u);
          push(s);
        } else if (in_second != 0u) {
          push(second + (in_second >> 1u));
        }
        const unsigned in_first = (hits >> first) & 3u;
        if (in_first == 3u) {
          const std::uint32_t s = nearer(first);
          push(s ^ 1u);
          item = predicted_slot(node, 1u << s);
        } else {
          const std::uint32_t s = first + (in_first >> 1u);
          item = predicted_slot(node, 1u << s);
        }
        continue;
      }
    } else {
      if (!best.enter_leaf(item.count)) return;
      intersect_packets(ray, packets + item.child, item.count, best);
    }
    if (!pop_live<kBehind>(stack, size, best.limit())) return;
    item = stack[size].slot;
  }
}

template <bool kBehind, class Collector>
SP_ALWAYS_INLINE void walk_from(const WideBvh& wide, const WideRay& ray, std::uint32_t parallel, bool large,
                                Collector& collector) {
  if (parallel != 0u) {
    traverse<true, false, kBehind>(wide, ray, parallel, collector);
  } else if (large) {
    traverse<false, true, kBehind>(wide, ray, 0u, collector);
  } else {
    traverse<false, false, kBehind>(wide, ray, 0u, collector);
  }
}

template <class Collector>
SP_ALWAYS_INLINE void walk(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax,
                           Collector& collector) {
  const shader::RayQuery q = shader::sp_make_query(origin, dir, tmin, tmax);
  const WideRay ray = make_wide_ray(q);
  const bool large = wide.wide4_bytes() > kPrefetchTreeBytes;
  if (q.tmin < 0.0f) {
    walk_from<true>(wide, ray, q.parallel_axes, large, collector);
  } else {
    walk_from<false>(wide, ray, q.parallel_axes, large, collector);
  }
}

// The two queries' bodies on the 4-wide tree (the baseline walk).
SP_ALWAYS_INLINE HitInfo closest_hit_in(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                        float tmin, float tmax) {
  Best best = Best::start(bvh, tmax);
  walk(wide, origin, dir, tmin, tmax, best);
  return best.hit;
}

SP_ALWAYS_INLINE shader::HitList nearest_hits_in(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                                 float tmin, float tmax) {
  Nearest nearest = Nearest::start(bvh, dir, tmax);
  walk(wide, origin, dir, tmin, tmax, nearest);
  return nearest.list;
}

SP_ALWAYS_INLINE bool segment_blocked_in(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
  Blocker blocker = Blocker::start(tmax);
  walk(wide, origin, dir, tmin, tmax, blocker);
  return blocker.blocked;
}

#if defined(SP_WIDE_AVX512)
SP_TARGET_AVX512 HitInfo closest_hit_avx512(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                            float tmin, float tmax) {
  return closest_hit_in(wide, bvh, origin, dir, tmin, tmax);
}
SP_TARGET_AVX512 shader::HitList nearest_hits_avx512(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin,
                                                     glm::vec3 dir, float tmin, float tmax) {
  return nearest_hits_in(wide, bvh, origin, dir, tmin, tmax);
}
SP_TARGET_AVX512 bool segment_blocked_avx512(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin,
                                             float tmax) {
  return segment_blocked_in(wide, origin, dir, tmin, tmax);
}
#endif

bool cpu_runs(WideWalk walk) {
  switch (walk) {
    case WideWalk::Baseline:
      return true;
    case WideWalk::Avx512:
    case WideWalk::Avx512Wide8:
      return wide8::cpu_runs();  // the same CPUs and builds
  }
  return false;
}

// The walk in use: the fastest this CPU runs, until select_wide_walk.
std::atomic<WideWalk>& selected() {
  static std::atomic<WideWalk> walk{cpu_runs(WideWalk::Avx512Wide8) ? WideWalk::Avx512Wide8 : WideWalk::Baseline};
  return walk;
}

// The walk a query on `wide` takes: the selected one, but the 4-wide
// AVX-512 walk where the 8-wide one is selected and the tree has no 8-wide
// copy (past kWide8MaxTreeBytes).
[[maybe_unused]] WideWalk walk_on(const WideBvh& wide) {
  const WideWalk walk = selected().load(std::memory_order_relaxed);
  return walk == WideWalk::Avx512Wide8 && wide.nodes8.empty() ? WideWalk::Avx512 : walk;
}

}  // namespace

bool wide_walk_available(WideWalk walk) { return cpu_runs(walk); }

bool select_wide_walk(WideWalk walk) {
  if (!cpu_runs(walk)) return false;
  selected().store(walk, std::memory_order_relaxed);
  return true;
}

WideWalk selected_wide_walk() { return selected().load(std::memory_order_relaxed); }

const char* wide_walk_name(WideWalk walk) {
  switch (walk) {
    case WideWalk::Baseline:
      return "baseline";
    case WideWalk::Avx512:
      return "avx512";
    case WideWalk::Avx512Wide8:
      return "avx512-8wide";
  }
  return "?";
}

HitInfo wide_closest_hit(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
#if defined(SP_WIDE_AVX512)
  switch (walk_on(wide)) {
    case WideWalk::Avx512Wide8:
      return wide8::closest_hit(wide, bvh, origin, dir, tmin, tmax);
    case WideWalk::Avx512:
      return closest_hit_avx512(wide, bvh, origin, dir, tmin, tmax);
    case WideWalk::Baseline:
      break;
  }
#endif
  return closest_hit_in(wide, bvh, origin, dir, tmin, tmax);
}

shader::HitList wide_nearest_hits(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin,
                                  float tmax) {
#if defined(SP_WIDE_AVX512)
  switch (walk_on(wide)) {
    case WideWalk::Avx512Wide8:
      return wide8::nearest_hits(wide, bvh, origin, dir, tmin, tmax);
    case WideWalk::Avx512:
      return nearest_hits_avx512(wide, bvh, origin, dir, tmin, tmax);
    case WideWalk::Baseline:
      break;
  }
#endif
  return nearest_hits_in(wide, bvh, origin, dir, tmin, tmax);
}

bool wide_segment_blocked(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
#if defined(SP_WIDE_AVX512)
  switch (walk_on(wide)) {
    case WideWalk::Avx512Wide8:
      return wide8::segment_blocked(wide, origin, dir, tmin, tmax);
    case WideWalk::Avx512:
      return segment_blocked_avx512(wide, origin, dir, tmin, tmax);
    case WideWalk::Baseline:
      break;
  }
#endif
  return segment_blocked_in(wide, origin, dir, tmin, tmax);
}

}  // namespace sp
