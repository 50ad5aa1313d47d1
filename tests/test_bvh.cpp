// BVH tests: structural invariants of the flattened tree, the traversal
// against a brute-force reference on many rays, and hits derived by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iomanip>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "bvh/wide_bvh.h"
#include "sp_traverse.h"
#include "support/bvh_scenes.h"

namespace {

using namespace sp::test;

struct CompareStats {
  std::size_t hits = 0;        // rays the brute force sees hit something
  std::size_t near_ties = 0;   // the BVH chose another hit a rounding error away
  std::size_t cut_short = 0;   // casts that rightly ended at SP_MAX_CAST_PACKETS
  std::size_t mismatches = 0;  // anything else that differs: always a bug
};

// The packets (SP_LEAF_PACKETS) of the leaves whose box the ray enters
// within (tmin, limit]. Any walk with the closest-hit rule enters every
// leaf that passes with the final best hit, and only leaves that pass with
// tmax: with limit = the brute force's answer this is the least work a
// whole walk does, with limit = tmax the most.
std::uint32_t packets_in_reach(const sp::Bvh& bvh, const Ray& r, float limit) {
  const auto q = sp::shader::sp_make_query(r.origin, r.dir, r.tmin, r.tmax);
  std::uint32_t packets = 0;
  for (const sp::BvhNode& n : bvh.nodes)
    if (n.count > 0u && sp::shader::sp_intersect_box(q, n.bmin, n.bmax, limit) != SP_FAR)
      packets += SP_LEAF_PACKETS(n.count);
  return packets;
}

// The traversal must return exactly what testing every triangle returns, with
// one tolerated exception, counted in near_ties: the shared box test prunes
// with a relative margin (Ize 2013), while the watertight t of a triangle close
// to the origin carries an error proportional to its vertices' distance, so
// between two surfaces within that error of each other it may keep the farther
// one (or, at an equal computed t, the higher scene index).
CompareStats compare_with_brute_force(const sp::Bvh& bvh, const std::vector<Ray>& rays) {
  CompareStats stats;
  for (const Ray& r : rays) {
    sp::HitInfo fast = sp::closest_hit(bvh, r.origin, r.dir, r.tmin, r.tmax);
    sp::HitInfo slow = sp::closest_hit_brute_force(bvh, r.origin, r.dir, r.tmin, r.tmax);
    if (slow.triangle != SP_INVALID) ++stats.hits;
    // A cast is cut short exactly when the walk would exceed its bound:
    // certainly past the most work it can do, never within the least.
    if (fast.cut_short != 0u) {
      const std::uint32_t most = packets_in_reach(bvh, r, r.tmax);
      if (most > SP_MAX_CAST_PACKETS && fast.triangle == SP_INVALID) {
        ++stats.cut_short;
        continue;
      }
    } else if (packets_in_reach(bvh, r, slow.t) > SP_MAX_CAST_PACKETS) {
      ADD_FAILURE() << "a whole walk past SP_MAX_CAST_PACKETS was not cut short";
    }
    if (fast.triangle == slow.triangle && fast.t == slow.t && fast.cut_short == 0u) continue;
    if (fast.triangle != SP_INVALID && slow.triangle != SP_INVALID && fast.t >= slow.t &&
        fast.t - slow.t <= 1.0e-5f * (1.0f + slow.t)) {
      ++stats.near_ties;
      continue;
    }
    if (++stats.mismatches <= 5) {
      auto scene = [&](const sp::HitInfo& h) {
        return h.triangle == SP_INVALID ? std::string("miss") : std::to_string(bvh.triangles[h.triangle].scene_index);
      };
      ADD_FAILURE() << std::setprecision(9) << "ray o=(" << r.origin.x << ", " << r.origin.y << ", " << r.origin.z
                    << ") d=(" << r.dir.x << ", " << r.dir.y << ", " << r.dir.z << ") t in (" << r.tmin << ", "
                    << r.tmax << "]: bvh " << scene(fast) << " t=" << fast.t << ", brute force " << scene(slow)
                    << " t=" << slow.t;
    }
  }
  // Near-ties need a surface within ~1e-6 relative of another: rare.
  EXPECT_LE(stats.near_ties, rays.size() / 1000) << "near-ties are no longer rare";
  if (stats.near_ties > 0) std::cout << "[   INFO   ] near-ties: " << stats.near_ties << " of " << rays.size() << "\n";
  return stats;
}

// Rays whose closest distance is shared by two triangles: these exercise the
// scene-index tie-break.
std::size_t count_exact_ties(const sp::Bvh& bvh, const std::vector<Ray>& rays) {
  std::size_t ties = 0;
  for (const Ray& r : rays) {
    sp::HitInfo best = sp::closest_hit_brute_force(bvh, r.origin, r.dir, r.tmin, r.tmax);
    if (best.triangle == SP_INVALID) continue;
    auto q = sp::shader::sp_make_query(r.origin, r.dir, r.tmin, r.tmax);
    std::size_t same = 0;
    for (const sp::BvhTriangle& t : bvh.triangles)
      same += sp::shader::sp_intersect_triangle(q, t.v0, t.v1, t.v2) == best.t;
    ties += same > 1;
  }
  return ties;
}

// Walks the tree from the root and checks everything the traversal assumes,
// plus exact bounds and a faithful copy of the input triangles.
void check_invariants(const sp::Bvh& bvh, const Soup& soup, const sp::BvhBuildSettings& settings) {
  const std::uint32_t max_depth = std::min(settings.max_depth, std::uint32_t{SP_BVH_MAX_DEPTH});
  ASSERT_FALSE(bvh.nodes.empty());
  ASSERT_EQ(bvh.triangles.size(), soup.size());
  std::vector<int> node_refs(bvh.nodes.size(), 0), tri_refs(bvh.triangles.size(), 0);
  struct Item {
    std::uint32_t node, level;
  };
  std::vector<Item> stack{{0u, 1u}};
  std::uint32_t deepest = 0;
  node_refs[0] = 1;
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    const sp::BvhNode& n = bvh.nodes[it.node];
    deepest = std::max(deepest, it.level);
    vec3 lo(INFINITY), hi(-INFINITY);
    if (n.count > 0) {
      ASSERT_LE(std::size_t{n.left_or_first} + n.count, bvh.triangles.size());
      // Only the depth cap may overfill a leaf.
      if (it.level < max_depth) {
        EXPECT_LE(n.count, settings.max_leaf_size) << "leaf " << it.node;
      }
      for (std::uint32_t i = n.left_or_first; i < n.left_or_first + n.count; ++i) {
        ++tri_refs[i];
        const sp::BvhTriangle& t = bvh.triangles[i];
        lo = glm::min(lo, glm::min(glm::min(t.v0, t.v1), t.v2));
        hi = glm::max(hi, glm::max(glm::max(t.v0, t.v1), t.v2));
      }
    } else {
      // Children are the adjacent pair left_or_first, left_or_first + 1.
      ASSERT_LT(std::size_t{n.left_or_first} + 1, bvh.nodes.size());
      for (std::uint32_t c = n.left_or_first; c <= n.left_or_first + 1; ++c) {
        ASSERT_NE(c, 0u);
        ++node_refs[c];
        const sp::BvhNode& child = bvh.nodes[c];
        EXPECT_TRUE(glm::all(glm::lessThanEqual(n.bmin, child.bmin)) &&
                    glm::all(glm::lessThanEqual(child.bmax, n.bmax)))
            << "child " << c << " outside parent " << it.node;
        lo = glm::min(lo, child.bmin);
        hi = glm::max(hi, child.bmax);
        stack.push_back({c, it.level + 1});
      }
    }
    EXPECT_EQ(lo, n.bmin) << "bounds of node " << it.node << " are not exact";
    EXPECT_EQ(hi, n.bmax) << "bounds of node " << it.node << " are not exact";
  }
  EXPECT_EQ(deepest, bvh.depth);
  EXPECT_LE(bvh.depth, max_depth);
  EXPECT_TRUE(std::all_of(node_refs.begin(), node_refs.end(), [](int r) { return r == 1; }))
      << "a node is unreachable or shared";
  EXPECT_TRUE(std::all_of(tri_refs.begin(), tri_refs.end(), [](int r) { return r == 1; }))
      << "a triangle is not referenced exactly once";
  std::vector<int> scene_refs(soup.size(), 0);
  for (const sp::BvhTriangle& t : bvh.triangles) {
    ASSERT_LT(t.scene_index, soup.size());
    ++scene_refs[t.scene_index];
    const vec3* v = &soup.vertices[3 * std::size_t{t.scene_index}];
    const glm::dvec3 area = glm::cross(glm::dvec3(v[1]) - glm::dvec3(v[0]), glm::dvec3(v[2]) - glm::dvec3(v[0]));
    if (area == glm::dvec3(0.0)) {  // zero area: collapsed onto v0, no normal
      EXPECT_TRUE(t.v0 == v[0] && t.v1 == v[0] && t.v2 == v[0] && t.normal == vec3(0.0f));
    } else {
      EXPECT_TRUE(t.v0 == v[0] && t.v1 == v[1] && t.v2 == v[2]);
      EXPECT_NEAR(glm::length(t.normal), 1.0f, 1e-6f);
      EXPECT_NEAR(glm::dot(glm::dvec3(t.normal), area / glm::length(area)), 1.0, 1e-6);  // (v1-v0) x (v2-v0)
    }
    EXPECT_EQ(t.layer, soup.layers[t.scene_index]);
    EXPECT_EQ(t.solid, t.scene_index);  // built without topology: every triangle a piece alone
    EXPECT_EQ(t.pad0, 0u);
  }
  EXPECT_TRUE(std::all_of(scene_refs.begin(), scene_refs.end(), [](int r) { return r == 1; }));
}

TEST(Bvh, RandomSoupMatchesBruteForce) {
  Soup soup = make_random_soup(3000, 1);
  for (std::uint32_t leaf : {1u, 4u, 8u}) {
    sp::BvhBuildSettings s;
    s.max_leaf_size = leaf;
    s.bins = leaf == 8u ? 2u : 16u;
    sp::Bvh bvh = soup.build(s);
    check_invariants(bvh, soup, s);
    CompareStats st = compare_with_brute_force(bvh, rays_in_box(vec3(-12), vec3(12), 8000, leaf));
    EXPECT_EQ(st.mismatches, 0u);
    EXPECT_GT(st.hits, 4000u);
  }
}

TEST(Bvh, RoomsMatchBruteForce) {
  Soup soup = make_rooms(4, 3, 2, 2);
  sp::Bvh bvh = soup.build();
  check_invariants(bvh, soup, {});
  std::vector<Ray> rays = rays_from_surfaces(soup, 30000, 2);
  CompareStats st = compare_with_brute_force(bvh, rays);
  EXPECT_EQ(st.mismatches, 0u);
  EXPECT_GT(st.hits, 25000u);
  rays.resize(5000);
  EXPECT_GT(count_exact_ties(bvh, rays), 500u) << "the scene no longer tests tie-breaks";
  st = compare_with_brute_force(bvh, rays_in_box(vec3(-1), vec3(21, 13, 7), 10000, 3));
  EXPECT_EQ(st.mismatches, 0u);
}

// Regression test for a bug fixed in shaders/shared/sp_traverse.h: for a ray
// with a zero direction component whose origin lies exactly on a node's bmax
// plane in that axis, sp_intersect_box computed (bmax - o) * inv_dir == 0, so
// the slab "ended" at t = 0 and the node was culled although the ray runs
// inside it. Rays along walls then missed edge hits the brute force finds.
TEST(Bvh, RaysInsideBoundsPlanesMatchBruteForce) {
  Soup room;
  add_box(room, vec3(0.0f), vec3(5.0f, 4.0f, 3.0f), 1);
  sp::Bvh one = room.build();
  // From the ceiling edge, horizontally: the wall's top edge is hit (t = 5).
  sp::HitInfo h = sp::closest_hit(one, vec3(0.0f, 2.0f, 3.0f), vec3(1, 0, 0), 0.0f, kNoLimit);
  EXPECT_EQ(h.t, sp::closest_hit_brute_force(one, vec3(0.0f, 2.0f, 3.0f), vec3(1, 0, 0), 0.0f, kNoLimit).t);
  EXPECT_NE(h.triangle, SP_INVALID) << "leak through the top edge";

  Soup soup = make_rooms(4, 3, 2, 2);
  sp::Bvh bvh = soup.build();
  CompareStats st = compare_with_brute_force(bvh, rays_along_planes(soup, 20000, 13));
  EXPECT_EQ(st.mismatches, 0u);
}

// Regression test for a bug fixed in shaders/shared/sp_traverse.h: a miss is
// t == SP_FAR, which passed the (tmin, tmax] window when tmax == SP_FAR, so
// every triangle tested "hit" at SP_FAR.
TEST(Bvh, TmaxAtSpFarMissesEmptySpace) {
  Soup soup = unit_square();
  sp::Bvh bvh = soup.build();
  EXPECT_EQ(sp::closest_hit(bvh, vec3(3, 3, 0), vec3(0, 0, 1), 0.0f, SP_FAR).triangle, SP_INVALID);
  EXPECT_EQ(sp::closest_hit_brute_force(bvh, vec3(3, 3, 0), vec3(0, 0, 1), 0.0f, SP_FAR).triangle, SP_INVALID);
}

// A closed box must leak no ray from inside, edges and corners included.
TEST(Bvh, ClosedBoxFromInsideLeaksNothing) {
  Soup soup;
  add_box(soup, vec3(-2.0f, -1.0f, 0.5f), vec3(3.0f, 1.7f, 4.0f), 8);
  sp::Bvh bvh = soup.build();
  check_invariants(bvh, soup, {});
  std::vector<Ray> rays = rays_in_box(vec3(-1.9f, -0.9f, 0.6f), vec3(2.9f, 1.6f, 3.9f), 20000, 4);
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> vertex(0, soup.vertices.size() - 1);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    rays[i].tmax = kNoLimit;
    if (i % 2) rays[i].dir = glm::normalize(soup.vertices[vertex(rng)] - rays[i].origin);  // at a vertex
  }
  CompareStats st = compare_with_brute_force(bvh, rays);
  EXPECT_EQ(st.mismatches, 0u);
  EXPECT_EQ(st.hits, rays.size()) << "rays escaped the closed box";
}

TEST(Bvh, SphereMatchesBruteForceAndIsClosed) {
  Soup soup;
  add_sphere(soup, vec3(1.0f, -2.0f, 0.5f), 3.0f, 20);
  sp::Bvh bvh = soup.build();
  check_invariants(bvh, soup, {});
  std::vector<Ray> inside = rays_in_box(vec3(-0.5f, -3.5f, -1.0f), vec3(2.5f, -0.5f, 2.0f), 15000, 6);
  for (Ray& r : inside) r.tmax = kNoLimit;
  CompareStats st = compare_with_brute_force(bvh, inside);
  EXPECT_EQ(st.mismatches, 0u);
  EXPECT_EQ(st.hits, inside.size()) << "rays escaped the closed sphere";
  st = compare_with_brute_force(bvh, rays_in_box(vec3(-6, -7, -5), vec3(6, 3, 6), 10000, 7));
  EXPECT_EQ(st.mismatches, 0u);
}

TEST(Bvh, IdenticalCentroidsWithDepthCap) {
  Soup soup = make_identical_centroids(5000);
  for (std::uint32_t depth : {4u, std::uint32_t{SP_BVH_MAX_DEPTH}}) {
    sp::BvhBuildSettings s;
    s.max_depth = depth;
    sp::Bvh bvh = soup.build(s);
    check_invariants(bvh, soup, s);
    if (depth == 4u) {
      EXPECT_EQ(bvh.depth, 4u);
    } else {  // halving down to 8 triangles (11 levels), then at most 7 more
      EXPECT_LE(bvh.depth, 18u);
    }
    CompareStats st = compare_with_brute_force(bvh, rays_in_box(vec3(0), vec3(2, 3, 4), 2000, depth));
    EXPECT_EQ(st.mismatches, 0u);
    EXPECT_GT(st.hits, 400u);
  }
}

// Triangles at x = 2^i binned with 2 bins: the upper half of the centroid
// range holds only the farthest, so most levels peel off one triangle and
// only the depth cap stops the tree at SP_BVH_MAX_DEPTH levels.
TEST(Bvh, UnbalancedInputRespectsDepthLimit) {
  Soup soup;
  for (int i = 0; i < 60; ++i) {  // 42 levels without the cap
    float x = std::ldexp(1.0f, i);
    soup.tri(vec3(x, 0, 0), vec3(x, 1, 0), vec3(x, 0, 1));
  }
  sp::BvhBuildSettings s;
  s.max_leaf_size = 1;
  s.bins = 2;
  sp::Bvh bvh = soup.build(s);
  check_invariants(bvh, soup, s);
  EXPECT_EQ(bvh.depth, std::uint32_t{SP_BVH_MAX_DEPTH});
  std::vector<Ray> rays;  // each one's first hit is the triangle at 2^i
  for (int i = 0; i < 60; ++i) rays.push_back({vec3(0.0f, 0.25f, 0.25f), vec3(1, 0, 0), std::ldexp(0.75f, i), 1e18f});
  CompareStats st = compare_with_brute_force(bvh, rays);
  EXPECT_EQ(st.mismatches, 0u);
  EXPECT_EQ(st.hits, 60u);
}

TEST(Bvh, SingleTriangleIsALeafRoot) {
  Soup soup;
  soup.tri(vec3(0, 0, 2), vec3(1, 0, 2), vec3(0, 1, 2), 7);
  sp::Bvh bvh = soup.build();
  check_invariants(bvh, soup, {});
  EXPECT_EQ(bvh.depth, 1u);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].count, 1u);
  sp::HitInfo h = sp::closest_hit(bvh, vec3(0.25f, 0.25f, 0), vec3(0, 0, 1), 0.0f, kNoLimit);
  EXPECT_EQ(h.triangle, 0u);
  EXPECT_EQ(h.t, 2.0f);
  EXPECT_EQ(bvh.triangles[0].normal, vec3(0, 0, 1));
}

TEST(Bvh, UnitSquareHitsByHand) {
  Soup soup = unit_square();
  sp::Bvh bvh = soup.build();
  auto scene_hit = [&](vec3 o, vec3 d, float tmin, float tmax) {
    sp::HitInfo h = sp::closest_hit(bvh, o, d, tmin, tmax);
    sp::HitInfo b = sp::closest_hit_brute_force(bvh, o, d, tmin, tmax);
    EXPECT_EQ(h.triangle, b.triangle);
    EXPECT_EQ(h.t, b.t);
    return std::pair{h.triangle == SP_INVALID ? SP_INVALID : bvh.triangles[h.triangle].scene_index, h.t};
  };
  EXPECT_EQ(scene_hit(vec3(0.75f, 0.25f, 0), vec3(0, 0, 1), 0, kNoLimit), std::pair(0u, 5.0f));
  EXPECT_EQ(scene_hit(vec3(0.25f, 0.75f, 0), vec3(0, 0, 1), 0, kNoLimit), std::pair(1u, 5.0f));
  EXPECT_EQ(scene_hit(vec3(0.25f, 0.75f, 10), vec3(0, 0, -1), 0, kNoLimit), std::pair(1u, 5.0f));  // two-sided
  // On the shared diagonal both triangles report t = 5; the lower index wins.
  EXPECT_EQ(scene_hit(vec3(0.5f, 0.5f, 0), vec3(0, 0, 1), 0, kNoLimit), std::pair(0u, 5.0f));
  // Window (tmin, tmax]: a hit at exactly tmax counts, at exactly tmin not.
  EXPECT_EQ(scene_hit(vec3(0.25f, 0.75f, 0), vec3(0, 0, 1), 0, 5.0f), std::pair(1u, 5.0f));
  EXPECT_EQ(scene_hit(vec3(0.25f, 0.75f, 0), vec3(0, 0, 1), 0, std::nextafter(5.0f, 0.0f)).first, SP_INVALID);
  EXPECT_EQ(scene_hit(vec3(0.25f, 0.75f, 0), vec3(0, 0, 1), 5.0f, kNoLimit).first, SP_INVALID);
  EXPECT_EQ(scene_hit(vec3(0.25f, 0.75f, 0), vec3(0, 0, 1), std::nextafter(5.0f, 0.0f), kNoLimit), std::pair(1u, 5.0f));
  // Watertight: rays from anywhere through points of the diagonal never miss.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), w(-20.0f, 20.0f);
  int misses = 0;
  for (int i = 0; i < 20000; ++i) {
    float s = u(rng);
    vec3 target(s, s, 5.0f);
    vec3 o(w(rng), w(rng), (i % 2 ? 1.0f : -1.0f) * (1.0f + u(rng) * 20.0f) + 5.0f);
    if (scene_hit(o, glm::normalize(target - o), 0, kNoLimit).first == SP_INVALID) ++misses;
  }
  EXPECT_EQ(misses, 0);
}

// Coincident faces: the lower scene index wins whatever order the BVH visits.
TEST(Bvh, CoincidentTrianglesLowestSceneIndexWins) {
  const vec3 a(0, 0, 5), b(2, 0, 5), c(0, 2, 5);
  // Hand-made tree whose first-visited leaf holds the higher scene index.
  sp::Bvh bvh;
  bvh.triangles = {{a, 0, b, 9, c, 0, vec3(0, 0, 1), 0}, {a, 0, b, 3, c, 0, vec3(0, 0, 1), 0}};
  bvh.nodes = {
      {vec3(0, 0, 5), 1, vec3(2, 2, 5), 0}, {vec3(0, 0, 5), 0, vec3(2, 2, 5), 1}, {vec3(0, 0, 5), 1, vec3(2, 2, 5), 1}};
  bvh.depth = 2;
  sp::HitInfo h = sp::closest_hit(bvh, vec3(0.5f, 0.5f, 0), vec3(0, 0, 1), 0, kNoLimit);
  EXPECT_EQ(h.triangle, 1u);
  EXPECT_EQ(h.t, 5.0f);
  EXPECT_EQ(sp::closest_hit_brute_force(bvh, vec3(0.5f, 0.5f, 0), vec3(0, 0, 1), 0, kNoLimit).triangle, 1u);

  // Built trees: the copies at input positions 0 and 1, or 0 and last, among
  // many triangles, and each copy alone in its leaf.
  for (bool last : {false, true}) {
    Soup soup = make_random_soup(500, 10);
    const std::size_t second = last ? soup.vertices.size() - 3 : 3;
    for (std::size_t i : {std::size_t{0}, second}) {
      soup.vertices[i] = a;
      soup.vertices[i + 1] = b;
      soup.vertices[i + 2] = c;
    }
    sp::BvhBuildSettings s;
    s.max_leaf_size = 1;
    sp::Bvh built = soup.build(s);
    check_invariants(built, soup, s);
    for (vec3 o : {vec3(0.5f, 0.5f, -20), vec3(0.5f, 0.5f, 30)}) {
      vec3 d(0, 0, o.z < 0 ? 1.0f : -1.0f);
      sp::HitInfo hit = sp::closest_hit(built, o, d, 0, kNoLimit);
      ASSERT_NE(hit.triangle, SP_INVALID);
      EXPECT_EQ(built.triangles[hit.triangle].scene_index, 0u);
      EXPECT_EQ(hit.triangle, sp::closest_hit_brute_force(built, o, d, 0, kNoLimit).triangle);
    }
  }
}

TEST(Bvh, DegenerateTrianglesAreNeverHit) {
  Soup soup;
  soup.tri(vec3(0, 0, 5), vec3(1, 1, 5), vec3(2, 2, 5));  // collinear
  soup.tri(vec3(1, 0, 6), vec3(1, 0, 6), vec3(1, 0, 6));  // a point
  soup.tri(vec3(0, 2, 7), vec3(2, 0, 7), vec3(0, 2, 7));  // repeated vertex
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> k(-192, 192);
  auto dyadic = [&] { return vec3(float(k(rng)), float(k(rng)), float(k(rng))) / 64.0f; };
  for (int i = 0; i < 300; ++i) {  // exactly collinear: the midpoint is exact
    vec3 p = dyadic(), q = dyadic();
    soup.tri(p, q, 0.5f * (p + q));
  }
  sp::Bvh bvh = soup.build();
  check_invariants(bvh, soup, {});
  for (const sp::BvhTriangle& t : bvh.triangles) EXPECT_EQ(t.normal, vec3(0.0f)) << t.scene_index;
  std::size_t hits = 0;
  std::vector<Ray> rays = rays_in_box(vec3(-4), vec3(4), 20000, 12);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (std::size_t i = 0; i < rays.size(); i += 2) {  // aimed at points of the segments
    const vec3* v = &soup.vertices[3 * (i / 2 % soup.size())];
    rays[i].dir = glm::normalize(v[0] + u(rng) * (v[1] - v[0]) - rays[i].origin);
  }
  for (const Ray& r : rays) {
    hits += sp::closest_hit_brute_force(bvh, r.origin, r.dir, r.tmin, r.tmax).triangle != SP_INVALID;
    hits += sp::closest_hit(bvh, r.origin, r.dir, r.tmin, r.tmax).triangle != SP_INVALID;
  }
  EXPECT_EQ(sp::closest_hit(bvh, vec3(1, 1, 0), vec3(0, 0, 1), 0, kNoLimit).triangle, SP_INVALID);
  EXPECT_EQ(sp::closest_hit(bvh, vec3(1, 0, 0), vec3(0, 0, 1), 0, kNoLimit).triangle, SP_INVALID);
  EXPECT_EQ(hits, 0u);
}

// The build hands subtrees to other threads, each into a node run of its
// own, and places the runs at the end; from 128k triangles the root's passes
// and the wide copies run on two threads too. The output must be
// byte-identical to the single-threaded build (the CPU and GPU backends'
// results are compared exactly), and the same from one build to the next.
void expect_same_tree_for_every_thread_count(const Soup& soup) {
  auto build = [&](unsigned threads) {
    sp::BvhBuildSettings settings;
    settings.threads = threads;
    return sp::build_bvh(soup.vertices, soup.layers, {}, settings);
  };
  const sp::Bvh serial = build(1);
  for (unsigned threads : {1u, 2u, 0u, 4u, 2u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    const sp::Bvh other = build(threads);
    EXPECT_EQ(other.depth, serial.depth);
    ASSERT_EQ(other.nodes.size(), serial.nodes.size());
    ASSERT_EQ(other.triangles.size(), serial.triangles.size());
    EXPECT_EQ(0, std::memcmp(other.nodes.data(), serial.nodes.data(), serial.nodes.size() * sizeof(sp::BvhNode)));
    EXPECT_EQ(0, std::memcmp(other.triangles.data(), serial.triangles.data(),
                             serial.triangles.size() * sizeof(sp::BvhTriangle)));
    // The wide copies, whose packets and trees are built as tasks of their own.
    ASSERT_TRUE(other.wide && serial.wide);
    EXPECT_EQ(other.wide->depth, serial.wide->depth);
    ASSERT_EQ(other.wide->nodes.size(), serial.wide->nodes.size());
    ASSERT_EQ(other.wide->packets.size(), serial.wide->packets.size());
    EXPECT_EQ(0, std::memcmp(other.wide->nodes.data(), serial.wide->nodes.data(),
                             serial.wide->nodes.size() * sizeof(sp::WideNode)));
    EXPECT_EQ(0, std::memcmp(other.wide->packets.data(), serial.wide->packets.data(),
                             serial.wide->packets.size() * sizeof(sp::TrianglePacket)));
    EXPECT_EQ(other.wide->depth8, serial.wide->depth8);
    ASSERT_EQ(other.wide->nodes8.size(), serial.wide->nodes8.size());
    // Empty where the CPU has no AVX-512: memcmp must not see its null data().
    if (!serial.wide->nodes8.empty()) {
      EXPECT_EQ(0, std::memcmp(other.wide->nodes8.data(), serial.wide->nodes8.data(),
                               serial.wide->nodes8.size() * sizeof(sp::WideNode8)));
    }
  }
  check_invariants(serial, soup, {});
}

Soup rooms_and_random(int nx, int ny, int nz, std::uint32_t random_triangles) {
  Soup soup = make_rooms(nx, ny, nz, 6);  // 1,080 triangles per room
  const Soup random = make_random_soup(random_triangles, 11);
  soup.vertices.insert(soup.vertices.end(), random.vertices.begin(), random.vertices.end());
  soup.layers.insert(soup.layers.end(), random.layers.begin(), random.layers.end());
  return soup;
}

TEST(Bvh, ParallelBuildIsByteIdenticalToSerial) {
  const Soup soup = rooms_and_random(6, 6, 6, 20000);  // 253,280 triangles
  ASSERT_GE(soup.layers.size(), 131072u);              // the root's passes on two threads
  expect_same_tree_for_every_thread_count(soup);
}

// From 16k to 128k triangles subtrees still go to other threads while the
// root's passes and the wide copies stay on one.
TEST(Bvh, MidSizeParallelBuildIsByteIdenticalToSerial) {
  const Soup soup = rooms_and_random(4, 4, 3, 5000);  // 56,840 triangles
  ASSERT_GE(soup.layers.size(), 16384u);
  ASSERT_LT(soup.layers.size(), 131072u);
  expect_same_tree_for_every_thread_count(soup);
}

// A root of 131,072 triangles or more is binned and partitioned as two
// halves whose parts then trade places, and subtrees are built on other
// threads. Whatever the threads, every node of 16,384 triangles or more
// must still be split at one plane: on some axis, each left child's centroid lies below each right
// child's (a binned split sends bins <= k left, and the bin index never
// decreases along the axis). Centroids are computed as the build does:
// doubled, min + max.
TEST(Bvh, LargeNodesAreSplitAtOnePlane) {
  Soup soup = make_rooms(5, 5, 5, 6);
  const Soup random = make_random_soup(30000, 5);
  soup.vertices.insert(soup.vertices.end(), random.vertices.begin(), random.vertices.end());
  soup.layers.insert(soup.layers.end(), random.layers.begin(), random.layers.end());
  for (unsigned threads : {1u, 2u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    sp::BvhBuildSettings settings;
    settings.threads = threads;
    const sp::Bvh bvh = sp::build_bvh(soup.vertices, soup.layers, {}, settings);
    struct Range {
      std::uint32_t first, last;
    };
    // Leaf-order triangle range of each node: a node's leaves are contiguous.
    std::function<Range(std::uint32_t)> range = [&](std::uint32_t node) -> Range {
      const sp::BvhNode& n = bvh.nodes[node];
      if (n.count > 0u) return {n.left_or_first, n.left_or_first + n.count};
      const Range l = range(n.left_or_first), r = range(n.left_or_first + 1u);
      EXPECT_EQ(l.last, r.first) << "children of node " << node << " are not contiguous";
      return {l.first, r.last};
    };
    auto centroids = [&](Range r) {
      std::pair<vec3, vec3> box{vec3(INFINITY), vec3(-INFINITY)};
      for (std::uint32_t i = r.first; i < r.last; ++i) {
        const sp::BvhTriangle& t = bvh.triangles[i];
        const vec3 c = glm::min(glm::min(t.v0, t.v1), t.v2) + glm::max(glm::max(t.v0, t.v1), t.v2);
        box.first = glm::min(box.first, c);
        box.second = glm::max(box.second, c);
      }
      return box;
    };
    std::size_t checked = 0;
    for (std::uint32_t node = 0; node < bvh.nodes.size(); ++node) {
      const sp::BvhNode& n = bvh.nodes[node];
      if (n.count > 0u) continue;
      const Range left = range(n.left_or_first), right = range(n.left_or_first + 1u);
      if (right.last - left.first < 16384u) continue;
      ++checked;
      const auto [left_lo, left_hi] = centroids(left);
      const auto [right_lo, right_hi] = centroids(right);
      EXPECT_TRUE(left_hi.x < right_lo.x || left_hi.y < right_lo.y || left_hi.z < right_lo.z)
          << "node " << node << " (" << right.last - left.first << " triangles) is not split at one plane";
    }
    EXPECT_GE(checked, 7u);  // the root and at least two levels below it
  }
}

}  // namespace
