// The public ray query (soundpaint/ray_query.h) against distances derived
// by hand in the test room: inside walls from x -3..3, y 0..3, z -2.5..2.5.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "soundpaint/ray_query.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

World room() {
  Scene scene = test::closed_room();
  Config config;
  config.listener_position = glm::vec3(-2.0f, 1.5f, 1.5f);
  config.layers["concrete"] = {1.0f, 5.0f};
  return make_world(scene, config).value();
}

TEST(RayQuery, FindsTheNearestSurfaceWithItsNormalFacingTheOrigin) {
  const World world = room();
  const Scene scene = test::closed_room();
  struct Case {
    Vec3 direction;
    float distance;
    Vec3 normal;
  };
  // From (1, 1.2, 0.5): floor 1.2 below, ceiling 1.8 above, +x wall 2 away,
  // -z wall 3 away; a direction of any length.
  const Case cases[] = {{{0, -1, 0}, 1.2f, {0, 1, 0}},
                        {{0, 5, 0}, 1.8f, {0, -1, 0}},
                        {{0.5f, 0, 0}, 2.0f, {-1, 0, 0}},
                        {{0, 0, -1}, 3.0f, {0, 0, 1}}};
  const Vec3 origin(1.0f, 1.2f, 0.5f);
  for (const Case& c : cases) {
    const std::optional<RayHit> hit = cast_ray(world, origin, c.direction).value();
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance, c.distance, 1e-5f);
    const float length =
        std::sqrt(c.direction.x * c.direction.x + c.direction.y * c.direction.y + c.direction.z * c.direction.z);
    EXPECT_NEAR(hit->position.x, origin.x + c.direction.x / length * c.distance, 1e-5f);
    EXPECT_NEAR(hit->position.y, origin.y + c.direction.y / length * c.distance, 1e-5f);
    EXPECT_NEAR(hit->position.z, origin.z + c.direction.z / length * c.distance, 1e-5f);
    EXPECT_NEAR(hit->normal.x, c.normal.x, 1e-6f);
    EXPECT_NEAR(hit->normal.y, c.normal.y, 1e-6f);
    EXPECT_NEAR(hit->normal.z, c.normal.z, 1e-6f);
    EXPECT_EQ(world.layer_names[hit->layer], "concrete");
    // The triangle index is the scene's: its plane holds the hit point.
    ASSERT_LT(hit->triangle, scene.triangle_count());
    const Vec3 a = scene.vertices[3 * std::size_t(hit->triangle)];
    const float plane = (hit->position.x - a.x) * c.normal.x + (hit->position.y - a.y) * c.normal.y +
                        (hit->position.z - a.z) * c.normal.z;
    EXPECT_NEAR(plane, 0.0f, 1e-5f);
  }
}

TEST(RayQuery, NothingWithinMaxDistanceIsNoHit) {
  const World world = room();
  const Vec3 origin(1.0f, 1.2f, 0.5f);
  EXPECT_FALSE(cast_ray(world, origin, {0, -1, 0}, 1.1f).value().has_value());
  EXPECT_TRUE(cast_ray(world, origin, {0, -1, 0}, 1.3f).value().has_value());
  // Outside the room, looking away from it.
  EXPECT_FALSE(cast_ray(world, {0, 10, 0}, {0, 1, 0}).value().has_value());
}

TEST(RayQuery, BadArgumentsAreErrorsNamingThem) {
  const World world = room();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Vec3 origin(1.0f, 1.2f, 0.5f);
  Result<std::optional<RayHit>> r = cast_ray(world, {nan, 0, 0}, {0, -1, 0});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(r.error().message.find("finite"), std::string::npos);
  r = cast_ray(world, origin, {0, 0, 0});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("direction"), std::string::npos);
  r = cast_ray(world, origin, {0, -1, 0}, 0.0f);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("max_distance"), std::string::npos);
  r = cast_ray(world, origin, {0, -1, 0}, nan);
  ASSERT_FALSE(r.ok());
}

}  // namespace
}  // namespace sp
