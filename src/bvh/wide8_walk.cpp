// The 8-wide tree and its single-ray walk in 256-bit AVX-512VL registers;
// see wide_bvh.h (WideNode8, and what every wide walk promises) and
// bench/RESULTS.md section 23 for what it measured.
//
// The walk is the 4-wide one of wide_bvh.cpp, eight slots at a time: the
// same box test lane by lane, the same packets and triangle test, and the
// binary walk's order over three levels instead of two. The intrinsics are
// compiled for AVX-512 through target attributes only, so this file builds
// with the baseline flags and runs its code only where cpu_runs() says so.
#include "bvh/wide8_walk.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <limits>

#include "bvh/wide_walk_parts.h"

#if defined(SP_WIDE_AVX512)
#include <immintrin.h>
#endif

namespace sp::wide8 {

#if !defined(SP_WIDE_AVX512)

bool cpu_runs() { return false; }
void collapse(const Bvh&, std::span<const std::uint32_t>, std::uint32_t, WideBvh&) { assert(false); }
HitInfo closest_hit(const WideBvh&, const Bvh&, glm::vec3, glm::vec3, float, float tmax) {
  assert(false);
  return HitInfo{tmax, SP_INVALID, 0u};
}
shader::HitList nearest_hits(const WideBvh&, const Bvh&, glm::vec3, glm::vec3, float, float) {
  assert(false);
  return {};
}
bool segment_blocked(const WideBvh&, glm::vec3, glm::vec3, float, float) {
  assert(false);
  return true;
}

#else

namespace {

using namespace wide_walk;

// ---------------------------------------------------------------- collapse

// The slots of the 8-wide node that replaces binary interior node `binary`
// (the layout of WideNode8): slots 4g to 4g + 3 are the 4-wide node's
// slots of child g, or child g alone in slot 4g when it is a leaf.
void slots_of(const Bvh& bvh, std::uint32_t binary, std::uint32_t (&slots)[kWide8Arity]) {
  std::fill(std::begin(slots), std::end(slots), SP_INVALID);
  for (std::uint32_t g = 0; g < 2u; ++g) {
    const std::uint32_t child = bvh.nodes[binary].left_or_first + g;
    if (bvh.nodes[child].count > 0u) {
      slots[4u * g] = child;
      continue;
    }
    std::uint32_t quad[kWideArity];
    wide_slots(bvh, child, quad);
    std::copy(std::begin(quad), std::end(quad), slots + 4u * g);
  }
}

class Collapser8 {
 public:
  Collapser8(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, WideBvh& wide)
      : bvh_(bvh), leaf_packets_(leaf_packets), wide_(wide) {}

  // Binary interior node `binary` and its subtree, depth first, children
  // after their parent; returns the node's index.
  std::uint32_t collapse(std::uint32_t binary, std::uint32_t level) {
    wide_.depth8 = std::max(wide_.depth8, level);
    std::uint32_t slots[kWide8Arity];
    slots_of(bvh_, binary, slots);
    const auto index = static_cast<std::uint32_t>(wide_.nodes8.size());
    wide_.nodes8.push_back(empty_node());
    for (std::uint32_t s = 0; s < kWide8Arity; ++s)
      if (slots[s] != SP_INVALID) fill_slot(index, s, slots[s]);
    for (std::uint32_t s = 0; s < kWide8Arity; ++s) {
      if (is_interior_slot(bvh_, slots[s])) {
        const std::uint32_t child = collapse(slots[s], level + 1u);
        wide_.nodes8[index].slot[s].child = child;
      }
    }
    return index;
  }

  // The root when it is a single leaf: one slot.
  void collapse_leaf_root() {
    wide_.depth8 = 1u;
    wide_.nodes8.push_back(empty_node());
    fill_slot(0u, 0u, 0u);
  }

 private:
  static WideNode8 empty_node() {
    WideNode8 node{};
    for (auto& row : node.bounds) std::fill(std::begin(row), std::end(row), std::numeric_limits<float>::quiet_NaN());
    return node;
  }

  void fill_slot(std::uint32_t index, std::uint32_t slot, std::uint32_t binary) {
    const BvhNode& n = bvh_.nodes[binary];
    WideNode8& node = wide_.nodes8[index];
    for (int a = 0; a < 3; ++a) {
      node.bounds[a][slot] = n.bmin[a];
      node.bounds[3 + a][slot] = n.bmax[a];
    }
    if (n.count > 0u) node.slot[slot] = WideSlot{leaf_packets_[binary], packets_of_leaf(n)};
  }

  const Bvh& bvh_;
  std::span<const std::uint32_t> leaf_packets_;
  WideBvh& wide_;
};

// --------------------------------------------------------------- traversal

#define SP_TARGET_WIDE8 SP_TARGET_AVX512

// A node pushes at most seven slots, and a path holds at most
// SP_BVH_MAX_DEPTH / 3 + 1 nodes of three binary levels each.
constexpr std::uint32_t kStackSize = (kWide8Arity - 1u) * (SP_BVH_MAX_DEPTH / 3u + 1u);

// Nodes this many levels below the root or deeper pick the one slot hit by
// its index; shallower ones by branches (predicted_slot8). Near the root
// the rays of one source take the same few paths, which the branch
// predictor learns, and the core loads the guessed node while the box test
// runs (as the 4-wide walk does everywhere, bench/RESULTS.md section 20).
// Deeper, in the descent through a tessellated wall, the slot hit is close
// to a random one of eight: a wrong guess costs more than waiting for the
// test (section 23).
constexpr std::uint32_t kPredictedLevels = 2;

// Per-ray constants in 256-bit registers.
struct Ray8 {
  __m256 origin[3];
  __m256 inv_dir[3];
  __m256 tmin;
  std::size_t entry_plane[3];  // byte offsets of each axis's planes in WideNode8::bounds
  std::size_t exit_plane[3];
};

SP_TARGET_WIDE8 SP_ALWAYS_INLINE Ray8 make_ray8(const shader::RayQuery& q) {
  Ray8 r;
  for (int a = 0; a < 3; ++a) {
    r.origin[a] = _mm256_set1_ps(q.origin[a]);
    r.inv_dir[a] = _mm256_set1_ps(q.inv_dir[a]);
    // The plane by the sign of inv_dir, as make_wide_ray.
    const std::size_t lo = static_cast<std::size_t>(a) * sizeof(WideNode8::bounds[0]);
    const std::size_t hi = lo + 3u * sizeof(WideNode8::bounds[0]);
    const bool negative = q.inv_dir[a] < 0.0f;
    r.entry_plane[a] = negative ? hi : lo;
    r.exit_plane[a] = negative ? lo : hi;
  }
  r.tmin = _mm256_set1_ps(q.tmin);
  return r;
}

SP_TARGET_WIDE8 SP_ALWAYS_INLINE __m256 plane8(const WideNode8& node, std::size_t offset) {
  return _mm256_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(node.bounds) + offset));
}

// far_margin on eight lanes: _mm256_max_ps returns its second operand on an
// unordered lane, as vmax does, so NaN lanes stay NaN.
template <bool kBehind>
SP_TARGET_WIDE8 SP_ALWAYS_INLINE __m256 far_margin8(__m256 tfar) {
  const __m256 ahead = _mm256_mul_ps(tfar, _mm256_set1_ps(kBoxMargin));
  if (!kBehind) return ahead;
  return _mm256_max_ps(_mm256_mul_ps(tfar, _mm256_set1_ps(kBoxMarginBehind)), ahead);
}

// node.slot[lane] for one-hot `lane_bit`, chosen by three branches (see
// predicted_slot in wide_bvh.cpp).
SP_ALWAYS_INLINE WideSlot predicted_slot8(const WideNode8& node, unsigned lane_bit) {
  if (lane_bit < 16u) {
    if (lane_bit < 4u) {
      if (lane_bit == 1u) {
        SP_KEEP_BRANCH();
        return node.slot[0];
      }
      SP_KEEP_BRANCH();
      return node.slot[1];
    }
    if (lane_bit == 4u) {
      SP_KEEP_BRANCH();
      return node.slot[2];
    }
    SP_KEEP_BRANCH();
    return node.slot[3];
  }
  if (lane_bit < 64u) {
    if (lane_bit == 16u) {
      SP_KEEP_BRANCH();
      return node.slot[4];
    }
    SP_KEEP_BRANCH();
    return node.slot[5];
  }
  if (lane_bit == 64u) {
    SP_KEEP_BRANCH();
    return node.slot[6];
  }
  return node.slot[7];
}

// The slots hit, in the binary walk's order: at each of the three levels
// a side whose two halves both hold hits enters the half with the smaller
// entry distance first, the left on a tie. A half's entry distance is
// sp_intersect_box's tnear for the binary node it stands for: its box is
// the union of its slots' (build_bvh's bounds are exact) and rounding is
// monotonic, so on each axis its entry plane's distance is the smallest of
// its slots' (first_pair in wide_bvh.cpp, one level up). A half's first
// slot is always used, so the NaN of an unused one (the first operand of
// _mm256_min_ps) never wins. order_hits fills an Ordered with them.
struct Ordered {
  std::uint32_t slot[kWide8Arity] = {};
  std::uint32_t count = 0;
};

SP_TARGET_WIDE8 SP_ALWAYS_INLINE void order_hits(const Ray8& r, const __m256 (&entry)[3], const float (&tnear)[8],
                                                 unsigned hits, Ordered& out) {
  __m256 pair_entry = r.tmin, quad_entry = r.tmin;
  for (int a = 0; a < 3; ++a) {
    const __m256 pairs = _mm256_min_ps(_mm256_permute_ps(entry[a], 0xB1), entry[a]);  // lanes 2i hold pair i's
    const __m256 quads = _mm256_min_ps(_mm256_permute_ps(pairs, 0x4E), pairs);        // lanes 4i hold quad i's
    pair_entry = _mm256_max_ps(pair_entry, pairs);
    quad_entry = _mm256_max_ps(quad_entry, quads);
  }
  alignas(32) float pair_t[8], quad_t[8];
  _mm256_store_ps(pair_t, pair_entry);
  _mm256_store_ps(quad_t, quad_entry);

  auto add_pair = [&](std::uint32_t p) {
    const unsigned in = (hits >> p) & 3u;
    if (in == 3u) {
      const std::uint32_t s = tnear[p] <= tnear[p + 1u] ? p : p + 1u;
      out.slot[out.count++] = s;
      out.slot[out.count++] = s ^ 1u;
    } else if (in != 0u) {
      out.slot[out.count++] = p + (in >> 1u);
    }
  };
  auto add_quad = [&](std::uint32_t q) {
    const unsigned in = (hits >> q) & 15u;
    if ((in & 3u) != 0u && (in & 12u) != 0u) {
      const std::uint32_t first = pair_t[q] <= pair_t[q + 2u] ? q : q + 2u;
      add_pair(first);
      add_pair(first ^ 2u);
    } else {
      add_pair((in & 3u) != 0u ? q : q + 2u);
    }
  };
  if ((hits & 15u) != 0u && (hits & 240u) != 0u) {
    const std::uint32_t first = quad_t[0] <= quad_t[4] ? 0u : 4u;
    add_quad(first);
    add_quad(first ^ 4u);
  } else {
    add_quad((hits & 15u) != 0u ? 0u : 4u);
  }
}

template <bool kParallel, bool kBehind, class Collector>
SP_TARGET_WIDE8 SP_ALWAYS_INLINE void traverse8(const WideBvh& wide, const WideRay& ray4, const Ray8& r,
                                                std::uint32_t parallel, Collector& best) {
  // A slot that waits: its box's entry distance, and its node's level.
  struct Entry {
    float t;
    WideSlot slot;
    std::uint32_t level;
  };
  Entry stack[kStackSize];
  std::uint32_t size = 0;
  WideSlot item{0u, 0u};  // the root
  std::uint32_t level = 0;
  const WideNode8* nodes = wide.nodes8.data();
  const TrianglePacket* packets = wide.packets.data();

  for (;;) {
    if (item.count == 0u) {
      const WideNode8& node = nodes[item.child];
      __m256 entry[3], exit[3];
      for (int a = 0; a < 3; ++a) {
        entry[a] = _mm256_mul_ps(_mm256_sub_ps(plane8(node, r.entry_plane[a]), r.origin[a]), r.inv_dir[a]);
        exit[a] = _mm256_mul_ps(_mm256_sub_ps(plane8(node, r.exit_plane[a]), r.origin[a]), r.inv_dir[a]);
        if (kParallel && (parallel & (1u << a))) {  // a ray inside the slab never leaves it
          const __mmask8 inside = _mm256_cmp_ps_mask(_mm256_load_ps(node.bounds[a]), r.origin[a], _CMP_LE_OQ) &
                                  _mm256_cmp_ps_mask(r.origin[a], _mm256_load_ps(node.bounds[3 + a]), _CMP_LE_OQ);
          exit[a] = _mm256_mask_blend_ps(inside, exit[a], _mm256_set1_ps(SP_FAR));
        }
      }
      // The 4-wide walk's min/max, operand for operand (NaN lanes stay NaN).
      const __m256 tnear = _mm256_max_ps(_mm256_max_ps(entry[0], entry[1]), _mm256_max_ps(r.tmin, entry[2]));
      const __m256 tfar =
          _mm256_min_ps(_mm256_min_ps(exit[0], exit[1]), _mm256_min_ps(_mm256_set1_ps(best.limit()), exit[2]));
      const unsigned hits = _mm256_cmp_ps_mask(tnear, far_margin8<kBehind>(tfar), _CMP_LE_OQ);
      if (hits != 0u) {
        ++level;
        if ((hits & (hits - 1u)) == 0u) {  // one hit, the common case
          item = level <= kPredictedLevels ? predicted_slot8(node, hits) : node.slot[std::countr_zero(hits)];
          continue;
        }
        alignas(32) float t[8];
        _mm256_store_ps(t, tnear);
        Ordered order;
        order_hits(r, entry, t, hits, order);
        // Pushed in reverse, so that they pop in order.
        for (std::uint32_t i = order.count - 1u; i > 0u; --i) {
          assert(size < kStackSize);
          stack[size++] = Entry{t[order.slot[i]], node.slot[order.slot[i]], level};
        }
        item = node.slot[order.slot[0]];
        continue;
      }
    } else {
      if (!best.enter_leaf(item.count)) return;
      intersect_packets(ray4, packets + item.child, item.count, best);
    }
    if (!pop_live<kBehind>(stack, size, best.limit())) return;
    item = stack[size].slot;
    level = stack[size].level;
  }
}

template <class Collector>
SP_TARGET_WIDE8 SP_ALWAYS_INLINE void walk8(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin,
                                            float tmax, Collector& collector) {
  const shader::RayQuery q = shader::sp_make_query(origin, dir, tmin, tmax);
  const WideRay ray4 = make_wide_ray(q);  // for the packets
  const Ray8 ray = make_ray8(q);
  const bool behind = q.tmin < 0.0f;
  if (q.parallel_axes != 0u) {
    if (behind) {
      traverse8<true, true>(wide, ray4, ray, q.parallel_axes, collector);
    } else {
      traverse8<true, false>(wide, ray4, ray, q.parallel_axes, collector);
    }
  } else if (behind) {
    traverse8<false, true>(wide, ray4, ray, 0u, collector);
  } else {
    traverse8<false, false>(wide, ray4, ray, 0u, collector);
  }
}

}  // namespace

bool cpu_runs() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
         __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
}

void collapse(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, std::uint32_t nodes, WideBvh& wide) {
  assert(!bvh.nodes.empty());
  wide.nodes8.clear();
  wide.depth8 = 0;
  // Sized first, so that the array takes what the tree needs: the upper
  // bound, one node per binary interior node, is up to seven times that.
  wide.nodes8.reserve(std::max(nodes, 1u));
  Collapser8 collapser(bvh, leaf_packets, wide);
  if (bvh.nodes[0].count > 0u) {
    collapser.collapse_leaf_root();
  } else {
    collapser.collapse(0u, 1u);
  }
}

SP_TARGET_WIDE8 HitInfo closest_hit(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin,
                                    float tmax) {
  Best best = Best::start(bvh, tmax);
  walk8(wide, origin, dir, tmin, tmax, best);
  return best.hit;
}

SP_TARGET_WIDE8 shader::HitList nearest_hits(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir,
                                             float tmin, float tmax) {
  Nearest nearest = Nearest::start(bvh, dir, tmax);
  walk8(wide, origin, dir, tmin, tmax, nearest);
  return nearest.list;
}

SP_TARGET_WIDE8 bool segment_blocked(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) {
  Blocker blocker = Blocker::start(tmax);
  walk8(wide, origin, dir, tmin, tmax, blocker);
  return blocker.blocked;
}

#endif

}  // namespace sp::wide8
