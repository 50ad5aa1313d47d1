// Physics with hand-derived expectations, run on both backends.
#include <cmath>
#include <map>
#include <set>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/glm_interop.h"
#include "sp_types.h"
#include "support/backend_cases.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

using Outcome = test::Recorded;
using test::closed_room;

class BackendPhysics : public test::GpuTest, public ::testing::WithParamInterface<test::BackendCase> {
 protected:
  Outcome run(const Scene& scene, const Config& config, int steps) {
    auto sim = make_simulator(make_world(scene, test::with_traversal(config, GetParam())).value(), GetParam().backend);
    return test::run_steps(*sim, static_cast<std::uint64_t>(steps));
  }
};

Config base_config() {
  Config c;
  c.listener_position = glm::vec3(0, 1.5f, 0);
  c.ray_budget = 300;
  c.min_energy = 0.001f;
  return c;
}

TEST_P(BackendPhysics, ClosedMirrorRoomLeaksNothingAndLosesOnlyAirEnergy) {
  Config config = base_config();
  config.layers["concrete"] = {1.0f, 5.0f};
  config.bounce_energy_loss = 0.0f;
  config.air_attenuation = 0.01f;
  config.max_bounces = 5;
  Outcome out = run(closed_room(), config, 2);
  EXPECT_EQ(out.stats.rays_emitted, 600u);
  EXPECT_EQ(out.stats.casts, 600u * 6);  // max_bounces + 1 hits per ray, never a miss
  EXPECT_EQ(out.stats.layers[0].hits, out.stats.casts);
  ASSERT_EQ(out.indicators.size(), out.stats.casts);
  for (const Indicator& ind : out.indicators) EXPECT_NEAR(ind.energy, 1.0f - 0.01f * ind.path_length, 2e-5f);
}

TEST_P(BackendPhysics, BounceLossAloneGivesGeometricEnergy) {
  Config config = base_config();
  config.layers["concrete"] = {1.0f, 0.0f};
  config.bounce_energy_loss = 0.25f;
  config.air_attenuation = 0.0f;
  config.max_bounces = 4;
  Outcome out = run(closed_room(), config, 1);
  ASSERT_FALSE(out.indicators.empty());
  for (const Indicator& ind : out.indicators) EXPECT_NEAR(ind.energy, std::pow(0.75, ind.bounces), 1e-6);
}

TEST_P(BackendPhysics, SlabCostsAttenuationTimesThicknessOverCosine) {
  // Source at the origin; wall x in [1, 1.2] that every ray penetrates. An
  // exit point p on the far face lies on the straight line from the source:
  // cos(theta) = p.x / |p|, so E = E0 - alpha * 0.2 / cos(theta).
  Scene scene;
  test::add_box(scene, {1.0f, -40, -40}, {1.2f, 40, 40}, "wood");
  scene.sources.push_back(test::source_at({0, 0, 0}));
  Config config = base_config();
  config.listener_position = glm::vec3(0.0f);
  config.layers["wood"] = {0.0f, 1.5f};
  config.air_attenuation = 0.0f;
  config.max_wall_thickness = 0.5f;  // paths longer than this (cos < 0.4) are absorbed
  config.max_bounces = 3;
  Outcome out = run(scene, config, 2);
  int exits = 0;
  for (const Indicator& ind : out.indicators) {
    if (ind.kind != SP_INDICATOR_EXIT) continue;
    ++exits;
    float cos_theta = sp::to_glm(ind.position).x / glm::length(sp::to_glm(ind.position));
    EXPECT_NEAR(ind.position.x, 1.2f, 1e-5f);
    EXPECT_GE(0.2f / cos_theta, 0.0f);
    EXPECT_LE(0.2f / cos_theta, 0.5f + 1e-4f) << "a path longer than W_max must be absorbed";
    EXPECT_NEAR(ind.energy, 1.0f - 1.5f * 0.2f / cos_theta, 2e-4f);
    EXPECT_NEAR(ind.path_length, glm::length(sp::to_glm(ind.position)), 2e-4f);
  }
  EXPECT_GT(exits, 50);
  const auto& wood = out.stats.layers[0];
  EXPECT_EQ(wood.reflections, 0u);
  EXPECT_EQ(wood.penetrations, wood.hits);
  // rays with cos(theta) < 0.4 enter but find no exit within W_max
  EXPECT_GT(wood.no_way_out, 0u);
  EXPECT_EQ(wood.penetrations - wood.no_way_out, static_cast<std::uint64_t>(exits));
}

TEST_P(BackendPhysics, SourceBeyondScanRadiusEmitsNothing) {
  Config config = base_config();
  config.scan_radius = 2.0f;
  config.listener_position = glm::vec3(-2.5f, 1.5f, 0.2f);  // 3 m from the source
  Outcome out = run(closed_room(), config, 3);
  EXPECT_EQ(out.stats.rays_emitted, 0u);
  EXPECT_EQ(out.stats.casts, 0u);
  EXPECT_TRUE(out.indicators.empty());
}

TEST_P(BackendPhysics, ZeroBudgetEmitsNothing) {
  Config config = base_config();
  config.ray_budget = 0;
  Outcome out = run(closed_room(), config, 3);
  EXPECT_EQ(out.stats.steps, 3u);
  EXPECT_EQ(out.stats.rays_emitted, 0u);
  EXPECT_TRUE(out.live.empty());
}

TEST_P(BackendPhysics, IntensityAndSizeFollowTheFormulas) {
  Scene scene = closed_room();
  scene.sources[0].max_distance = 10.0f;
  scene.sources[0].loudness = 2.0f;
  Config config = base_config();
  config.listener_position = glm::vec3(-2.5f, 1.5f, 0.2f);  // d_ls = 3 m
  config.indicator_size = 0.4f;
  Outcome out = run(scene, config, 1);
  ASSERT_FALSE(out.indicators.empty());
  for (const Indicator& ind : out.indicators) {
    EXPECT_FLOAT_EQ(ind.intensity, 0.7f);
    EXPECT_NEAR(ind.size, 0.4f * ind.energy / 2.0f, 1e-6f);
  }
  // opacity = I * (1 - age / lifetime), zero once expired
  EXPECT_FLOAT_EQ(indicator_opacity(out.indicators[0], 0.25, 1.0f), 0.7f * 0.75f);
  EXPECT_FLOAT_EQ(indicator_opacity(out.indicators[0], 2.0, 1.0f), 0.0f);
}

TEST_P(BackendPhysics, RingKeepsSpotsForTheirLifetimeWithinCapacity) {
  // quota ceil(64 * 0.1 / 0.4) = 16 a step; a spot is alive 4 steps.
  Config config = base_config();
  config.max_indicators = 64;
  config.indicator_lifetime = 0.4f;
  config.dt = 0.1;
  Outcome out = run(closed_room(), config, 10);
  ASSERT_GT(out.stats.indicators, 640u) << "every step makes more than its quota";
  EXPECT_LE(out.live.size(), 64u);
  EXPECT_GE(out.live.size(), 48u);
  std::map<std::uint32_t, std::uint32_t> per_step;
  for (const Indicator& ind : out.live) per_step[ind.step] += 1;
  EXPECT_EQ(per_step.size(), 4u) << "steps 6..9 alive: none overwritten early";
  for (auto [step, count] : per_step) {
    EXPECT_GE(step, 6u);
    EXPECT_LE(count, 16u);
  }
}

TEST_P(BackendPhysics, ManySourcesSplitTheBudget) {
  Scene scene = closed_room();
  scene.sources.clear();
  for (int k = 0; k < 7; ++k) scene.sources.push_back(test::source_at({-2.5f + 0.8f * float(k), 1.0f, 0.0f}));
  Config config = base_config();
  config.ray_budget = 100;  // 100 = 7 * 14 + 2: the two lowest ids get 15
  Outcome out = run(scene, config, 1);
  EXPECT_EQ(out.stats.rays_emitted, 100u);
  std::vector<std::set<std::uint32_t>> rays_of(7);
  for (const Indicator& ind : out.indicators) rays_of[ind.source_id].insert(ind.ray_index);
  EXPECT_EQ(rays_of[0].size(), 15u);
  EXPECT_EQ(rays_of[1].size(), 15u);
  EXPECT_EQ(rays_of[2].size(), 14u);
  EXPECT_EQ(rays_of[6].size(), 14u);
}

class GpuLimits : public test::GpuTest {};

TEST_F(GpuLimits, BudgetBeyondTheStorageBufferRangeFailsCleanly) {
  // 2M rays of 96-byte state need 192 MB in one binding: beyond lavapipe's
  // 128 MiB maxStorageBufferRange (and most GPUs' binding limits too).
  Config config = base_config();
  config.ray_budget = 2'000'000;
  const auto range = test::GpuEnvironment::context()->properties().limits.maxStorageBufferRange;
  if (std::uint64_t{config.ray_budget} * sizeof(shader::RayState) <= range) GTEST_SKIP() << "device range too large";
  auto sim = gpu::create_simulator(make_world(closed_room(), config).value(), *test::GpuEnvironment::context());
  ASSERT_FALSE(sim.ok());
  EXPECT_EQ(sim.error().code, ErrorCode::LimitExceeded);
  EXPECT_NE(sim.error().message.find("rays"), std::string::npos) << sim.error().message;
  EXPECT_NE(sim.error().message.find("maxStorageBufferRange"), std::string::npos) << sim.error().message;
}

TEST_F(GpuLimits, StepsAfterTheBudgetSplitNeverExceedTheBuffers) {
  // Budget 1 with 7 sources: one ray goes to source 0, the rest get none.
  Scene scene = closed_room();
  for (int k = 0; k < 6; ++k) scene.sources.push_back(test::source_at({-2.0f + 0.5f * float(k), 1.0f, 0.0f}));
  Config config = base_config();
  config.ray_budget = 1;
  auto sim = make_simulator(make_world(scene, config).value(), Backend::Gpu);
  for (int n = 0; n < 4; ++n) ASSERT_TRUE(sim->step().ok());
  auto stats = sim->stats().value();
  EXPECT_EQ(stats.rays_emitted, 4u);
  for (const Indicator& ind : sim->last_step_indicators().value()) EXPECT_EQ(ind.source_id, 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, BackendPhysics, ::testing::ValuesIn(test::backend_cases()), test::backend_case_name);

}  // namespace
}  // namespace sp
