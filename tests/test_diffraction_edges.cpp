// Which edges sound bends round (docs/model.md#diffraction): a box's
// convex edges, a sheet's rim, concave and buried edges left out; thin
// solids keep theirs while touching brushes bury theirs, however the level
// is exported; a refit finds them again.
#include <bit>
#include <cstddef>
#include <cstring>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bvh/diffraction_edges.h"
#include "core/glm_interop.h"
#include "sim/world_geometry.h"
#include "soundpaint/config.h"
#include "support/brush_gltf.h"
#include "support/exposed_edges.h"
#include "support/scene_builder.h"
#include "support/test_directory.h"
#include "support/thin_screen.h"

namespace sp {
namespace {

using test::add_box;
using test::add_quad;
using test::bits_at;
using test::brush_bits;
using test::level_world;

int exposed_count(const std::vector<shader::TriangleEdges>& table) {
  int n = 0;
  for (const shader::TriangleEdges& e : table) n += std::popcount(e.exposed);
  return n;
}

Bvh bvh_of(const Scene& scene) { return build_bvh(to_glm(scene.vertices), scene.triangle_layers); }


TEST(DiffractionEdges, ABoxHasTwelveConvexEdgesAtRightAngles) {
  // 12 triangles; each holds two of the box's edges (its third is a face's
  // diagonal, flat), and each box edge is held by two triangles: 24 bits.
  Scene scene;
  add_box(scene, {0, 0, 0}, {1, 2, 3}, "stone");
  const Bvh bvh = bvh_of(scene);
  const auto table = find_exposed_edges(bvh);
  ASSERT_EQ(table.size(), 12u);
  EXPECT_EQ(exposed_count(table), 24);
  for (const shader::TriangleEdges& e : table) {
    EXPECT_EQ(std::popcount(e.exposed), 2);
    for (int i = 0; i < 3; ++i) {
      if (((e.exposed >> i) & 1u) == 0u) continue;
      EXPECT_NEAR(e.turn_cos[i], 0.0f, 1e-6f);
      EXPECT_NEAR(e.turn_sin[i], 1.0f, 1e-6f);
    }
  }
}

TEST(DiffractionEdges, TheFarFaceNormalFollowsFromTheTurn) {
  // Every exposed edge of a box: cos * n + sin * o (o across the edge, out
  // of the triangle) must be the normal of the other face at that edge,
  // which for a box is the outward axis the edge's midpoint sits on.
  Scene scene;
  add_box(scene, {-1, -1, -1}, {1, 1, 1}, "stone");
  const Bvh bvh = bvh_of(scene);
  const auto table = find_exposed_edges(bvh);
  for (std::size_t t = 0; t < bvh.triangles.size(); ++t) {
    const BvhTriangle& tri = bvh.triangles[t];
    const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
    for (int i = 0; i < 3; ++i) {
      if (((table[t].exposed >> i) & 1u) == 0u) continue;
      const glm::vec3 along = glm::normalize(v[(i + 1) % 3] - v[i]);
      const glm::vec3 out = glm::cross(along, tri.normal);
      const glm::vec3 far = tri.normal * table[t].turn_cos[i] + out * table[t].turn_sin[i];
      // The midpoint of a box edge has two coordinates at +-1: one is this
      // face's axis, the other the far face's.
      const glm::vec3 mid = 0.5f * (v[i] + v[(i + 1) % 3]);
      const glm::vec3 expected = mid - tri.normal * glm::dot(mid, tri.normal);  // drop this face's axis
      EXPECT_NEAR(glm::distance(far, expected), 0.0f, 1e-5f);
    }
  }
}

TEST(DiffractionEdges, ASheetsRimIsAFreeBoundary) {
  Scene scene;
  add_quad(scene, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, "pane");
  const auto table = find_exposed_edges(bvh_of(scene));
  EXPECT_EQ(exposed_count(table), 4);  // the diagonal is shared and flat
  for (const shader::TriangleEdges& e : table)
    for (int i = 0; i < 3; ++i)
      if ((e.exposed >> i) & 1u) {
        EXPECT_EQ(e.turn_cos[i], -1.0f);
        EXPECT_EQ(e.turn_sin[i], 0.0f);
      }
}

TEST(DiffractionEdges, ConcaveAndBuriedEdgesAreNotExposed) {
  // Two quads meeting at x = 0 along z. Fronts facing into the corner
  // (a room's floor and wall): concave, never exposed; only the rims are.
  Scene inner;
  add_quad(inner, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, "floor");  // y = 0, front +y
  add_quad(inner, {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, "wall");   // x = 0, front +x
  const auto concave = find_exposed_edges(bvh_of(inner));
  // 8 rim edges of the two quads, less the shared one counted by neither.
  EXPECT_EQ(exposed_count(concave), 6);
  // The same quads facing away from each other: a convex ridge, exposed.
  Scene outer;
  add_quad(outer, {0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, "floor");  // y = 0, front -y
  add_quad(outer, {0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}, "wall");   // x = 0, front -x
  EXPECT_EQ(exposed_count(find_exposed_edges(bvh_of(outer))), 8);

  // A block standing on a slab: its bottom edges touch the slab's top, so
  // they are buried; its four top and four upright edges stay exposed.
  Scene standing;
  add_box(standing, {-5, -1, -5}, {5, 0, 5}, "slab");
  add_box(standing, {0, 0, 0}, {1, 1, 1}, "block");
  const Bvh bvh = bvh_of(standing);
  const auto table = find_exposed_edges(bvh);
  int block_bits = 0;
  for (std::size_t t = 0; t < bvh.triangles.size(); ++t)
    if (bvh.triangles[t].layer == 1u) block_bits += std::popcount(table[t].exposed);
  EXPECT_EQ(block_bits, 2 * 8);
}

TEST(DiffractionEdges, RefitFindsThemAgainWhenTheyAreKept) {
  // A block lifted off a slab uncovers its bottom edges.
  Scene scene;
  add_box(scene, {-5, -1, -5}, {5, 0, 5}, "slab");
  add_box(scene, {0, 0, 0}, {1, 1, 1}, "block");
  Bvh bvh = bvh_of(scene);
  bvh.edges = find_exposed_edges(bvh);
  const int before = exposed_count(bvh.edges);
  std::vector<glm::vec3> moved = to_glm(scene.vertices);
  for (std::size_t k = 36; k < moved.size(); ++k) moved[k].y += 0.5f;
  const BvhChanges changes = refit_bvh(bvh, moved).value();
  EXPECT_FALSE(changes.edges.empty());
  EXPECT_EQ(exposed_count(bvh.edges), before + 2 * 4);
  // Found again near what moved only, the same as from scratch.
  const auto fresh = find_exposed_edges(bvh);
  ASSERT_EQ(fresh.size(), bvh.edges.size());
  EXPECT_EQ(std::memcmp(fresh.data(), bvh.edges.data(), fresh.size() * sizeof(fresh[0])), 0);
  // And back down: buried again.
  ASSERT_TRUE(refit_bvh(bvh, to_glm(scene.vertices)).ok());
  EXPECT_EQ(exposed_count(bvh.edges), before);
}

TEST(DiffractionEdges, AThinScreensOwnFacesNeverBuryItsEdges) {
  // Closed boxes 1 and 2 cm thick: each edge's midpoint lies about t/2 from
  // the other triangle of the narrow face it bounds (their diagonal runs
  // through the face's centre), which buried every edge (issue 38). Faces
  // of the edge's own solid no longer bury it.
  for (float t : {0.01f, 0.02f}) {
    SCOPED_TRACE(t);
    Scene alone;
    add_box(alone, {-2, 0, -0.5f * t}, {0, 2.5f, 0.5f * t}, "glass");
    const World lone = level_world(alone);
    EXPECT_EQ(exposed_count(lone.geometry->bvh.edges), 24);  // all 12 edges, as any box
    for (const shader::TriangleEdges& e : lone.geometry->bvh.edges) {
      for (int i = 0; i < 3; ++i) {
        if ((e.exposed >> i) & 1u) {
          EXPECT_NEAR(e.turn_sin[i], 1.0f, 1e-6f);
        }
      }
    }

    // Standing on a floor brush, before a back wall: the floor buries the
    // screen's 4 bottom edges and nothing else of it.
    const World level = level_world(test::thin_screen_level(t));
    const Bvh& bvh = level.geometry->bvh;
    EXPECT_EQ(brush_bits(bvh, 0), 24);  // the floor: the wall meets its rim 1.5 m from the rim's midpoint
    EXPECT_EQ(brush_bits(bvh, 1), 16);  // the screen: 4 top and 4 upright edges
    EXPECT_EQ(brush_bits(bvh, 2), 16);  // the wall: all but its 4 bottom edges
    for (float z : {-0.5f * t, 0.5f * t}) {
      EXPECT_EQ(bits_at(bvh, {0, 1.25f, z}), 2);   // the free upright edges
      EXPECT_EQ(bits_at(bvh, {-2, 1.25f, z}), 2);  // and the far ones
      EXPECT_EQ(bits_at(bvh, {-1, 2.5f, z}), 2);   // the top
      EXPECT_EQ(bits_at(bvh, {-1, 0, z}), 0);      // the bottom, on the floor
    }
    EXPECT_EQ(bits_at(bvh, {0, 2.5f, 0}), 2);
    EXPECT_EQ(bits_at(bvh, {0, 0, 0}), 0);
  }
}

TEST(DiffractionEdges, TouchingBrushesStillBuryTheEdgesWhereTheyMeet) {
  // All on one layer, as a level merged into one mesh: only the triangles'
  // shared edges tell the brushes apart, and touching brushes share none.
  Scene scene;
  add_box(scene, {-5, -0.3f, -5}, {5, 0, 5}, "level");           // 0: a floor
  add_box(scene, {-3, 0, -0.1f}, {3, 2.5f, 0.1f}, "level");      // 1: a wall standing on it
  add_box(scene, {-0.5f, 0, -0.6f}, {0.5f, 1, -0.1f}, "level");  // 2: a block on both, flush with the wall
  const World world = level_world(scene);
  const Bvh& bvh = world.geometry->bvh;
  EXPECT_EQ(brush_bits(bvh, 0), 24);
  EXPECT_EQ(brush_bits(bvh, 1), 16);          // all but its 4 bottom edges
  EXPECT_EQ(brush_bits(bvh, 2), 10);          // its top front and top side edges, its front uprights
  EXPECT_EQ(bits_at(bvh, {0, 1, -0.1f}), 0);  // the block's back edges lie on the wall
  EXPECT_EQ(bits_at(bvh, {0.5f, 0.5f, -0.1f}), 0);
  EXPECT_EQ(bits_at(bvh, {0, 1, -0.6f}), 2);

  // A 1 cm pane between two jambs, on the floor: the jambs bury its sides,
  // though its own faces no longer do; only its top rim diffracts.
  Scene frame;
  add_box(frame, {-5, -0.3f, -5}, {5, 0, 5}, "level");
  add_box(frame, {-1.1f, 0, -0.05f}, {-1, 2.2f, 0.05f}, "level");
  add_box(frame, {1, 0, -0.05f}, {1.1f, 2.2f, 0.05f}, "level");
  add_box(frame, {-1, 0, -0.005f}, {1, 2, 0.005f}, "level");
  const World framed = level_world(frame);
  const Bvh& pane = framed.geometry->bvh;
  EXPECT_EQ(brush_bits(pane, 1), 16);  // a jamb: the pane's top lies 20 cm below its own
  EXPECT_EQ(brush_bits(pane, 2), 16);
  EXPECT_EQ(brush_bits(pane, 3), 4);
  EXPECT_EQ(bits_at(pane, {0, 2, -0.005f}), 2);
  EXPECT_EQ(bits_at(pane, {0, 2, 0.005f}), 2);
}

class DiffractionLevelFiles : public test::TestDirectory {};

TEST_F(DiffractionLevelFiles, SolidsComeFromSharedEdgesHoweverTheLevelIsExported) {
  // The thin-screen level written with a node per brush, and merged into
  // one mesh on one layer: the loader keeps the triangles' order, and the
  // same edges are exposed either way.
  const Scene built = test::thin_screen_level(0.01f);
  for (bool merged : {false, true}) {
    SCOPED_TRACE(merged ? "merged" : "a node per brush");
    const test::GltfBuilder file = merged ? test::gltf_merged(built) : test::gltf_node_per_brush(built);
    const Scene loaded = load_scene(write("level.gltf", file.gltf())).value();
    ASSERT_EQ(loaded.triangle_count(), built.triangle_count());
    EXPECT_EQ(loaded.layer_names.size(), merged ? 1u : 3u);
    const World world = level_world(loaded);
    const Bvh& bvh = world.geometry->bvh;
    EXPECT_EQ(brush_bits(bvh, 0), 24);
    EXPECT_EQ(brush_bits(bvh, 1), 16);
    EXPECT_EQ(brush_bits(bvh, 2), 16);
    EXPECT_EQ(bits_at(bvh, {0, 1.25f, -0.005f}), 2);
    EXPECT_EQ(bits_at(bvh, {0, 1.25f, 0.005f}), 2);
  }
}

}  // namespace
}  // namespace sp
