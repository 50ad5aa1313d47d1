// cpu_traversal: Embree as the CPU backend's optional cast. Where the
// library has no Embree, asking for it is a configuration error; where it
// has, Embree finds the same nearest surfaces as soundpaint's own traversal
// (the physics tests of test_backends and test_live_scene run on it too).
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bvh/bvh.h"
#include "sim/embree_traversal.h"
#include "sim/world_geometry.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

// The closed room with a pillar in it: walls at all angles of incidence,
// corners, and a box that shadows part of the room.
Scene room_with_pillar() {
  Scene scene = test::closed_room();
  test::add_box(scene, {0.5f, 0.0f, -0.4f}, {1.3f, 3.0f, 0.6f}, "concrete");
  return scene;
}

TEST(CpuTraversal, EmbreeIsAConfigErrorWhereItIsNotBuiltIn) {
  Config config;
  config.listener_position = glm::vec3(0, 1.5f, 0);
  config.cpu_traversal = CpuTraversal::Embree;
  const Result<World> world = make_world(room_with_pillar(), config);
  if (embree_available()) {
    ASSERT_TRUE(world.ok()) << world.error().message;
    return;
  }
  ASSERT_FALSE(world.ok());
  EXPECT_EQ(world.error().code, ErrorCode::InvalidConfig);
  EXPECT_NE(world.error().message.find("cpu_traversal"), std::string::npos) << world.error().message;
}

TEST(CpuTraversal, EmbreeFindsTheSameNearestSurfaces) {
  if (!embree_available()) GTEST_SKIP() << "built without -DSOUNDPAINT_EMBREE=ON";
  Config config;
  config.listener_position = glm::vec3(0, 1.5f, 0);
  const World world = make_world(room_with_pillar(), config).value();
  const Bvh& bvh = world.geometry->bvh;
  const EmbreeTraversal embree(bvh, 1);

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  constexpr int kRays = 4000;
  int same = 0, far_misses = 0;
  for (int i = 0; i < kRays; ++i) {
    // Inside the room (x in [-2.7, 2.7], y in [0.3, 2.7], z in [-2.2, 2.2]),
    // off the pillar.
    glm::vec3 origin(-1.5f + 1.1f * unit(rng), 1.5f + 1.1f * unit(rng), 2.0f * unit(rng));
    glm::vec3 dir(unit(rng), unit(rng), unit(rng));
    if (glm::length(dir) < 1e-3f) continue;
    dir = glm::normalize(dir);
    // Reaches short of some walls, so that misses are compared too.
    const float reach = 1.0f + 4.0f * (0.5f + 0.5f * unit(rng));
    const HitInfo ours = closest_hit(bvh, origin, dir, 0.0f, reach);
    const HitInfo theirs = embree.closest_hit(origin, dir, 0.0f, reach);
    if (ours.triangle == SP_INVALID || theirs.triangle == SP_INVALID) {
      far_misses += ours.triangle == theirs.triangle ? 0 : 1;
      same += ours.triangle == theirs.triangle ? 1 : 0;
      continue;
    }
    // The same surface point (a ray through a shared edge may name either
    // triangle), at the same distance up to float rounding.
    EXPECT_NEAR(theirs.t, ours.t, 1e-4f * ours.t + 1e-5f) << "ray " << i;
    const glm::vec3 a = glm::vec3(bvh.triangles[ours.triangle].normal);
    const glm::vec3 b = glm::vec3(bvh.triangles[theirs.triangle].normal);
    same += glm::dot(a, b) > 0.999f ? 1 : 0;
  }
  // Only rays that end within rounding of a wall may disagree on a miss.
  EXPECT_LE(far_misses, 2);
  EXPECT_GE(same, kRays - 4);
}

}  // namespace
}  // namespace sp
