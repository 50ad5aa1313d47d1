// The public API's own vector, matrix and indicator types (soundpaint/math.h,
// soundpaint/simulation.h): what a host passes in is what the library sees.
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "core/glm_interop.h"
#include "sim/indicator_convert.h"
#include "sim/world_geometry.h"
#include "soundpaint/math.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {

// An engine's own vector type: any x, y, z with a (x, y, z) constructor.
struct EngineVector {
  float x, y, z;
  EngineVector(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
};

TEST(PublicMath, Vec3TakesAndGivesAnyVectorOfThreeFloats) {
  const Vec3 from_glm = glm::vec3(1.5f, -2.0f, 3.25f);
  EXPECT_EQ(from_glm, Vec3(1.5f, -2.0f, 3.25f));
  const glm::vec3 back = from_glm;
  EXPECT_EQ(back, glm::vec3(1.5f, -2.0f, 3.25f));
  const EngineVector engine = Vec3(4.0f, 5.0f, 6.0f);
  EXPECT_EQ(engine.x, 4.0f);
  EXPECT_EQ(engine.z, 6.0f);
  EXPECT_EQ(Vec3(EngineVector(7.0f, 8.0f, 9.0f)), Vec3(7.0f, 8.0f, 9.0f));
  Vec3 indexed(1.0f, 2.0f, 3.0f);
  indexed[1] = 5.0f;
  EXPECT_EQ(indexed[0] + indexed[1] + indexed[2], 9.0f);
}

TEST(PublicMath, ConversionsThatWouldLoseOrInventDataAreRefused) {
  static_assert(!std::is_convertible_v<glm::vec4, Vec3>, "a 4-vector must not silently lose its w");
  static_assert(!std::is_convertible_v<glm::vec2, Vec3>);
  static_assert(!std::is_convertible_v<std::vector<Vec3>, Mat4>, "a container of vectors is not a matrix");
  static_assert(!std::is_convertible_v<glm::mat3, Mat4>);
  static_assert(std::is_convertible_v<glm::mat4, Mat4> && std::is_convertible_v<Mat4, glm::mat4>);
  SUCCEED();
}

TEST(PublicMath, Mat4IsColumnMajorAsGlmAndDefaultsToIdentity) {
  EXPECT_EQ(glm::mat4(Mat4{}), glm::mat4(1.0f));
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 2.0f, 1.0f)) *
                          glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f));
  const Mat4 ours = moved;
  EXPECT_EQ(ours.translation(), Vec3(3.0f, 2.0f, 1.0f));
  EXPECT_EQ(ours[3][0], 3.0f);
  EXPECT_FLOAT_EQ(ours[0][2], -std::sin(0.5f));  // column 0, row 2: glm's m[0][2]
  EXPECT_EQ(to_glm(ours), moved);
  Camera camera;
  camera.world = moved;
  EXPECT_EQ(camera.position(), Vec3(3.0f, 2.0f, 1.0f));
}

TEST(PublicMath, IndicatorsCrossTheApiBitForBit) {
  shader::Indicator inner{};
  inner.position = glm::vec3(1.0f, 2.0f, 3.0f);
  inner.energy = 0.5f;
  inner.normal = glm::vec3(0.0f, 1.0f, 0.0f);
  inner.size = 0.25f;
  inner.color = glm::vec3(0.9f, 0.6f, 0.0f);
  inner.intensity = 0.75f;
  inner.dir = glm::vec3(0.0f, -1.0f, 0.0f);
  inner.path_length = 4.5f;
  inner.kind = SP_INDICATOR_EXIT;
  inner.source_id = 7;
  inner.bounces = 2;
  inner.penetrations = 1;
  inner.diffractions = 1;
  inner.step = 11;
  inner.ray_index = 13;
  inner.iteration = 3;
  const Indicator outer = to_public(inner);
  EXPECT_EQ(outer.position, Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(outer.normal, Vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(outer.color, Vec3(0.9f, 0.6f, 0.0f));
  EXPECT_EQ(outer.dir, Vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(outer.energy, 0.5f);
  EXPECT_EQ(outer.size, 0.25f);
  EXPECT_EQ(outer.intensity, 0.75f);
  EXPECT_EQ(outer.path_length, 4.5f);
  EXPECT_EQ(outer.kind, kIndicatorExit);
  EXPECT_EQ(outer.source_id, 7u);
  EXPECT_EQ(outer.bounces, 2u);
  EXPECT_EQ(outer.penetrations, 1u);
  EXPECT_EQ(outer.diffractions, 1u);
  EXPECT_EQ(outer.step, 11u);
  EXPECT_EQ(outer.ray_index, 13u);
  EXPECT_EQ(outer.iteration, 3u);
  const shader::Indicator round_trip = to_shader(outer);
  EXPECT_EQ(std::memcmp(&round_trip, &inner, sizeof inner), 0);
}

// A World of one triangle.
World one_triangle_world() {
  Scene scene;
  scene.vertices = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  scene.triangle_layers = {0};
  scene.layer_names = {"concrete"};
  Config config;
  config.listener_position = Vec3(0.0f, 0.0f, 0.0f);
  return make_world(scene, config).value();
}

// Copies share one geometry (no deep copy); a change (a refit, through
// mutate()) gives the changed copy its own, and never reaches the others.
TEST(PublicMath, WorldCopiesShareTheirGeometryUntilOneChangesIt) {
  const World world = one_triangle_world();
  World copy = world;
  EXPECT_EQ(copy.triangle_count(), 1u);
  EXPECT_TRUE(copy.geometry.shares_with(world.geometry));
  copy.geometry.mutate().bvh.triangles.clear();
  EXPECT_FALSE(copy.geometry.shares_with(world.geometry));
  EXPECT_EQ(world.triangle_count(), 1u) << "a copy's refit or rebuild must not reach the original";
  EXPECT_EQ(copy.triangle_count(), 0u);
}

// A moved-from World is left empty, not broken: reading, copying and
// assigning it must not reach a null geometry.
TEST(PublicMath, AMovedFromWorldReadsAsEmpty) {
  World moved_from = one_triangle_world();
  const World taken = std::move(moved_from);
  EXPECT_EQ(taken.triangle_count(), 1u);
  EXPECT_EQ(std::as_const(moved_from).triangle_count(), 0u);
  const World copy = moved_from;
  EXPECT_EQ(copy.triangle_count(), 0u);
  World assigned = taken;
  assigned = moved_from;
  EXPECT_EQ(assigned.triangle_count(), 0u);
  // Written to, it gets geometry of its own again.
  moved_from.geometry.mutate().bvh.triangles = taken.geometry->bvh.triangles;
  EXPECT_EQ(moved_from.triangle_count(), 1u);
}

}  // namespace
}  // namespace sp
