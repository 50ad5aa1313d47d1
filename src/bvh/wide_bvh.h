// CPU-only 4-wide BVH, collapsed from the binary sp::Bvh that the GPU
// traverses, so the CPU backend tests four boxes (or four triangles) with one
// SIMD instruction per slab: ~10 wide nodes per cast on scenes/level.gltf
// instead of ~38 binary ones. On CPUs with AVX-512 an 8-wide copy of the
// same tree (three binary levels per node, WideNode8) is walked instead,
// eight boxes per 256-bit instruction; everything below holds for it alike.
//
// References: Wald, Benthin, Boulos, "Getting Rid of Packets: Efficient SIMD
// Single-Ray Traversal using Multi-branching BVHs", IEEE Symposium on
// Interactive Ray Tracing 2008 (4-wide nodes by collapsing a binary tree,
// nearest-first order, a stack of entry distances); Embree's BVH4 works
// alike (Wald et al., "Embree: A Kernel Framework for Efficient CPU Ray
// Tracing", ACM TOG 33(4), 2014).
//
// Same answer as sp_closest_hit (shaders/shared/sp_traverse.h) on every ray,
// triangle and t bit for bit, which the CPU backend needs to stay the GPU's
// reference:
//  - Box test: sp_intersect_box lane by lane (same operations, same
//    margin as sp_box_far_margin, same axis-parallel rule). Taking each axis's entry
//    and exit plane by the sign of inv_dir gives its min/max exactly.
//  - Triangle test: sp_intersect_triangle's Woop arithmetic, operation by
//    operation, on four lanes; IEEE rounding makes each lane bit-identical
//    (the build uses -ffp-contract=off, so no lane fuses a multiply-add).
//  - Visits: the binary walk enters a node when its box passes with the best
//    hit so far, in a fixed order (depth first, nearer child first, left on a
//    tie; entry distances do not depend on the limit). A box contains its
//    descendants' and rounding is monotonic, so a leaf passing implies its
//    ancestors passing: the walk enters leaf L exactly when L's box passes
//    with the best hit of the leaves entered before L. The wide walk enters
//    the same leaves in the same order, so where the box margin hides a hit
//    from the binary walk (the near-ties of test_bvh.cpp) it hides it here
//    too. Ordering slots by their own entry distance alone would not: it
//    changes which hits are known when a box is tested. Hence the fixed
//    two-level (three-level) collapse below rather than Wald's widest-first
//    one: it keeps the binary order computable from the slots.
// tests/test_wide_bvh.cpp compares the two walks on many rays.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh_geometry.h"
#include "bvh/bvh.h"

namespace sp {

// Children per wide node: one SSE register of floats.
inline constexpr std::uint32_t kWideArity = 4;

// What a slot of a wide node leads to:
//
//   count | child                        | box in WideNode::bounds
//   ------+------------------------------+------------------------
//   0     | index into WideBvh::nodes    | the binary node's box
//   n > 0 | first of n TrianglePackets   | the binary leaf's box
//   0     | 0 (unused slot)              | NaN: never hit (below)
struct WideSlot {
  std::uint32_t child;
  std::uint32_t count;
};

// One node, 128 bytes (two cache lines): the binary node N it replaces has
// children A (left) and B; slots 0 and 1 are A's children, or A itself in
// slot 0 when A is a leaf; slots 2 and 3 the same for B. Slot i is lane i of
// every Vec4.
//
// Unused slots (1 or 3, beside a leaf) hold NaN bounds. Every slab distance
// is then NaN, the traversal's min/max keep the NaN (it is always their
// second operand) and `tnear <= tfar` is false, so an unused slot misses
// whatever the ray and its (tmin, tmax] are.
struct alignas(64) WideNode {
  Vec4 bounds[6];  // lo.x lo.y lo.z hi.x hi.y hi.z, one lane per slot
  WideSlot slot[kWideArity];
};
static_assert(sizeof(WideNode) == 128);

// Four triangles of one leaf as structure of arrays, 160 bytes. A leaf of n
// triangles owns ceil(n / 4) consecutive packets. A padding lane has all
// three vertices at (0, 0, 0) and triangle SP_INVALID: u = v = w = 0
// exactly, so the Woop test's det is 0 and the lane never hits, just as a
// degenerate triangle collapsed by make_bvh_triangle never does.
struct alignas(32) TrianglePacket {
  Vec4 v[3][3];                        // v[vertex][axis], copied from Bvh::triangles
  std::uint32_t triangle[kWideArity];  // leaf-order index into Bvh::triangles
};
static_assert(sizeof(TrianglePacket) == 160);

// Children per node of the 8-wide tree that the AVX-512 walk takes
// (wide8_walk.cpp): three binary levels per node, so a descent through a
// finely tessellated wall takes a third fewer nodes than four at a time.
inline constexpr std::uint32_t kWide8Arity = 8;

// One node of the 8-wide tree, 256 bytes (four cache lines). It replaces
// binary interior node N: slot 4g + 2h + k holds child k of grandchild h of
// child g of N (0: left); a grandchild that is a leaf sits alone in slot
// 4g + 2h, a child that is a leaf alone in slot 4g. Unused slots hold NaN
// bounds and miss, as in WideNode. Leaf slots point into WideBvh::packets,
// which both trees share. Bounds are float rows of eight lanes: one 256-bit
// register per plane.
struct alignas(64) WideNode8 {
  float bounds[6][kWide8Arity];  // lo.x lo.y lo.z hi.x hi.y hi.z, one lane per slot
  WideSlot slot[kWide8Arity];
};
static_assert(sizeof(WideNode8) == 256);

// Walks of trees larger than this prefetch each node's children while its
// boxes are tested (wide_bvh.cpp, prefetch_slots). On the 2-vCPU AMD EPYC of
// bench/RESULTS.md (1 MiB L2 per core) prefetching made trees of 1-2 MiB
// (10k-17k triangles) 3-7 % slower, and larger ones as fast or faster
// (section 13: level_big's 27 MiB 1.0x, 100k triangles 1.36x, 1M 1.5x).
inline constexpr std::size_t kPrefetchTreeBytes = std::size_t{4} << 20;

// The 8-wide tree is built only for trees whose 4-wide nodes and packets
// take at most this much. Past it the walk waits on memory more than on
// its own instructions, and the 4-wide walk, reading two cache lines per
// node rather than four and prefetching, was faster on the benchmark VM:
// at 1M triangles (65 MB) 12-15 % faster on one thread; at 252k (15 MB)
// the 8-wide walk was 6 % faster (bench/RESULTS.md section 23).
inline constexpr std::size_t kWide8MaxTreeBytes = std::size_t{32} << 20;

struct WideBvh {
  LargeArray<WideNode> nodes;  // nodes[0] is the root; children after their parent
  LargeArray<TrianglePacket> packets;
  std::uint32_t depth = 0;  // wide levels, root included; <= the binary depth
  // The 8-wide tree over the same packets, built where this CPU runs the
  // 8-wide walk (wide_walk_available) and wide4_bytes() is at most
  // kWide8MaxTreeBytes; empty elsewhere.
  LargeArray<WideNode8> nodes8;
  std::uint32_t depth8 = 0;  // its levels, root included

  // The 4-wide tree's nodes and packets, and all of it.
  std::size_t wide4_bytes() const { return nodes.size() * sizeof(WideNode) + packets.size() * sizeof(TrianglePacket); }
  std::size_t bytes() const { return wide4_bytes() + nodes8.size() * sizeof(WideNode8); }
};

class BuildWorkers;

// Collapses `bvh` (wide_collapse.cpp); given `workers`, the packets, the
// 4-wide tree's subtrees and the 8-wide tree are offered to its threads (the
// result is the same either way). Packets follow their leaves' order in
// bvh.nodes. Preconditions, as build_bvh makes the tree: bvh.nodes is not
// empty; every node but the root is the child of exactly one node, which
// comes before it (the layout is one forward scan); and every interior
// node's box is exactly the union of its children's (the traversal derives
// a parent's entry distance from its children's).
WideBvh build_wide_bvh(const Bvh& bvh, BuildWorkers* workers = nullptr);

// sp_closest_hit's answer for `bvh`, from `wide` = build_wide_bvh(bvh).
HitInfo wide_closest_hit(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

// sp_nearest_hits' answer (the matter query's list), the same way: the walk
// is the same with the list's limit in place of the best hit.
shader::HitList wide_nearest_hits(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin,
                                  float tmax);

// sp_segment_blocked's answer (is anything in (tmin, tmax]?), the same way:
// the closest-hit walk, ended by the first hit it finds.
bool wide_segment_blocked(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

// The compiled copies of the walk above. Every one gives the same answer
// bit for bit; tests/test_wide_bvh.cpp checks each this CPU runs.
enum class WideWalk {
  // The 4-wide tree: SSE2 on x86-64, NEON on Arm, scalar lanes elsewhere.
  Baseline,
  // The 4-wide tree, the same source compiled for x86-64 with AVX-512
  // F/VL/BW/DQ and AVX2/BMI2 (GCC and Clang builds): EVEX encodings and 32
  // vector registers.
  Avx512,
  // The 8-wide tree (nodes8) in 256-bit registers, on the same CPUs and
  // builds as Avx512; on a tree without nodes8 (a large one), Avx512.
  Avx512Wide8,
};

// Whether this build has `walk` and this CPU runs it.
bool wide_walk_available(WideWalk walk);
// The walk wide_closest_hit and wide_nearest_hits use: at first the fastest
// available. select_wide_walk changes it for the whole process (for tests
// and benchmarks; not while other threads cast) and returns false, changing
// nothing, when `walk` is not available.
WideWalk selected_wide_walk();
bool select_wide_walk(WideWalk walk);
const char* wide_walk_name(WideWalk walk);

}  // namespace sp
