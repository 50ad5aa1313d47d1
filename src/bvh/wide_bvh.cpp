// Collapse of the binary BVH into 4-wide nodes and their single-ray SIMD
// traversal; see wide_bvh.h for the references and the node layout.
//
// Written with simd4.h's Vec4 and Int4 (one SSE2 register per Vec4 on
// x86, NEON on ARM, four scalar lanes elsewhere), as bvh_geometry.h is.
#include "bvh/wide_bvh.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <limits>

#include "bvh/build_workers.h"
#include "bvh/wide8_walk.h"
#include "bvh/wide_walk_parts.h"
#include "sp_traverse.h"

namespace sp {
namespace {

using namespace wide_walk;

// A node pushes at most kWideArity - 1 siblings, and a path holds fewer wide
// nodes than the binary depth, so the stack cannot overflow.
constexpr std::uint32_t kStackSize = (kWideArity - 1u) * SP_BVH_MAX_DEPTH;

// ---------------------------------------------------------------- collapse

// Whether slot entry `slot` (from wide_slots) leads to another wide node.
bool is_interior_slot(const Bvh& bvh, std::uint32_t slot) { return slot != SP_INVALID && bvh.nodes[slot].count == 0u; }

// What the collapse of a binary subtree writes: its wide nodes and packets.
struct CollapseSize {
  std::uint32_t nodes = 0;
  std::uint32_t packets = 0;
};

// The size of the collapse of binary interior node `binary`'s subtree,
// walking the same slots collapse() does, so the output can be laid out
// before it is written (and subtrees written concurrently).
CollapseSize collapse_size(const Bvh& bvh, std::uint32_t binary) {
  CollapseSize size{1u, 0u};
  std::uint32_t slots[kWideArity];
  wide_slots(bvh, binary, slots);
  for (const std::uint32_t slot : slots) {
    if (slot == SP_INVALID) continue;
    const BvhNode& n = bvh.nodes[slot];
    if (n.count > 0u) {
      size.packets += packets_of_leaf(n);
    } else {
      const CollapseSize child = collapse_size(bvh, slot);
      size.nodes += child.nodes;
      size.packets += child.packets;
    }
  }
  return size;
}

// Writes the collapse of one binary subtree into `wide`, whose arrays are
// already sized, from the given node and packet positions on: the wide
// nodes in depth-first order (children after their parent), each leaf's
// packets when its slot is filled. Collapsers of disjoint subtrees, given
// the positions a serial collapse would reach, write disjoint parts of the
// same arrays and together write exactly what one serial collapse writes.
class Collapser {
 public:
  // `leaf_packets`, when given, gets each binary leaf's first packet (for
  // the 8-wide tree, which shares them).
  Collapser(const Bvh& bvh, WideBvh& wide, CollapseSize cursor, std::vector<std::uint32_t>* leaf_packets)
      : bvh_(bvh), wide_(wide), cursor_(cursor), leaf_packets_(leaf_packets) {}

  // The wide node of binary interior node `binary` at wide level `level`,
  // and its subtree; returns its index.
  std::uint32_t collapse(std::uint32_t binary, std::uint32_t level) {
    std::uint32_t slots[kWideArity];
    const std::uint32_t index = write_node(binary, level, slots);
    for (std::uint32_t s = 0; s < kWideArity; ++s) {
      if (is_interior_slot(bvh_, slots[s])) {
        wide_.nodes[index].slot[s].child = collapse(slots[s], level + 1u);
      }
    }
    return index;
  }

  // The wide node of binary interior node `binary` alone, with its leaf
  // slots' packets; its interior slots' children are left for the caller.
  std::uint32_t write_node(std::uint32_t binary, std::uint32_t level, std::uint32_t (&slots)[kWideArity]) {
    depth_ = std::max(depth_, level);
    wide_slots(bvh_, binary, slots);
    const std::uint32_t index = cursor_.nodes++;
    WideNode& node = wide_.nodes[index];
    node = empty_node();
    for (std::uint32_t s = 0; s < kWideArity; ++s)
      if (slots[s] != SP_INVALID) fill_slot(node, s, slots[s]);
    return index;
  }

  // The root when it is a single leaf: a wide root with one slot.
  void collapse_leaf_root() {
    depth_ = 1u;
    WideNode& root = wide_.nodes[cursor_.nodes++];
    root = empty_node();
    fill_slot(root, 0u, 0u);
  }

  std::uint32_t depth() const { return depth_; }

 private:
  static WideNode empty_node() {
    WideNode node{};
    for (Vec4& b : node.bounds) b = splat(std::numeric_limits<float>::quiet_NaN());
    return node;
  }

  // Slot `slot` of `node` becomes binary node `binary`; a leaf gets its
  // packets now, an interior node its wide index later.
  void fill_slot(WideNode& node, std::uint32_t slot, std::uint32_t binary) {
    const BvhNode& n = bvh_.nodes[binary];
    for (int a = 0; a < 3; ++a) {
      node.bounds[a].set(static_cast<int>(slot), n.bmin[a]);
      node.bounds[3 + a].set(static_cast<int>(slot), n.bmax[a]);
    }
    if (n.count > 0u) {
      node.slot[slot] = WideSlot{add_packets(n.left_or_first, n.count), packets_of_leaf(n)};
      if (leaf_packets_ != nullptr) (*leaf_packets_)[binary] = node.slot[slot].child;
    }
  }

  // Packs leaf triangles [first, first + count); returns the first packet.
  std::uint32_t add_packets(std::uint32_t first, std::uint32_t count) {
    const std::uint32_t start = cursor_.packets;
    for (std::uint32_t base = 0; base < count; base += kWideArity) {
      TrianglePacket p{};  // padding lanes: vertices at the origin
      for (std::uint32_t lane = 0; lane < kWideArity; ++lane) {
        if (base + lane >= count) {
          p.triangle[lane] = SP_INVALID;
          continue;
        }
        const std::uint32_t i = first + base + lane;
        const BvhTriangle& t = bvh_.triangles[i];
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k)
          for (int a = 0; a < 3; ++a) p.v[k][a].set(static_cast<int>(lane), v[k][a]);
        p.triangle[lane] = i;
      }
      wide_.packets[cursor_.packets++] = p;
    }
    return start;
  }

  const Bvh& bvh_;
  WideBvh& wide_;
  CollapseSize cursor_;
  std::vector<std::uint32_t>* leaf_packets_;
  std::uint32_t depth_ = 0;
};

// --------------------------------------------------------------- traversal

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
      intersect_packets(ray, packets + item.child, item.count, best);
    }
    if (!pop_live<kBehind>(stack, size, best.limit())) return;
    item = stack[size].slot;
  }
}

}  // namespace

namespace {

// The 4-wide collapse. With `for_wide8`, and a tree of at most
// kWide8MaxTreeBytes, `leaf_packets` gets each binary leaf's first packet
// for the 8-wide collapse; else it stays empty, and a large tree's build
// does not pay for it.
void collapse_wide4(const Bvh& bvh, BuildWorkers* workers, bool for_wide8, std::vector<std::uint32_t>& leaf_packets,
                    WideBvh& wide) {
  if (bvh.nodes[0].count > 0u) {
    wide.nodes.resize(1u);
    wide.packets.resize(packets_of_leaf(bvh.nodes[0]));
    if (for_wide8) leaf_packets.assign(1u, SP_INVALID);
    Collapser collapser(bvh, wide, {}, for_wide8 ? &leaf_packets : nullptr);
    collapser.collapse_leaf_root();
    wide.depth = collapser.depth();
    return;
  }
  // Laid out as one serial collapse writes it: the root's node and its leaf
  // slots' packets, then the subtree of each interior slot in slot order.
  // Sizing the subtrees first tells each one where it writes.
  std::uint32_t slots[kWideArity];
  wide_slots(bvh, 0u, slots);
  auto interior = [&](std::uint32_t s) { return is_interior_slot(bvh, slots[s]); };
  CollapseSize start[kWideArity] = {};
  CollapseSize total{1u, 0u};
  for (std::uint32_t s = 0; s < kWideArity; ++s)
    if (slots[s] != SP_INVALID && !interior(s)) total.packets += packets_of_leaf(bvh.nodes[slots[s]]);
  for (std::uint32_t s = 0; s < kWideArity; ++s) {
    if (!interior(s)) continue;
    start[s] = total;
    const CollapseSize size = collapse_size(bvh, slots[s]);
    total.nodes += size.nodes;
    total.packets += size.packets;
  }
  const std::size_t bytes =
      std::size_t{total.nodes} * sizeof(WideNode) + std::size_t{total.packets} * sizeof(TrianglePacket);
  if (for_wide8 && bytes <= kWide8MaxTreeBytes) leaf_packets.assign(bvh.nodes.size(), SP_INVALID);
  std::vector<std::uint32_t>* const leaf_packets_out = leaf_packets.empty() ? nullptr : &leaf_packets;
  wide.nodes.resize(total.nodes);
  wide.packets.resize(total.packets);

  Collapser root(bvh, wide, {}, leaf_packets_out);
  root.write_node(0u, 1u, slots);
  wide.depth = root.depth();
  // The subtrees write disjoint parts of the arrays, so they may run on
  // other threads.
  std::uint32_t subtree_depth[kWideArity] = {};
  for (std::uint32_t s = 0; s < kWideArity; ++s)
    if (interior(s)) wide.nodes[0].slot[s].child = start[s].nodes;
  auto collapse_subtree = [&](std::uint32_t s) {
    if (!interior(s)) return;
    Collapser collapser(bvh, wide, start[s], leaf_packets_out);
    collapser.collapse(slots[s], 2u);
    subtree_depth[s] = collapser.depth();
  };
  BuildWorkers serial(1u);
  BuildWorkers& forks = workers != nullptr ? *workers : serial;
  static_assert(kWideArity == 4u);
  auto collapse_pair = [&](std::uint32_t first) {
    forks.run_both([&] { collapse_subtree(first + 1u); }, [&] { collapse_subtree(first); });
  };
  forks.run_both([&] { collapse_pair(2u); }, [&] { collapse_pair(0u); });
  for (std::uint32_t s = 0; s < kWideArity; ++s) wide.depth = std::max(wide.depth, subtree_depth[s]);
}

}  // namespace

WideBvh build_wide_bvh(const Bvh& bvh, BuildWorkers* workers) {
  assert(!bvh.nodes.empty());
  WideBvh wide;
  // Where the 8-wide walk runs, both trees (up to the 8-wide one's size):
  // the 8-wide one for it, the 4-wide one for the walks that
  // select_wide_walk may choose instead.
  std::vector<std::uint32_t> leaf_packets;
  collapse_wide4(bvh, workers, wide8::cpu_runs(), leaf_packets, wide);
  if (!leaf_packets.empty()) wide8::collapse(bvh, leaf_packets, wide);
  return wide;
}

namespace {

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

#if defined(SP_WIDE_AVX512)
SP_TARGET_AVX512 HitInfo closest_hit_avx512(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                            float tmin, float tmax) {
  return closest_hit_in(wide, bvh, origin, dir, tmin, tmax);
}
SP_TARGET_AVX512 shader::HitList nearest_hits_avx512(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin,
                                                     glm::vec3 dir, float tmin, float tmax) {
  return nearest_hits_in(wide, bvh, origin, dir, tmin, tmax);
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
  switch (selected_wide_walk()) {
    case WideWalk::Avx512Wide8:
      if (!wide.nodes8.empty()) return wide8::closest_hit(wide, bvh, origin, dir, tmin, tmax);
      [[fallthrough]];
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
  switch (selected_wide_walk()) {
    case WideWalk::Avx512Wide8:
      if (!wide.nodes8.empty()) return wide8::nearest_hits(wide, bvh, origin, dir, tmin, tmax);
      [[fallthrough]];
    case WideWalk::Avx512:
      return nearest_hits_avx512(wide, bvh, origin, dir, tmin, tmax);
    case WideWalk::Baseline:
      break;
  }
#endif
  return nearest_hits_in(wide, bvh, origin, dir, tmin, tmax);
}

}  // namespace sp
