// Tests of refit_bvh and bvh_sah_cost: a moving wall with hits derived by
// hand, the reported change ranges against a bitwise comparison of the
// arrays, random rigid motions against brute force and a fresh build, the
// SAH cost of hand-made trees, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "bvh/bvh.h"
#include "soundpaint/result.h"
#include "support/bvh_scenes.h"

namespace {

using namespace sp::test;

template <class Array>
bool same_bytes(const Array& a, const Array& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

// The closest hit as (scene index, t), after checking that the wide walk,
// the binary walk the GPU runs (no wide copy) and brute force all agree on
// it exactly.
std::pair<std::uint32_t, float> scene_hit(const sp::Bvh& bvh, vec3 origin, vec3 dir) {
  sp::Bvh binary = bvh;
  binary.wide.reset();
  const sp::HitInfo wide = sp::closest_hit(bvh, origin, dir, 0.0f, kNoLimit);
  const sp::HitInfo walk = sp::closest_hit(binary, origin, dir, 0.0f, kNoLimit);
  const sp::HitInfo brute = sp::closest_hit_brute_force(bvh, origin, dir, 0.0f, kNoLimit);
  EXPECT_EQ(wide.triangle, brute.triangle);
  EXPECT_EQ(wide.t, brute.t);
  EXPECT_EQ(walk.triangle, brute.triangle);
  EXPECT_EQ(walk.t, brute.t);
  if (brute.triangle == SP_INVALID) return {SP_INVALID, brute.t};
  return {bvh.triangles[brute.triangle].scene_index, brute.t};
}

// Every node's box must be exactly the bounds of the triangles below it,
// computed here by walking the subtree, independently of the refit.
void expect_exact_bounds(const sp::Bvh& bvh) {
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    vec3 lo(INFINITY), hi(-INFINITY);
    std::vector<std::uint32_t> stack{static_cast<std::uint32_t>(i)};
    while (!stack.empty()) {
      const sp::BvhNode& n = bvh.nodes[stack.back()];
      stack.pop_back();
      if (n.count == 0u) {
        stack.push_back(n.left_or_first);
        stack.push_back(n.left_or_first + 1u);
        continue;
      }
      for (std::uint32_t t = n.left_or_first; t < n.left_or_first + n.count; ++t) {
        const sp::BvhTriangle& tri = bvh.triangles[t];
        lo = glm::min(lo, glm::min(glm::min(tri.v0, tri.v1), tri.v2));
        hi = glm::max(hi, glm::max(glm::max(tri.v0, tri.v1), tri.v2));
      }
    }
    EXPECT_EQ(bvh.nodes[i].bmin, lo) << "node " << i;
    EXPECT_EQ(bvh.nodes[i].bmax, hi) << "node " << i;
  }
}

// Sorted, disjoint, non-empty, inside [0, size), and covering every entry
// whose bytes differ between `before` and `after`.
template <class Array>
void expect_ranges_cover_changes(const std::vector<sp::BvhIndexRange>& ranges, const Array& before,
                                 const Array& after) {
  using T = typename Array::value_type;
  ASSERT_EQ(before.size(), after.size());
  std::vector<bool> covered(before.size(), false);
  std::uint32_t previous_last = 0;
  for (std::size_t r = 0; r < ranges.size(); ++r) {
    EXPECT_LT(ranges[r].first, ranges[r].last);
    EXPECT_LE(ranges[r].last, before.size());
    if (r > 0) {
      EXPECT_LT(previous_last, ranges[r].first) << "ranges overlap, touch or are unsorted";
    }
    previous_last = ranges[r].last;
    for (std::uint32_t i = ranges[r].first; i < ranges[r].last && i < before.size(); ++i) covered[i] = true;
  }
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (std::memcmp(&before[i], &after[i], sizeof(T)) != 0) {
      EXPECT_TRUE(covered[i]) << "entry " << i;
    }
  }
}

std::uint32_t leaf_index_of(const sp::Bvh& bvh, std::uint32_t scene_index) {
  for (std::uint32_t i = 0; i < bvh.triangles.size(); ++i) {
    if (bvh.triangles[i].scene_index == scene_index) return i;
  }
  ADD_FAILURE() << "scene index " << scene_index << " not in the tree";
  return 0;
}

// The leaf-order triangles [first, last) below `node`.
std::pair<std::uint32_t, std::uint32_t> triangle_range(const sp::Bvh& bvh, std::uint32_t node) {
  std::uint32_t first = SP_INVALID, last = 0;
  std::vector<std::uint32_t> stack{node};
  while (!stack.empty()) {
    const sp::BvhNode& n = bvh.nodes[stack.back()];
    stack.pop_back();
    if (n.count == 0u) {
      stack.push_back(n.left_or_first);
      stack.push_back(n.left_or_first + 1u);
    } else {
      first = std::min(first, n.left_or_first);
      last = std::max(last, n.left_or_first + n.count);
    }
  }
  return {first, last};
}

// Nodes on the path from the root to the leaf that holds leaf-order triangle `t`.
std::set<std::uint32_t> path_to(const sp::Bvh& bvh, std::uint32_t t) {
  std::set<std::uint32_t> path{0u};
  std::uint32_t node = 0;
  while (bvh.nodes[node].count == 0u) {
    const std::uint32_t left = bvh.nodes[node].left_or_first;
    const auto [first, last] = triangle_range(bvh, left);
    node = (first <= t && t < last) ? left : left + 1u;
    path.insert(node);
  }
  return path;
}

void translate_triangle(Soup& soup, std::uint32_t scene_index, vec3 offset) {
  for (int k = 0; k < 3; ++k) soup.vertices[3u * scene_index + std::uint32_t(k)] += offset;
}

// ------------------------------------------------------------ a moving wall

// A 10 x 4 x 3 room (scene triangles 0..11, add_box's order: x faces, y
// faces, z faces) and a wall quad at y = 2 spanning x in [1, 3] and z in
// [0.5, 2.5] (scene 12: below the diagonal z = x - 0.5, scene 13: above).
// Refitting it 5 m along +x must make it vanish from where it was and appear
// where it went, on every traversal path.
TEST(BvhRefit, WallMovedByRefitIsHitWhereItWent) {
  Soup soup;
  add_box(soup, vec3(0.0f), vec3(10.0f, 4.0f, 3.0f), 1);
  soup.tri(vec3(1, 2, 0.5f), vec3(3, 2, 0.5f), vec3(3, 2, 2.5f));
  soup.tri(vec3(1, 2, 0.5f), vec3(3, 2, 2.5f), vec3(1, 2, 2.5f));
  ASSERT_EQ(soup.size(), 14u);
  sp::Bvh bvh = soup.build();

  // Ray a passes through the wall's old place, ray b through its new one,
  // both along +y from y = 0.5 at z = 1.
  const vec3 a_origin(2.5f, 0.5f, 1.0f), b_origin(7.0f, 0.5f, 1.0f), up(0.0f, 1.0f, 0.0f);
  // Before: a hits the wall (y = 2, t = 1.5; z = 1 < x - 0.5 = 2: scene 12);
  // b hits the far wall y = 4 at t = 3.5. The +y face is cut along its
  // diagonal from (x, z) = (0, 3) to (10, 0): scene 6 below z = 3 - 0.3 x,
  // scene 7 above; at x = 7, z = 1 > 0.9: scene 7.
  auto [a_scene, a_t] = scene_hit(bvh, a_origin, up);
  EXPECT_EQ(a_scene, 12u);
  EXPECT_FLOAT_EQ(a_t, 1.5f);
  auto [b_scene, b_t] = scene_hit(bvh, b_origin, up);
  EXPECT_EQ(b_scene, 7u);
  EXPECT_FLOAT_EQ(b_t, 3.5f);

  const sp::Bvh before = bvh;  // shares the wide copy, which must survive unchanged
  translate_triangle(soup, 12, vec3(5.0f, 0.0f, 0.0f));
  translate_triangle(soup, 13, vec3(5.0f, 0.0f, 0.0f));
  sp::BvhChanges changes = sp::refit_bvh(bvh, soup.vertices).value();
  EXPECT_FALSE(changes.triangles.empty());
  EXPECT_FALSE(changes.nodes.empty());
  ASSERT_NE(bvh.wide, nullptr);
  EXPECT_NE(bvh.wide, before.wide) << "the shared wide copy must be replaced, not kept";
  expect_exact_bounds(bvh);

  // After: a passes where the wall was and hits the far wall at x = 2.5,
  // z = 1 < 3 - 0.75: scene 6, t = 3.5. b hits the moved wall (x in [6, 8],
  // diagonal z = x - 5.5; z = 1 < 1.5: scene 12) at t = 1.5.
  std::tie(a_scene, a_t) = scene_hit(bvh, a_origin, up);
  EXPECT_EQ(a_scene, 6u);
  EXPECT_FLOAT_EQ(a_t, 3.5f);
  std::tie(b_scene, b_t) = scene_hit(bvh, b_origin, up);
  EXPECT_EQ(b_scene, 12u);
  EXPECT_FLOAT_EQ(b_t, 1.5f);
  // Above the moved wall's diagonal: scene 13.
  std::tie(b_scene, b_t) = scene_hit(bvh, vec3(6.5f, 0.5f, 2.0f), up);
  EXPECT_EQ(b_scene, 13u);
  EXPECT_FLOAT_EQ(b_t, 1.5f);

  // The copy taken before the refit still sees the wall where it was.
  const sp::HitInfo old_hit = sp::closest_hit(before, a_origin, up, 0.0f, kNoLimit);
  ASSERT_NE(old_hit.triangle, SP_INVALID);
  EXPECT_EQ(before.triangles[old_hit.triangle].scene_index, 12u);
  EXPECT_FLOAT_EQ(old_hit.t, 1.5f);
}

// A tree whose wide copy was dropped keeps walking `nodes` after a refit.
TEST(BvhRefit, TreeWithoutWideCopyStaysWithout) {
  Soup soup = unit_square();
  sp::Bvh bvh = soup.build();
  bvh.wide.reset();
  for (vec3& v : soup.vertices) v.z = 7.0f;
  ASSERT_TRUE(sp::refit_bvh(bvh, soup.vertices).ok());
  EXPECT_EQ(bvh.wide, nullptr);
  EXPECT_EQ(scene_hit(bvh, vec3(0.75f, 0.25f, 0.0f), vec3(0, 0, 1)), std::pair(0u, 7.0f));
}

// ------------------------------------------------------------ change ranges

TEST(BvhRefit, UnchangedVerticesReportNoChanges) {
  Soup soup = make_random_soup(300, 21);
  sp::Bvh bvh = soup.build();
  const sp::Bvh original = bvh;
  sp::BvhChanges changes = sp::refit_bvh(bvh, soup.vertices).value();
  EXPECT_TRUE(changes.nodes.empty());
  EXPECT_TRUE(changes.triangles.empty());
  EXPECT_TRUE(same_bytes(bvh.nodes, original.nodes));
  EXPECT_TRUE(same_bytes(bvh.triangles, original.triangles));
  EXPECT_EQ(bvh.wide, original.wide) << "nothing changed, so nothing needed rebuilding";
}

// Coordinates at +0 and -0 on the scene's bounding planes: which zero a
// node's bound holds depends on the order the builder scanned its triangles
// (before partitioning them further), which a recomputation does not repeat.
// Such bounds are equal as floats and must not count as changes.
TEST(BvhRefit, SignedZeroBoundsAreNoChange) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> pos(0.0f, 10.0f), sign(0.0f, 1.0f);
  auto zero = [&] { return sign(rng) < 0.5f ? 0.0f : -0.0f; };
  Soup soup;
  for (int i = 0; i < 400; ++i) {
    const vec3 c(pos(rng), pos(rng), pos(rng));
    // Every triangle touches x = 0, y = 0 or z = 0 with a zero of either sign.
    vec3 a = c, b = c + vec3(0.5f, 0.0f, 0.0f), d = c + vec3(0.0f, 0.5f, 0.5f);
    a[i % 3] = zero();
    b[(i + 1) % 3] = zero();
    soup.tri(a, b, d);
  }
  sp::Bvh bvh = soup.build();
  const sp::Bvh original = bvh;
  sp::BvhChanges changes = sp::refit_bvh(bvh, soup.vertices).value();
  EXPECT_TRUE(changes.nodes.empty());
  EXPECT_TRUE(changes.triangles.empty());
  EXPECT_TRUE(same_bytes(bvh.nodes, original.nodes));
}

// One triangle moved 30 m up: exactly its own entry changes, and exactly the
// nodes on the path from the root to its leaf (each grows to reach it).
TEST(BvhRefit, MovingOneTriangleReportsItsLeafAndItsAncestors) {
  Soup soup = make_random_soup(300, 23);
  sp::Bvh bvh = soup.build();
  const sp::Bvh before = bvh;
  const std::uint32_t moved = 123;
  const std::uint32_t leaf_index = leaf_index_of(bvh, moved);
  translate_triangle(soup, moved, vec3(0.0f, 0.0f, 30.0f));
  sp::BvhChanges changes = sp::refit_bvh(bvh, soup.vertices).value();

  ASSERT_EQ(changes.triangles.size(), 1u);
  EXPECT_EQ(changes.triangles[0].first, leaf_index);
  EXPECT_EQ(changes.triangles[0].last, leaf_index + 1u);
  ASSERT_FALSE(changes.nodes.empty());
  EXPECT_EQ(changes.nodes[0].first, 0u) << "the root grew";
  expect_ranges_cover_changes(changes.nodes, before.nodes, bvh.nodes);
  expect_ranges_cover_changes(changes.triangles, before.triangles, bvh.triangles);

  // The soup lies within z in [-11.5, 11.5], so the moved triangle (z >= 18.5)
  // sets the top of every box on its path.
  const vec3* v = &soup.vertices[3u * moved];
  const float top = std::max(std::max(v[0].z, v[1].z), v[2].z);
  const std::set<std::uint32_t> path = path_to(before, leaf_index);
  EXPECT_GE(path.size(), 3u);
  for (std::uint32_t i = 0; i < bvh.nodes.size(); ++i) {
    const bool changed = std::memcmp(&before.nodes[i], &bvh.nodes[i], sizeof(sp::BvhNode)) != 0;
    EXPECT_EQ(changed, path.count(i) == 1u) << "node " << i;
    if (path.count(i)) {
      EXPECT_EQ(bvh.nodes[i].bmax.z, top) << "node " << i;
    }
  }
  expect_exact_bounds(bvh);
}

// Changed triangles at most 16 unchanged entries apart share one range.
TEST(BvhRefit, NearbyChangesMergeIntoOneRange) {
  Soup soup = make_random_soup(300, 24);
  const sp::Bvh built = soup.build();
  struct Case {
    std::uint32_t first, second;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
  };
  const Case cases[] = {
      {50, 60, {{50, 61}}},
      {50, 67, {{50, 68}}},            // 16 unchanged between: merged
      {50, 68, {{50, 51}, {68, 69}}},  // 17: separate
      {50, 200, {{50, 51}, {200, 201}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::to_string(c.first) + ", " + std::to_string(c.second));
    sp::Bvh bvh = built;
    Soup moved = soup;
    for (std::uint32_t leaf : {c.first, c.second})
      translate_triangle(moved, bvh.triangles[leaf].scene_index, vec3(0.25f, 0.0f, 0.0f));
    sp::BvhChanges changes = sp::refit_bvh(bvh, moved.vertices).value();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const sp::BvhIndexRange& r : changes.triangles) got.emplace_back(r.first, r.last);
    EXPECT_EQ(got, c.expected);
  }
}

// ------------------------------------------------ random motions, brute force

// Rotates and translates every triangle whose scene index `pick` selects, as
// one rigid body about the origin of `rng`'s choosing.
std::vector<vec3> rigid_motion(const Soup& soup, std::mt19937& rng, const std::vector<bool>& pick) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const vec3 axis = glm::normalize(vec3(u(rng), u(rng), u(rng)) + vec3(0.0f, 0.0f, 1e-3f));
  const glm::quat rotation = glm::angleAxis(3.0f * u(rng), axis);
  const vec3 pivot(5.0f * u(rng), 5.0f * u(rng), 5.0f * u(rng));
  const vec3 shift(8.0f * u(rng), 8.0f * u(rng), 8.0f * u(rng));
  std::vector<vec3> v = soup.vertices;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (pick[i / 3]) v[i] = pivot + shift + rotation * (v[i] - pivot);
  }
  return v;
}

TEST(BvhRefit, RandomRigidMotionsMatchBruteForceAndAFreshBuild) {
  const Soup soup = make_random_soup(400, 25);
  sp::Bvh bvh = soup.build();
  std::mt19937 rng(26);
  std::uniform_int_distribution<int> coin(0, 3);
  for (int round = 0; round < 4; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    std::vector<bool> pick(soup.size());
    for (std::size_t i = 0; i < pick.size(); ++i) pick[i] = coin(rng) == 0;  // about a quarter
    Soup moved = soup;
    moved.vertices = rigid_motion(soup, rng, pick);
    if (round == 2) {  // one triangle collapses to a segment, as a closing door's sliver might
      moved.vertices[5] = moved.vertices[4];
    }
    ASSERT_TRUE(sp::refit_bvh(bvh, moved.vertices).ok());
    expect_exact_bounds(bvh);

    // The triangles are exactly the ones a fresh build makes from the moved
    // soup (corners, collapse, normal, layer), only in the old leaf order.
    const sp::Bvh fresh = moved.build();
    std::vector<sp::BvhTriangle> by_scene(fresh.triangle_count());
    for (const sp::BvhTriangle& t : fresh.triangles) by_scene[t.scene_index] = t;
    std::size_t differing = 0;
    for (const sp::BvhTriangle& t : bvh.triangles)
      differing += std::memcmp(&t, &by_scene[t.scene_index], sizeof(t)) != 0;
    EXPECT_EQ(differing, 0u);
    if (round == 2) {
      EXPECT_EQ(bvh.triangles[leaf_index_of(bvh, 1)].normal, vec3(0.0f));
    }

    sp::Bvh binary = bvh;
    binary.wide.reset();
    std::size_t hits = 0, mismatches = 0;
    for (const Ray& r : rays_in_box(vec3(-14.0f), vec3(14.0f), 8000, 27u + std::uint32_t(round))) {
      const sp::HitInfo brute = sp::closest_hit_brute_force(bvh, r.origin, r.dir, r.tmin, r.tmax);
      const sp::HitInfo wide = sp::closest_hit(bvh, r.origin, r.dir, r.tmin, r.tmax);
      const sp::HitInfo walk = sp::closest_hit(binary, r.origin, r.dir, r.tmin, r.tmax);
      const sp::HitInfo rebuilt = sp::closest_hit_brute_force(fresh, r.origin, r.dir, r.tmin, r.tmax);
      hits += brute.triangle != SP_INVALID;
      const bool same = wide.triangle == brute.triangle && wide.t == brute.t && walk.triangle == brute.triangle &&
                        walk.t == brute.t && rebuilt.t == brute.t &&
                        (brute.triangle == SP_INVALID) == (rebuilt.triangle == SP_INVALID) &&
                        (brute.triangle == SP_INVALID ||
                         bvh.triangles[brute.triangle].scene_index == fresh.triangles[rebuilt.triangle].scene_index);
      if (!same && ++mismatches <= 5)
        ADD_FAILURE() << "ray o=(" << r.origin.x << ", " << r.origin.y << ", " << r.origin.z << "): brute "
                      << brute.triangle << " t=" << brute.t << ", wide " << wide.triangle << " t=" << wide.t
                      << ", binary " << walk.triangle << " t=" << walk.t;
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(hits, 600u);
  }
}

// --------------------------------------------------------------- SAH cost

sp::BvhNode node(vec3 lo, vec3 hi, std::uint32_t left_or_first, std::uint32_t count) {
  return sp::BvhNode{lo, left_or_first, hi, count};
}

// Root [0,2]x[0,1]x[0,1] (half area 2 + 1 + 2 = 5) over a leaf [0,1]^3 (3)
// with 1 triangle and a leaf [1,2]x[0,1]x[0,1] (3) with 3: cost
// traversal_cost + 3/5 * 1 + 3/5 * 3.
TEST(BvhRefit, SahCostOfAHandMadeTree) {
  sp::Bvh bvh;
  bvh.nodes = {node(vec3(0), vec3(2, 1, 1), 1, 0), node(vec3(0), vec3(1), 0, 1),
               node(vec3(1, 0, 0), vec3(2, 1, 1), 1, 3)};
  bvh.triangles.assign(4, sp::BvhTriangle{});
  EXPECT_NEAR(sp::bvh_sah_cost(bvh, 1.0f), 1.0 + 12.0 / 5.0, 1e-12);
  EXPECT_NEAR(sp::bvh_sah_cost(bvh, 2.0f), 2.0 + 12.0 / 5.0, 1e-12);
  EXPECT_EQ(sp::bvh_sah_cost(sp::Bvh{}), 0.0);
}

// All boxes on the x axis: zero area everywhere, each 0/0 counting as 1.
TEST(BvhRefit, SahCostOfAZeroAreaTreeCountsEveryNode) {
  sp::Bvh bvh;
  bvh.nodes = {node(vec3(0), vec3(2, 0, 0), 1, 0), node(vec3(0), vec3(1, 0, 0), 0, 1),
               node(vec3(1, 0, 0), vec3(2, 0, 0), 1, 2)};
  bvh.triangles.assign(3, sp::BvhTriangle{});
  EXPECT_EQ(sp::bvh_sah_cost(bvh, 1.0f), 1.0 + 1.0 + 2.0);
  EXPECT_EQ(sp::bvh_sah_cost(bvh, 3.0f), 3.0 + 1.0 + 2.0);
}

// Ten triangles spread over the tree jump across the scene (each centroid c
// to -c; the soup is centred on the origin, so the root box barely changes):
// every box on their paths now spans the scene. Refitting back restores the
// original tree byte for byte, hence its cost exactly.
TEST(BvhRefit, SahCostGrowsWhenTrianglesJumpAcrossTheSceneAndRecoversExactly) {
  const Soup soup = make_random_soup(300, 28);
  sp::Bvh bvh = soup.build();
  const sp::Bvh original = bvh;
  const double cost = sp::bvh_sah_cost(bvh);
  EXPECT_GT(cost, 1.0);

  Soup jumped = soup;
  for (std::uint32_t k = 0; k < 10; ++k) {
    const std::uint32_t scene = original.triangles[30u * k].scene_index;
    const vec3* v = &soup.vertices[3u * scene];
    translate_triangle(jumped, scene, -2.0f * (v[0] + v[1] + v[2]) / 3.0f);
  }
  ASSERT_TRUE(sp::refit_bvh(bvh, jumped.vertices).ok());
  const double jumped_cost = sp::bvh_sah_cost(bvh);
  EXPECT_GT(jumped_cost, 1.5 * cost);
  // A fresh build of the same vertices is as good as the original tree again.
  EXPECT_LT(sp::bvh_sah_cost(jumped.build()), 1.2 * cost);

  sp::BvhChanges changes = sp::refit_bvh(bvh, soup.vertices).value();
  EXPECT_FALSE(changes.nodes.empty());
  EXPECT_EQ(sp::bvh_sah_cost(bvh), cost);
  EXPECT_TRUE(same_bytes(bvh.nodes, original.nodes));
  EXPECT_TRUE(same_bytes(bvh.triangles, original.triangles));
}

// --------------------------------------------------------------- bad input

// Calls refit_bvh expecting InvalidArgument with `words` in the message, and
// `bvh` left exactly as it was.
void expect_rejected(sp::Bvh& bvh, const std::vector<vec3>& vertices, const std::string& words) {
  const sp::Bvh before = bvh;
  const auto result = sp::refit_bvh(bvh, vertices);
  if (result.ok()) {
    ADD_FAILURE() << "accepted; expected an error about " << words;
  } else {
    EXPECT_EQ(result.error().code, sp::ErrorCode::InvalidArgument);
    EXPECT_NE(result.error().message.find(words), std::string::npos) << result.error().message;
  }
  EXPECT_TRUE(same_bytes(bvh.nodes, before.nodes));
  EXPECT_TRUE(same_bytes(bvh.triangles, before.triangles));
  EXPECT_EQ(bvh.wide, before.wide);
}

TEST(BvhRefit, BadInputIsRejectedAndLeavesTheTreeAlone) {
  Soup soup = make_random_soup(50, 29);
  sp::Bvh bvh = soup.build();
  std::vector<vec3> v = soup.vertices;
  v.pop_back();
  expect_rejected(bvh, v, "expected 3 vertices per triangle, 150 for 50 triangles, got 149");
  v = soup.vertices;
  v.insert(v.end(), {vec3(0), vec3(0), vec3(0)});
  expect_rejected(bvh, v, "got 153");
  expect_rejected(bvh, {}, "got 0");

  v = soup.vertices;
  v[100].y = std::numeric_limits<float>::quiet_NaN();
  expect_rejected(bvh, v, "vertex 100 (of triangle 33) is not finite");
  v = soup.vertices;
  v[2].z = -std::numeric_limits<float>::infinity();
  expect_rejected(bvh, v, "vertex 2 (of triangle 0) is not finite");

  // A hand-made tree whose child precedes its parent cannot be refitted bottom-up.
  sp::Bvh hand;
  hand.nodes = {node(vec3(0), vec3(1), 1, 0), node(vec3(0), vec3(1), 0, 1), node(vec3(0), vec3(1), 0, 0)};
  hand.triangles = {sp::BvhTriangle{vec3(0), 0, vec3(1, 0, 0), 0, vec3(0, 1, 0), 0, vec3(0, 0, 1), 0}};
  expect_rejected(hand, {vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)}, "node 2's children are not after it");

  // Children after their parents, but shared by two nodes, or a node no
  // parent leads to: the wide copies' one-pass layout would miscount both.
  hand.nodes = {node(vec3(0), vec3(1), 1, 0), node(vec3(0), vec3(1), 3, 0), node(vec3(0), vec3(1), 3, 0),
                node(vec3(0), vec3(1), 0, 1), node(vec3(0), vec3(1), 0, 1)};
  expect_rejected(hand, {vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)}, "node 3 is the child of two nodes");
  hand.nodes = {node(vec3(0), vec3(1), 1, 0), node(vec3(0), vec3(1), 0, 1), node(vec3(0), vec3(1), 0, 1),
                node(vec3(0), vec3(1), 0, 1)};
  expect_rejected(hand, {vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)}, "node 3 is no node's child");

  sp::Bvh empty;
  sp::BvhChanges changes = sp::refit_bvh(empty, {}).value();
  EXPECT_TRUE(changes.nodes.empty() && changes.triangles.empty());
}

}  // namespace
