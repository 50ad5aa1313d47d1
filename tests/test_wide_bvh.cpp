// Tests of the CPU-only 4-wide and 8-wide BVHs (src/bvh/wide_bvh.h): the
// collapsed trees' invariants, and their traversal against the binary one shared with the
// GPU (shaders/shared/sp_traverse.h). The two must agree exactly, on every
// ray: the same triangle and the same t, bit for bit. No mismatch class is
// tolerated: the wide traversal enters the binary walk's leaves in the binary
// walk's order with the same box test, so even the rare hit that the box
// margin hides from the binary walk (the near-ties of test_bvh.cpp) is hidden
// from both alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/wide_bvh.h"
#include "bvh/bvh.h"
#include "sp_traverse.h"
#include "support/bvh_scenes.h"

namespace {

using namespace sp::test;

constexpr float kInf = std::numeric_limits<float>::infinity();

// ------------------------------------------------------------- invariants

// Walks the binary tree and the wide tree together. Checks the slot layout
// that the traversal's ordering relies on (slots 2g, 2g + 1: the children of
// child g, or child g alone in slot 2g), bounds copied exactly, each slot's
// box inside its parent slot's box, unused slots, and the packets: every
// triangle in exactly one lane, in leaf order, with its vertices.
class WideChecker {
 public:
  explicit WideChecker(const sp::Bvh& bvh) : bvh_(bvh), wide_(*bvh.wide) {
    node_refs_.assign(wide_.nodes.size(), 0);
    packet_refs_.assign(wide_.packets.size(), 0);
    triangle_refs_.assign(bvh.triangles.size(), 0);
  }

  void run() {
    ASSERT_FALSE(wide_.nodes.empty());
    node_refs_[0] = 1;
    const sp::BvhNode& root = bvh_.nodes[0];
    if (root.count > 0u) {  // a leaf root: one wide node, one slot
      EXPECT_EQ(wide_.nodes.size(), 1u);
      check_node(0u, {0u, SP_INVALID, SP_INVALID, SP_INVALID}, root, 1u);
    } else {
      check_interior(0u, 0u, 1u);
    }
    EXPECT_EQ(deepest_, wide_.depth);
    EXPECT_LE(wide_.depth, bvh_.depth);
    EXPECT_TRUE(std::all_of(node_refs_.begin(), node_refs_.end(), [](int r) { return r == 1; }))
        << "a wide node is unreachable or shared";
    EXPECT_TRUE(std::all_of(packet_refs_.begin(), packet_refs_.end(), [](int r) { return r == 1; }))
        << "a packet is unreachable or shared";
    EXPECT_TRUE(std::all_of(triangle_refs_.begin(), triangle_refs_.end(), [](int r) { return r == 1; }))
        << "a triangle is not in exactly one packet lane";
  }

 private:
  // Wide node `w` stands for binary interior node `binary`.
  void check_interior(std::uint32_t w, std::uint32_t binary, std::uint32_t level) {
    std::uint32_t slots[4] = {SP_INVALID, SP_INVALID, SP_INVALID, SP_INVALID};
    for (std::uint32_t g = 0; g < 2u; ++g) {
      const std::uint32_t child = bvh_.nodes[binary].left_or_first + g;
      const sp::BvhNode& n = bvh_.nodes[child];
      slots[2u * g] = n.count > 0u ? child : n.left_or_first;
      if (n.count == 0u) slots[2u * g + 1u] = n.left_or_first + 1u;
    }
    check_node(w, slots, bvh_.nodes[binary], level);
  }

  void check_node(std::uint32_t w, const std::uint32_t (&slots)[4], const sp::BvhNode& parent, std::uint32_t level) {
    deepest_ = std::max(deepest_, level);
    const sp::WideNode& node = wide_.nodes[w];
    for (std::uint32_t s = 0; s < 4u; ++s) {
      if (slots[s] == SP_INVALID) {
        for (const sp::Vec4& b : node.bounds) EXPECT_TRUE(std::isnan(b[s])) << "unused slot " << s << " of " << w;
        EXPECT_EQ(node.slot[s].child, 0u);
        EXPECT_EQ(node.slot[s].count, 0u);
        continue;
      }
      const sp::BvhNode& n = bvh_.nodes[slots[s]];
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(node.bounds[a][s], n.bmin[a]) << "slot " << s << " of wide node " << w;
        EXPECT_EQ(node.bounds[3 + a][s], n.bmax[a]) << "slot " << s << " of wide node " << w;
        EXPECT_LE(parent.bmin[a], node.bounds[a][s]) << "slot " << s << " outside its parent, wide node " << w;
        EXPECT_LE(node.bounds[3 + a][s], parent.bmax[a]) << "slot " << s << " outside its parent, wide node " << w;
      }
      if (n.count > 0u) {
        check_leaf(node.slot[s], n);
      } else {
        EXPECT_EQ(node.slot[s].count, 0u);
        ASSERT_LT(node.slot[s].child, wide_.nodes.size());
        EXPECT_GT(node.slot[s].child, w) << "children are stored after their parent";
        ++node_refs_[node.slot[s].child];
        check_interior(node.slot[s].child, slots[s], level + 1u);
      }
    }
  }

  void check_leaf(sp::WideSlot slot, const sp::BvhNode& leaf) {
    EXPECT_EQ(slot.count, (leaf.count + 3u) / 4u);
    ASSERT_LE(std::size_t{slot.child} + slot.count, wide_.packets.size());
    for (std::uint32_t j = 0; j < slot.count; ++j) {
      const sp::TrianglePacket& p = wide_.packets[slot.child + j];
      ++packet_refs_[slot.child + j];
      for (std::uint32_t lane = 0; lane < 4u; ++lane) {
        const std::uint32_t i = leaf.left_or_first + 4u * j + lane;
        if (4u * j + lane >= leaf.count) {  // padding: never hits (det == 0)
          EXPECT_EQ(p.triangle[lane], SP_INVALID);
          for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) EXPECT_EQ(p.v[k][a][lane], 0.0f);
          continue;
        }
        ASSERT_EQ(p.triangle[lane], i) << "packets keep leaf order";
        ++triangle_refs_[i];
        const sp::BvhTriangle& t = bvh_.triangles[i];
        const vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k)
          for (int a = 0; a < 3; ++a) EXPECT_EQ(p.v[k][a][lane], v[k][a]);
      }
    }
  }

  const sp::Bvh& bvh_;
  const sp::WideBvh& wide_;
  std::vector<int> node_refs_, packet_refs_, triangle_refs_;
  std::uint32_t deepest_ = 0;
};

// The 8-wide tree, built where this CPU runs its walk: slot 4g + 2h + k
// holds child k of grandchild h of child g (a leaf alone in the first slot
// of its range), bounds copied exactly, unused slots NaN, leaf slots on the
// packets the 4-wide tree made for the same leaf, every node reached once.
class Wide8Checker {
 public:
  explicit Wide8Checker(const sp::Bvh& bvh) : bvh_(bvh), wide_(*bvh.wide) {}

  void run() {
    ASSERT_EQ(wide_.nodes8.empty(),
              !sp::wide_walk_available(sp::WideWalk::Avx512Wide8) || wide_.wide4_bytes() > sp::kWide8MaxTreeBytes)
        << "the 8-wide tree exists exactly where its walk runs, up to its size";
    if (wide_.nodes8.empty()) return;
    node_refs_.assign(wide_.nodes8.size(), 0);
    node_refs_[0] = 1;
    std::uint32_t slots[8];
    std::fill(std::begin(slots), std::end(slots), SP_INVALID);
    if (bvh_.nodes[0].count > 0u) {
      slots[0] = 0u;
      check_node(0u, slots, 1u);
    } else {
      check_interior(0u, 0u, 1u);
    }
    EXPECT_EQ(deepest_, wide_.depth8);
    EXPECT_TRUE(std::all_of(node_refs_.begin(), node_refs_.end(), [](int r) { return r == 1; }))
        << "an 8-wide node is unreachable or shared";
  }

 private:
  void check_interior(std::uint32_t w, std::uint32_t binary, std::uint32_t level) {
    std::uint32_t slots[8];
    std::fill(std::begin(slots), std::end(slots), SP_INVALID);
    for (std::uint32_t g = 0; g < 2u; ++g) {
      const std::uint32_t child = bvh_.nodes[binary].left_or_first + g;
      if (bvh_.nodes[child].count > 0u) {
        slots[4u * g] = child;
        continue;
      }
      for (std::uint32_t h = 0; h < 2u; ++h) {
        const std::uint32_t grandchild = bvh_.nodes[child].left_or_first + h;
        const sp::BvhNode& n = bvh_.nodes[grandchild];
        if (n.count > 0u) {
          slots[4u * g + 2u * h] = grandchild;
        } else {
          slots[4u * g + 2u * h] = n.left_or_first;
          slots[4u * g + 2u * h + 1u] = n.left_or_first + 1u;
        }
      }
    }
    check_node(w, slots, level);
  }

  void check_node(std::uint32_t w, const std::uint32_t (&slots)[8], std::uint32_t level) {
    deepest_ = std::max(deepest_, level);
    const sp::WideNode8& node = wide_.nodes8[w];
    for (std::uint32_t s = 0; s < 8u; ++s) {
      if (slots[s] == SP_INVALID) {
        for (const auto& row : node.bounds) EXPECT_TRUE(std::isnan(row[s])) << "unused slot " << s << " of " << w;
        continue;
      }
      const sp::BvhNode& n = bvh_.nodes[slots[s]];
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(node.bounds[a][s], n.bmin[a]) << "slot " << s << " of 8-wide node " << w;
        EXPECT_EQ(node.bounds[3 + a][s], n.bmax[a]) << "slot " << s << " of 8-wide node " << w;
      }
      if (n.count > 0u) {
        EXPECT_EQ(node.slot[s].count, (n.count + 3u) / 4u);
        ASSERT_LT(node.slot[s].child, wide_.packets.size());
        EXPECT_EQ(wide_.packets[node.slot[s].child].triangle[0], n.left_or_first)
            << "slot " << s << " of 8-wide node " << w << " leads to its leaf's packets";
      } else {
        EXPECT_EQ(node.slot[s].count, 0u);
        ASSERT_LT(node.slot[s].child, wide_.nodes8.size());
        EXPECT_GT(node.slot[s].child, w) << "children are stored after their parent";
        ++node_refs_[node.slot[s].child];
        check_interior(node.slot[s].child, slots[s], level + 1u);
      }
    }
  }

  const sp::Bvh& bvh_;
  const sp::WideBvh& wide_;
  std::vector<int> node_refs_;
  std::uint32_t deepest_ = 0;
};

void check_wide_invariants(const sp::Bvh& bvh) {
  ASSERT_TRUE(bvh.wide) << "build_bvh makes the wide tree";
  WideChecker(bvh).run();
  Wide8Checker(bvh).run();
}

// -------------------------------------------------------------- traversal

// Spreads the rays over the (tmin, tmax] windows the simulation and the
// edge cases use: as given, tmax = SP_FAR (the traversal must still treat
// t == SP_FAR as a miss), tmin = SP_EPSILON (reflected rays), a finite tmax,
// an unbounded window (tmin = -inf, tmax = +inf: hits behind the origin
// count, and unused slots must miss whatever the limit), and the matter
// query's look-back (tmin = -SP_CONTACT_TOLERANCE: boxes behind the origin
// take the other margin, sp_box_far_margin).
std::vector<Ray> vary_windows(std::vector<Ray> rays, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    Ray& r = rays[i];
    switch (i % 8) {
      case 1:
        r.tmax = SP_FAR;
        break;
      case 2:
        r.tmin = SP_EPSILON;
        break;
      case 3:
        r.tmax = 0.25f + 8.0f * u(rng);
        break;
      case 4:
        r.tmin = SP_EPSILON;
        r.tmax = SP_FAR;
        break;
      case 5:
        r.tmin = -kInf;
        r.tmax = kInf;
        break;
      case 6:  // the matter query's look-back
        r.tmin = -SP_CONTACT_TOLERANCE;
        break;
      default:
        break;
    }
  }
  return rays;
}

struct Agreement {
  std::size_t rays = 0;
  std::size_t hits = 0;
  std::size_t cut_short = 0;        // closest-hit casts past SP_MAX_CAST_PACKETS
  std::size_t lists_cut_short = 0;  // nearest-hits lists likewise
  std::size_t blocked = 0;          // segments the binary occlusion walk calls blocked
};

// The matter query's lists, entry by entry, bit for bit.
bool same_list(const sp::shader::HitList& a, const sp::shader::HitList& b) {
  if (a.cut_short != b.cut_short) return false;
  if (a.cut_short != 0u) return true;  // neither list is to be read
  if (a.count != b.count) return false;
  for (std::uint32_t k = 0; k < a.count; ++k)
    if (a.triangle[k] != b.triangle[k] || a.key[k] != b.key[k] ||
        std::bit_cast<std::uint32_t>(a.t[k]) != std::bit_cast<std::uint32_t>(b.t[k]))
      return false;
  return true;
}

// Selects a compiled walk (wide_bvh.h) for a scope, then puts back the one
// that was in use.
class WalkSelection {
 public:
  explicit WalkSelection(sp::WideWalk walk) : before_(sp::selected_wide_walk()) {
    selected_ = sp::select_wide_walk(walk);
  }
  ~WalkSelection() { sp::select_wide_walk(before_); }
  bool selected() const { return selected_; }

 private:
  sp::WideWalk before_;
  bool selected_ = false;
};

// expect_same_as_binary (below) for the walk selected now.
Agreement expect_selected_walk_same_as_binary(const sp::Bvh& bvh, const std::vector<Ray>& rays) {
  Agreement agreement;
  std::size_t failures = 0;
  std::size_t list_failures = 0;
  std::size_t blocked_failures = 0;
  for (const Ray& r : rays) {
    const sp::shader::HitList wide_list = sp::nearest_hits(bvh, r.origin, r.dir, r.tmin, r.tmax);
    sp::shader::HitList binary_list;
    sp::shader::sp_nearest_hits(bvh.nodes.data(), bvh.triangles.data(), r.origin, r.dir, r.tmin, r.tmax, binary_list);
    if (!same_list(wide_list, binary_list) && ++list_failures <= 5) {
      ADD_FAILURE() << std::hexfloat << "nearest hits of ray o=(" << r.origin.x << ", " << r.origin.y << ", "
                    << r.origin.z << ") d=(" << r.dir.x << ", " << r.dir.y << ", " << r.dir.z << ") t in (" << r.tmin
                    << ", " << r.tmax << "]: wide " << wide_list.count << " hits, binary " << binary_list.count;
    }
    const sp::HitInfo wide = sp::wide_closest_hit(*bvh.wide, bvh, r.origin, r.dir, r.tmin, r.tmax);
    const sp::HitInfo binary =
        sp::shader::sp_closest_hit(bvh.nodes.data(), bvh.triangles.data(), r.origin, r.dir, r.tmin, r.tmax);
    const sp::HitInfo dispatched = sp::closest_hit(bvh, r.origin, r.dir, r.tmin, r.tmax);
    ++agreement.rays;
    agreement.hits += binary.triangle != SP_INVALID;
    agreement.cut_short += binary.cut_short;
    agreement.lists_cut_short += binary_list.cut_short;
    const bool same = wide.triangle == binary.triangle && wide.cut_short == binary.cut_short &&
                      std::bit_cast<std::uint32_t>(wide.t) == std::bit_cast<std::uint32_t>(binary.t);
    const bool same_dispatched = dispatched.triangle == wide.triangle && dispatched.cut_short == wide.cut_short &&
                                 std::bit_cast<std::uint32_t>(dispatched.t) == std::bit_cast<std::uint32_t>(wide.t);
    // The occlusion query over the same segment: the wide walk (dispatched
    // by segment_blocked) against the binary one the GPU runs.
    const bool binary_blocked =
        sp::shader::sp_segment_blocked(bvh.nodes.data(), bvh.triangles.data(), r.origin, r.dir, r.tmin, r.tmax);
    const bool wide_blocked = sp::segment_blocked(bvh, r.origin, r.dir, r.tmin, r.tmax);
    agreement.blocked += binary_blocked;
    if (wide_blocked != binary_blocked && ++blocked_failures <= 5) {
      ADD_FAILURE() << std::hexfloat << "segment of ray o=(" << r.origin.x << ", " << r.origin.y << ", " << r.origin.z
                    << ") d=(" << r.dir.x << ", " << r.dir.y << ", " << r.dir.z << ") t in (" << r.tmin << ", "
                    << r.tmax << "]: wide says " << (wide_blocked ? "blocked" : "open") << ", binary "
                    << (binary_blocked ? "blocked" : "open");
    }
    if ((!same || !same_dispatched) && ++failures <= 5) {
      ADD_FAILURE() << std::hexfloat << "ray o=(" << r.origin.x << ", " << r.origin.y << ", " << r.origin.z << ") d=("
                    << r.dir.x << ", " << r.dir.y << ", " << r.dir.z << ") t in (" << r.tmin << ", " << r.tmax
                    << "]: wide " << wide.triangle << " t=" << wide.t << " cut " << wide.cut_short << ", binary "
                    << binary.triangle << " t=" << binary.t << " cut " << binary.cut_short << ", closest_hit "
                    << dispatched.triangle << " t=" << dispatched.t << " cut " << dispatched.cut_short;
    }
  }
  EXPECT_EQ(failures, 0u) << "of " << rays.size() << " rays";
  EXPECT_EQ(list_failures, 0u) << "nearest-hit lists, of " << rays.size() << " rays";
  EXPECT_EQ(blocked_failures, 0u) << "occlusion queries, of " << rays.size() << " segments";
  return agreement;
}

// Every ray, with every compiled walk this CPU runs: wide == binary,
// triangle and t bit for bit; closest_hit (which dispatches to the wide
// tree) says the same. The same for the nearest-hits list of the matter
// query. Returns the last walk's agreement (all walks must agree anyway).
Agreement expect_same_as_binary(const sp::Bvh& bvh, const std::vector<Ray>& rays) {
  Agreement agreement;
  for (const sp::WideWalk walk : {sp::WideWalk::Baseline, sp::WideWalk::Avx512, sp::WideWalk::Avx512Wide8}) {
    const WalkSelection selection(walk);
    if (!selection.selected()) continue;
    SCOPED_TRACE(std::string("walk ") + sp::wide_walk_name(walk));
    agreement = expect_selected_walk_same_as_binary(bvh, rays);
  }
  return agreement;
}

std::vector<Ray> concat(std::vector<Ray> a, const std::vector<Ray>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The scenes below cast 144k rays in all, each with the binary walk and
// every wide walk this CPU runs.

TEST(WideBvh, RandomSoupMatchesBinary) {
  Soup soup = make_random_soup(3000, 21);
  for (std::uint32_t leaf : {1u, 4u, 8u}) {
    sp::BvhBuildSettings s;
    s.max_leaf_size = leaf;  // 8: two packets per full leaf
    s.bins = leaf == 8u ? 2u : 16u;
    sp::Bvh bvh = soup.build(s);
    check_wide_invariants(bvh);
    Agreement a = expect_same_as_binary(bvh, vary_windows(rays_in_box(vec3(-12), vec3(12), 10000, leaf), leaf));
    EXPECT_GT(a.hits, 5000u);
    EXPECT_GT(a.blocked, 5000u);
    EXPECT_LT(a.blocked, a.rays - 1000u) << "segments that meet nothing are open, and tested";
  }
}

// The matter query looks SP_CONTACT_TOLERANCE behind its origin. A face
// there, in a flat leaf (one quad: entry and exit on one plane), has
// a negative exit distance; scaled up by the box margin it would fall below
// the entry and the face would be missed. Hand-derived: the floor y = 0
// lies 0.5 mm above an origin going down at slope (0.3, -0.9, 0.2), so at
// t = -0.0005 / |d.y| along the unit direction d.
TEST(WideBvh, FaceJustBehindTheOriginInAFlatLeafIsFound) {
  Soup soup;
  soup.tri(vec3(-1, 0, -1), vec3(1, 0, 1), vec3(1, 0, -1));
  soup.tri(vec3(-1, 0, -1), vec3(-1, 0, 1), vec3(1, 0, 1));
  const sp::Bvh bvh = soup.build();
  const vec3 dir = glm::normalize(vec3(0.3f, -0.9f, 0.2f));
  const vec3 origin(0.2f, -0.0005f, -0.4f);  // above triangle 0 (x > z)
  const float expected_t = -0.0005f / -dir.y;
  sp::shader::HitList binary;
  sp::shader::sp_nearest_hits(bvh.nodes.data(), bvh.triangles.data(), origin, dir, -SP_CONTACT_TOLERANCE, 1.0f, binary);
  const sp::shader::HitList wide = sp::nearest_hits(bvh, origin, dir, -SP_CONTACT_TOLERANCE, 1.0f);
  const sp::shader::HitList* lists[] = {&binary, &wide};
  for (const sp::shader::HitList* list : lists) {
    ASSERT_EQ(list->count, 1u) << (list == &binary ? "binary walk" : "wide walk");
    EXPECT_NEAR(list->t[0], expected_t, 1e-8f);
    EXPECT_EQ(bvh.triangles[list->triangle[0]].scene_index, 0u);
  }
  // Starting at the origin (tmin 0) it is behind the window: no hit, and
  // the closest-hit walks agree.
  sp::shader::HitList ahead;
  sp::shader::sp_nearest_hits(bvh.nodes.data(), bvh.triangles.data(), origin, dir, 0.0f, 1.0f, ahead);
  EXPECT_EQ(ahead.count, 0u);
  EXPECT_EQ(sp::closest_hit(bvh, origin, dir, 0.0f, 1.0f).triangle, SP_INVALID);
}

// A tree large enough that the walk prefetches (kPrefetchTreeBytes).
TEST(WideBvh, LargeTreesMatchBinary) {
  Soup soup = make_random_soup(64000, 31);
  sp::Bvh bvh = soup.build();
  ASSERT_GT(bvh.wide->wide4_bytes(), sp::kPrefetchTreeBytes);
  check_wide_invariants(bvh);
  Agreement a = expect_same_as_binary(bvh, vary_windows(rays_in_box(vec3(-12), vec3(12), 6000, 32), 33));
  EXPECT_GT(a.hits, 3000u);
}

// Trees past kWide8MaxTreeBytes get no 8-wide copy; there the 8-wide walk,
// when selected, hands the query to the 4-wide AVX-512 walk. A smaller tree
// with its 8-wide copy taken away stands in for one (a real one takes some
// 800k triangles).
TEST(WideBvh, TreesWithoutAnEightWideCopyTakeTheFourWideWalk) {
  if (!sp::wide_walk_available(sp::WideWalk::Avx512Wide8)) GTEST_SKIP() << "this CPU or build has no 8-wide walk";
  Soup soup = make_random_soup(3000, 41);
  sp::Bvh bvh = soup.build();
  auto without_wide8 = std::make_shared<sp::WideBvh>(*bvh.wide);
  ASSERT_FALSE(without_wide8->nodes8.empty());
  decltype(without_wide8->nodes8)().swap(without_wide8->nodes8);  // freed: nothing left to walk
  without_wide8->depth8 = 0;
  bvh.wide = without_wide8;
  const WalkSelection selection(sp::WideWalk::Avx512Wide8);
  ASSERT_TRUE(selection.selected());
  const Agreement a =
      expect_selected_walk_same_as_binary(bvh, vary_windows(rays_in_box(vec3(-6), vec3(6), 2000, 42), 43));
  EXPECT_GT(a.hits, 500u);
}

// Axis-aligned walls (node bounds planes coincide with faces), coincident
// walls (exact ties between scene indices), T-junctions, rays that start on
// surfaces or run inside a wall's plane with zero direction components.
TEST(WideBvh, RoomsMatchBinary) {
  Soup soup = make_rooms(4, 3, 2, 2);
  sp::Bvh bvh = soup.build();
  check_wide_invariants(bvh);
  std::vector<Ray> rays = concat(rays_from_surfaces(soup, 30000, 22), rays_along_planes(soup, 20000, 23));
  rays = concat(rays, rays_in_box(vec3(-1), vec3(21, 13, 7), 10000, 24));
  Agreement a = expect_same_as_binary(bvh, vary_windows(rays, 25));
  EXPECT_GT(a.hits, 45000u);
}

// Direction components at and around the slab test's 1e-20 guard, of
// either sign, and -0: the walk derives inverse directions, the parallel
// axes and the planes it tests first from them, as sp_make_query does.
TEST(WideBvh, TinyDirectionComponentsMatchBinary) {
  Soup soup = make_rooms(2, 2, 1, 2);
  sp::Bvh bvh = soup.build();
  const float tiny[] = {0.0f, -0.0f, 1e-25f, -1e-25f, 1e-20f, -1e-20f, 2e-20f, -2e-20f};
  std::vector<Ray> rays = rays_along_planes(soup, 8000, 41);
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> pick(0, 7), axis(0, 2);
  for (Ray& r : rays) {
    for (int a = 0; a < 3; ++a)
      if (r.dir[a] == 0.0f) r.dir[a] = tiny[pick(rng)];
    if (rng() % 2u == 0u) r.dir[axis(rng)] = tiny[pick(rng)];  // one more, wherever it was
  }
  rays.erase(std::remove_if(rays.begin(), rays.end(),
                            [](const Ray& r) {
                              return std::max({std::abs(r.dir.x), std::abs(r.dir.y), std::abs(r.dir.z)}) < 0.1f;
                            }),
             rays.end());
  Agreement a = expect_same_as_binary(bvh, rays);
  EXPECT_GT(a.hits, 4000u);
}

TEST(WideBvh, ClosedShapesMatchBinary) {
  Soup box;
  add_box(box, vec3(-2.0f, -1.0f, 0.5f), vec3(3.0f, 1.7f, 4.0f), 8);
  sp::Bvh box_bvh = box.build();
  check_wide_invariants(box_bvh);
  std::vector<Ray> inside = rays_in_box(vec3(-1.9f, -0.9f, 0.6f), vec3(2.9f, 1.6f, 3.9f), 10000, 26);
  expect_same_as_binary(box_bvh, concat(vary_windows(inside, 27), rays_along_planes(box, 5000, 28)));

  Soup sphere;
  add_sphere(sphere, vec3(1.0f, -2.0f, 0.5f), 3.0f, 20);
  sp::Bvh sphere_bvh = sphere.build();
  check_wide_invariants(sphere_bvh);
  std::vector<Ray> rays =
      concat(rays_in_box(vec3(-6, -7, -5), vec3(6, 3, 6), 10000, 29), rays_from_surfaces(sphere, 10000, 30));
  Agreement a = expect_same_as_binary(sphere_bvh, vary_windows(rays, 31));
  EXPECT_GT(a.hits, 8000u);
}

// Leaves of hundreds of triangles (the depth cap) take many packets; the
// unbalanced tree reaches SP_BVH_MAX_DEPTH levels, the stack's bound. 600
// triangles keep a cast through them under SP_MAX_CAST_PACKETS, so every
// cast ends whole (HostileShapesCutTheSameCastsAsBinary tests the cut).
TEST(WideBvh, DepthCapAndDeepTreesMatchBinary) {
  Soup soup = make_identical_centroids(600);
  for (std::uint32_t depth : {4u, std::uint32_t{SP_BVH_MAX_DEPTH}}) {
    sp::BvhBuildSettings s;
    s.max_depth = depth;
    sp::Bvh bvh = soup.build(s);
    check_wide_invariants(bvh);
    Agreement a = expect_same_as_binary(bvh, vary_windows(rays_in_box(vec3(0), vec3(2, 3, 4), 4000, depth), depth));
    EXPECT_GT(a.hits, 800u);
    EXPECT_EQ(a.cut_short, 0u);
  }

  Soup deep;
  for (int i = 0; i < 60; ++i) {
    float x = std::ldexp(1.0f, i);
    deep.tri(vec3(x, 0, 0), vec3(x, 1, 0), vec3(x, 0, 1));
  }
  sp::BvhBuildSettings s;
  s.max_leaf_size = 1;
  s.bins = 2;
  sp::Bvh bvh = deep.build(s);
  ASSERT_EQ(bvh.depth, std::uint32_t{SP_BVH_MAX_DEPTH});
  check_wide_invariants(bvh);
  std::vector<Ray> rays;
  for (int i = 0; i < 60; ++i) {
    rays.push_back({vec3(0.0f, 0.25f, 0.25f), vec3(1, 0, 0), std::ldexp(0.75f, i), 1e18f});
    rays.push_back({vec3(std::ldexp(1.5f, i), 0.25f, 0.25f), vec3(-1, 0, 0), 0.0f, SP_FAR});
  }
  Agreement a = expect_same_as_binary(bvh, rays);
  EXPECT_EQ(a.hits, rays.size());
}

// One to three triangles: a leaf root (one slot) and wide nodes with unused
// slots, whose NaN bounds must miss even for an unbounded window.
TEST(WideBvh, TinyTreesMatchBinary) {
  Soup soup;
  soup.tri(vec3(0, 0, 2), vec3(1, 0, 2), vec3(0, 1, 2));
  soup.tri(vec3(3, 0, 2), vec3(4, 0, 2), vec3(3, 1, 2));
  soup.tri(vec3(0, 3, 5), vec3(1, 3, 5), vec3(0, 4, 5));
  for (std::uint32_t n = 1; n <= 3; ++n) {
    Soup part;
    part.vertices.assign(soup.vertices.begin(), soup.vertices.begin() + 3 * n);
    part.layers.assign(n, 0u);
    sp::BvhBuildSettings s;
    s.max_leaf_size = 1;
    sp::Bvh bvh = part.build(s);
    check_wide_invariants(bvh);
    if (n == 1) {
      EXPECT_EQ(bvh.wide->nodes.size(), 1u);
    }
    Agreement a = expect_same_as_binary(bvh, vary_windows(rays_in_box(vec3(-1), vec3(5, 5, 6), 3000, 40 + n), n));
    EXPECT_GT(a.hits, 0u);
  }
}

// Coincident copies in separate leaves: the lower scene index wins whatever
// the order the leaves are entered in.
TEST(WideBvh, CoincidentTrianglesMatchBinary) {
  Soup soup = make_random_soup(500, 32);
  const vec3 a(0, 0, 5), b(2, 0, 5), c(0, 2, 5);
  for (std::size_t i : {std::size_t{0}, std::size_t{3 * 250}, soup.vertices.size() - 3}) {
    soup.vertices[i] = a;
    soup.vertices[i + 1] = b;
    soup.vertices[i + 2] = c;
  }
  sp::BvhBuildSettings s;
  s.max_leaf_size = 1;
  sp::Bvh bvh = soup.build(s);
  check_wide_invariants(bvh);
  std::mt19937 rng(33);
  std::uniform_real_distribution<float> u(0.05f, 0.9f);
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    const vec3 target(u(rng), u(rng), 5.0f);
    const vec3 o(u(rng) * 20.0f - 10.0f, u(rng) * 20.0f - 10.0f, i % 2 ? -15.0f : 25.0f);
    rays.push_back({o, glm::normalize(target - o), 0.0f, kNoLimit});
  }
  Agreement hits = expect_same_as_binary(bvh, rays);
  EXPECT_GT(hits.hits, 1900u);
  const sp::HitInfo h = sp::closest_hit(bvh, vec3(0.5f, 0.5f, -20.0f), vec3(0, 0, 1), 0.0f, kNoLimit);
  ASSERT_NE(h.triangle, SP_INVALID);
  EXPECT_EQ(bvh.triangles[h.triangle].scene_index, 0u);
}

// Hostile levels (issue 38): a quad repeated 3,000 times, and 2,000 long
// slivers whose boxes all overlap, defeat the tree, so casts through them
// reach SP_MAX_CAST_PACKETS. Every walk must cut the same casts at the same
// leaf as the binary walk (the GPU's), and leave the others whole.
TEST(WideBvh, HostileShapesCutTheSameCastsAsBinary) {
  Soup coincident;
  for (int i = 0; i < 1500; ++i) {
    coincident.tri(vec3(-2, 0, -2), vec3(2, 0, -2), vec3(2, 0, 2));
    coincident.tri(vec3(-2, 0, -2), vec3(2, 0, 2), vec3(-2, 0, 2));
  }
  Soup slivers;
  std::mt19937 rng(38);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const vec3 d = glm::normalize(vec3(u(rng), u(rng), u(rng)));
    const vec3 c(u(rng), u(rng), u(rng));
    slivers.tri(c - 10.0f * d, c + 10.0f * d, c - 10.0f * d + vec3(0.01f, 0.01f, 0.0f));
  }
  for (Soup* soup : {&coincident, &slivers}) {
    sp::Bvh bvh = soup->build(sp::BvhBuildSettings{});
    check_wide_invariants(bvh);
    std::vector<Ray> rays;
    constexpr std::size_t kMissing = 200;  // start above the shape and head away from it
    for (std::size_t i = 0; i < kMissing; ++i)
      rays.push_back({vec3(u(rng), 12.0f, u(rng)), glm::normalize(vec3(u(rng), 1.0f, u(rng))), 0.0f, kNoLimit});
    for (int i = 0; i < 1000; ++i) {
      const vec3 o(u(rng) * 3.0f, 3.0f + u(rng), u(rng) * 3.0f);
      const vec3 target(u(rng), u(rng) * 0.5f, u(rng));
      rays.push_back({o, glm::normalize(target - o), 0.0f, kNoLimit});
      rays.push_back({target, glm::normalize(o - target), -1e-3f, 0.5f});  // a matter query's window
    }
    const Agreement agreement = expect_same_as_binary(bvh, rays);
    EXPECT_GT(agreement.cut_short, 100u) << "the shape no longer defeats the tree: make it harder";
    EXPECT_LE(agreement.cut_short, rays.size() - kMissing) << "rays that miss the shape end whole";
    EXPECT_GT(agreement.lists_cut_short, 100u);
    EXPECT_GE(agreement.blocked, agreement.cut_short) << "a walk cut short is blocked";
  }
}

// The baseline walk is always there; the process starts on the fastest one
// the CPU runs; a walk the CPU cannot run is refused and changes nothing.
TEST(WideBvh, WalkSelectionStartsOnTheFastestAvailable) {
  const bool avx512 = sp::wide_walk_available(sp::WideWalk::Avx512);
  EXPECT_EQ(sp::wide_walk_available(sp::WideWalk::Avx512Wide8), avx512) << "the same CPUs run both";
  const sp::WideWalk fastest = avx512 ? sp::WideWalk::Avx512Wide8 : sp::WideWalk::Baseline;
  std::printf("compiled walks this CPU runs: baseline%s\n", avx512 ? ", avx512, avx512-8wide" : "");
  EXPECT_TRUE(sp::wide_walk_available(sp::WideWalk::Baseline));
  EXPECT_EQ(sp::selected_wide_walk(), fastest);
  {
    const WalkSelection baseline(sp::WideWalk::Baseline);
    EXPECT_TRUE(baseline.selected());
    EXPECT_EQ(sp::selected_wide_walk(), sp::WideWalk::Baseline);
    EXPECT_EQ(sp::select_wide_walk(sp::WideWalk::Avx512), avx512);
    EXPECT_EQ(sp::selected_wide_walk(), avx512 ? sp::WideWalk::Avx512 : sp::WideWalk::Baseline);
    EXPECT_EQ(sp::select_wide_walk(sp::WideWalk::Avx512Wide8), avx512);
    EXPECT_EQ(sp::selected_wide_walk(), fastest);
  }
  EXPECT_EQ(sp::selected_wide_walk(), fastest);
}

// Copies of a Bvh share the immutable wide tree; without one, closest_hit
// walks the binary nodes and answers the same.
TEST(WideBvh, CopiesShareTheTreeAndNullFallsBack) {
  Soup soup = make_rooms(2, 2, 1, 2);
  const sp::Bvh bvh = soup.build();
  sp::Bvh copy = bvh;
  EXPECT_EQ(copy.wide, bvh.wide);
  sp::Bvh moved = std::move(copy);
  EXPECT_EQ(moved.wide, bvh.wide);
  moved.wide.reset();
  for (const Ray& r : rays_from_surfaces(soup, 2000, 34)) {
    const sp::HitInfo w = sp::closest_hit(bvh, r.origin, r.dir, r.tmin, r.tmax);
    const sp::HitInfo b = sp::closest_hit(moved, r.origin, r.dir, r.tmin, r.tmax);
    ASSERT_EQ(w.triangle, b.triangle);
    ASSERT_EQ(std::bit_cast<std::uint32_t>(w.t), std::bit_cast<std::uint32_t>(b.t));
  }
}

}  // namespace
