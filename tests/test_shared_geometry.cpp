// One level's geometry, built once, serves every world made from it:
// simulators of both backends and the penetration probe share it, other
// settings need no rebuild, and only a scene whose moving parts move gets a
// copy of its own (issue 36, item 1).
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "bvh/bvh.h"
#include "core/glm_interop.h"
#include "sim/world_geometry.h"
#include "soundpaint/check.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

using test::closed_room;

Config room_config() {
  Config config;
  config.listener_position = glm::vec3(0.0f, 1.5f, 0.0f);
  config.ray_budget = 200;
  return config;
}

class SharedGeometry : public test::GpuTest {};

TEST_F(SharedGeometry, OneGeometryServesACpuAndAGpuSimulatorAndAProbe) {
  const Scene scene = closed_room();
  const std::uint64_t before = bvh_builds();
  const WorldGeometryHandle geometry = build_geometry(scene).value();
  EXPECT_EQ(bvh_builds(), before + 1);

  Config config = room_config();
  auto cpu = make_simulator(make_world(scene, config, geometry).value(), Backend::Cpu);
  config.ray_budget = 300;  // other settings, the same geometry
  config.max_bounces = 2;
  auto gpu = make_simulator(make_world(scene, config, geometry).value(), Backend::Gpu);
  const PenetrationProbe probe = probe_penetration(scene, config, CheckSettings{}, geometry).value();
  (void)test::run_steps(*cpu, 3);
  (void)test::run_steps(*gpu, 3);
  EXPECT_GT(probe.penetrations, 0u);
  EXPECT_EQ(bvh_builds(), before + 1) << "a world, a backend or a probe built the level again";
  EXPECT_TRUE(cpu->world().geometry.shares_with(geometry));
  EXPECT_TRUE(gpu->world().geometry.shares_with(geometry));
}

// Diffraction's edges are found the first time a world asks, once for
// every holder; worlds without diffraction never need them.
TEST_F(SharedGeometry, DiffractionsEdgesAreFoundOnceWhenAWorldFirstAsks) {
  const Scene scene = closed_room();
  const WorldGeometryHandle geometry = build_geometry(scene).value();
  EXPECT_TRUE(geometry->bvh.edges.empty());
  Config config = room_config();
  const World plain = make_world(scene, config, geometry).value();
  EXPECT_TRUE(geometry->bvh.edges.empty());
  config.diffraction.enabled = true;
  const std::uint64_t before = bvh_builds();
  const World bending = make_world(scene, config, geometry).value();
  EXPECT_EQ(geometry->bvh.edges.size(), geometry->bvh.triangles.size());
  EXPECT_TRUE(bending.geometry.shares_with(plain.geometry));
  EXPECT_EQ(bvh_builds(), before);
}

// A moving part's first move copies the geometry for that scene alone.
TEST_F(SharedGeometry, AMovingPartMovesItsOwnCopy) {
  Scene scene = closed_room();
  test::add_box(scene, {1.0f, 0.0f, 1.0f}, {1.1f, 2.0f, 2.0f}, "wood");  // a door
  scene.instance_names = {"door"};
  scene.triangle_instances.assign(scene.triangle_count(), kStaticInstance);
  for (std::size_t t = scene.triangle_count() - 12; t < scene.triangle_count(); ++t) scene.triangle_instances[t] = 0;
  const WorldGeometryHandle geometry = build_geometry(scene).value();
  auto moving = make_simulator(make_world(scene, room_config(), geometry).value(), Backend::Cpu);
  auto still = make_simulator(make_world(scene, room_config(), geometry).value(), Backend::Cpu);
  const glm::mat4 swing = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0));
  ASSERT_TRUE(moving->scene().set_instance_transform(0, swing).ok());
  ASSERT_TRUE(moving->step().ok());
  ASSERT_TRUE(still->step().ok());
  EXPECT_FALSE(moving->world().geometry.shares_with(geometry));
  EXPECT_TRUE(still->world().geometry.shares_with(geometry));
}

TEST(SharedGeometryErrors, AGeometryOfAnotherSceneIsRefused) {
  const WorldGeometryHandle geometry = build_geometry(closed_room()).value();
  Scene other = closed_room();
  test::add_box(other, {0, 0, 0}, {0.5f, 0.5f, 0.5f}, "wood");
  const auto world = make_world(other, room_config(), geometry);
  ASSERT_FALSE(world.ok());
  EXPECT_EQ(world.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(world.error().message.find("another scene"), std::string::npos) << world.error().message;
}

}  // namespace
}  // namespace sp
