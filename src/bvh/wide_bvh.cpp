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
#include "sp_traverse.h"

namespace sp {
namespace {

// sp_box_far_margin's scalings of a box's exit distance: a positive one
// and a negative one, behind the origin.
constexpr float kBoxMargin = SP_BOX_MARGIN;
constexpr float kBoxMarginBehind = SP_BOX_MARGIN_BEHIND;
// A node pushes at most kWideArity - 1 siblings, and a path holds fewer wide
// nodes than the binary depth, so the stack cannot overflow.
constexpr std::uint32_t kStackSize = (kWideArity - 1u) * SP_BVH_MAX_DEPTH;

// The walk is inlined whole into each entry point below, so that the
// AVX-512 one compiles all of it for AVX-512.
#if defined(_MSC_VER)
#define SP_ALWAYS_INLINE __forceinline
#else
#define SP_ALWAYS_INLINE __attribute__((always_inline)) inline
#endif

// A second copy of the walk for x86-64 CPUs with AVX-512 (F, VL, BW, DQ)
// and AVX2/BMI2, chosen at run time. It is the same source: the same SSE
// operations, encoded with EVEX, where 32 vector registers hold the ray's
// constants that spill from SSE's 16 (the walk waits on its own dependency
// chain, and AVX2's 16 registers did not help: bench/RESULTS.md sections 13
// and 14). Lane results are the same IEEE operations bit for bit: no FMA
// is enabled here, and -ffp-contract=off forbids forming one. GCC and Clang
// only; MSVC and the scalar build keep the baseline walk.
#if defined(SP_SIMD_SSE2) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SP_WIDE_AVX512 1
#define SP_TARGET_AVX512 __attribute__((target("avx2,bmi,bmi2,avx512f,avx512vl,avx512bw,avx512dq")))
#endif

// ---------------------------------------------------------------- collapse

// The slots of the wide node that replaces binary interior node `binary`:
// slots 2g and 2g + 1 hold the children of child g of `binary` (g = 0:
// left), or child g itself in slot 2g when it is a leaf; SP_INVALID where
// unused.
void wide_slots(const Bvh& bvh, std::uint32_t binary, std::uint32_t (&slots)[kWideArity]) {
  for (std::uint32_t s = 0; s < kWideArity; ++s) slots[s] = SP_INVALID;
  for (std::uint32_t g = 0; g < 2u; ++g) {
    const std::uint32_t child = bvh.nodes[binary].left_or_first + g;
    const BvhNode& n = bvh.nodes[child];
    slots[2u * g] = n.count > 0u ? child : n.left_or_first;
    if (n.count == 0u) slots[2u * g + 1u] = n.left_or_first + 1u;
  }
}

// Whether slot entry `slot` (from wide_slots) leads to another wide node.
bool is_interior_slot(const Bvh& bvh, std::uint32_t slot) { return slot != SP_INVALID && bvh.nodes[slot].count == 0u; }

std::uint32_t packets_of_leaf(const BvhNode& leaf) { return (leaf.count + kWideArity - 1u) / kWideArity; }

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
  Collapser(const Bvh& bvh, WideBvh& wide, CollapseSize cursor) : bvh_(bvh), wide_(wide), cursor_(cursor) {}

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
    if (n.count > 0u) node.slot[slot] = WideSlot{add_packets(n.left_or_first, n.count), packets_of_leaf(n)};
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
  std::uint32_t depth_ = 0;
};

// --------------------------------------------------------------- traversal

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

SP_ALWAYS_INLINE Vec4 plane(const WideNode& node, std::size_t offset) {
  return *reinterpret_cast<const Vec4*>(reinterpret_cast<const char*>(node.bounds) + offset);
}

// Distances of the four slots' entry planes on axis `a`.
SP_ALWAYS_INLINE Vec4 slab_entry(const WideRay& r, const WideNode& node, int a) {
  return (plane(node, r.entry_plane[a]) - r.origin[a]) * r.inv_dir[a];
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

// Keeps the compiler from turning a branch into conditional moves
// (predicted_slot). MSVC has no inline assembly on x64; its build may merge
// the branches, which changes the speed, not the answer.
#if defined(__GNUC__) || defined(__clang__)
#define SP_KEEP_BRANCH() asm volatile("")
#else
#define SP_KEEP_BRANCH() ((void)0)
#endif

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

// What a walk collects. Its limit() is the farthest distance still worth
// visiting, which only ever shrinks; offer() takes a hit with t in
// (tmin, limit()].

// The best hit so far, with sp_closest_hit's acceptance rule.
struct Best {
  HitInfo hit;
  const BvhTriangle* triangles;

  float limit() const { return hit.t; }
  std::uint32_t scene(std::uint32_t triangle) const {
    return triangle == SP_INVALID ? SP_INVALID : triangles[triangle].scene_index;
  }
  // The scene index is read only for an exact tie, where sp_better_hit
  // needs it.
  void offer(float t, std::uint32_t triangle) {
    if (t < hit.t || scene(triangle) < scene(hit.triangle)) hit = HitInfo{t, triangle};
  }
};

// The nearest hits, with sp_nearest_hits' list, keys and limit.
struct Nearest {
  shader::HitList list;
  float tmax;
  glm::vec3 dir;
  const BvhTriangle* triangles;

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
    // Pop, skipping slots that a closer hit has since ruled out: re-testing
    // the box with the new limit would give the same entry distance, and
    // far_margin(min(exit, limit)) is below it exactly when
    // far_margin(limit) is (far_margin is monotonic).
    const float limit = far_margin<kBehind>(best.limit());
    for (;;) {
      if (size == 0u) return;
      --size;
      if (stack[size].t <= limit) break;
    }
    item = stack[size].slot;
  }
}

}  // namespace

WideBvh build_wide_bvh(const Bvh& bvh, BuildWorkers* workers) {
  assert(!bvh.nodes.empty());
  WideBvh wide;
  if (bvh.nodes[0].count > 0u) {
    wide.nodes.resize(1u);
    wide.packets.resize(packets_of_leaf(bvh.nodes[0]));
    Collapser collapser(bvh, wide, {});
    collapser.collapse_leaf_root();
    wide.depth = collapser.depth();
    return wide;
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
  wide.nodes.resize(total.nodes);
  wide.packets.resize(total.packets);

  Collapser root(bvh, wide, {});
  root.write_node(0u, 1u, slots);
  wide.depth = root.depth();
  // The subtrees write disjoint parts of the arrays, so they may run on
  // other threads.
  std::uint32_t subtree_depth[kWideArity] = {};
  for (std::uint32_t s = 0; s < kWideArity; ++s)
    if (interior(s)) wide.nodes[0].slot[s].child = start[s].nodes;
  auto collapse_subtree = [&](std::uint32_t s) {
    if (!interior(s)) return;
    Collapser collapser(bvh, wide, start[s]);
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
  const bool large = wide.bytes() > kPrefetchTreeBytes;
  if (q.tmin < 0.0f) {
    walk_from<true>(wide, ray, q.parallel_axes, large, collector);
  } else {
    walk_from<false>(wide, ray, q.parallel_axes, large, collector);
  }
}

// The two queries' bodies, inlined into the baseline entry points (the
// public functions below) and into the AVX-512 ones.
SP_ALWAYS_INLINE HitInfo closest_hit_in(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                        float tmin, float tmax) {
  Best best{HitInfo{tmax, SP_INVALID}, bvh.triangles.data()};
  walk(wide, origin, dir, tmin, tmax, best);
  return best.hit;
}

SP_ALWAYS_INLINE shader::HitList nearest_hits_in(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                                 float tmin, float tmax) {
  Nearest nearest{{}, tmax, dir, bvh.triangles.data()};
  nearest.list.count = 0u;
  nearest.list.t[SP_MATTER_MAX_HITS - 1u] = tmax;
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
#if defined(SP_WIDE_AVX512)
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
             __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
#else
      return false;
#endif
  }
  return false;
}

// The walk in use: the fastest this CPU runs, until select_wide_walk.
std::atomic<WideWalk>& selected() {
  static std::atomic<WideWalk> walk{cpu_runs(WideWalk::Avx512) ? WideWalk::Avx512 : WideWalk::Baseline};
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

const char* wide_walk_name(WideWalk walk) { return walk == WideWalk::Avx512 ? "avx512" : "baseline"; }

HitInfo wide_closest_hit(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
#if defined(SP_WIDE_AVX512)
  if (selected_wide_walk() == WideWalk::Avx512) return closest_hit_avx512(wide, bvh, origin, dir, tmin, tmax);
#endif
  return closest_hit_in(wide, bvh, origin, dir, tmin, tmax);
}

shader::HitList wide_nearest_hits(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin,
                                  float tmax) {
#if defined(SP_WIDE_AVX512)
  if (selected_wide_walk() == WideWalk::Avx512) return nearest_hits_avx512(wide, bvh, origin, dir, tmin, tmax);
#endif
  return nearest_hits_in(wide, bvh, origin, dir, tmin, tmax);
}

}  // namespace sp
