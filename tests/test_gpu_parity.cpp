// The GPU backend against the CPU reference: the same world and seed must
// give the same indicators. Both run the shared ray model (shaders/shared);
// the GPU's `precise` and the CPU's -ffp-contract=off make their arithmetic
// round alike, so differences can only come from operations whose precision
// Vulkan leaves to the driver (division, sqrt). The tolerance below admits
// those: >= 99.9% of indicators identical within 1e-4 in position and energy.
#include <map>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "core/glm_interop.h"
#include "sp_types.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"
#include "support/thin_screen.h"

namespace sp {
namespace {

using Trace = test::Recorded;

class GpuParity : public test::GpuTest {
 protected:
  Trace run(const Scene& scene, const Config& config, Backend backend, int steps) {
    auto sim = make_simulator(make_world(scene, config).value(), backend);
    return test::run_steps(*sim, static_cast<std::uint64_t>(steps));
  }

  void expect_parity(const Scene& scene, const Config& config, int steps) {
    expect_parity(run(scene, config, Backend::Cpu, steps), run(scene, config, Backend::Gpu, steps));
  }

  void expect_parity(const Trace& cpu, const Trace& gpu) {
    ASSERT_GT(cpu.indicators.size(), 100u) << "scenario too small to compare";
    // kind too: a sheet's hit and exit share their ray and iteration.
    using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
    std::map<Key, const Indicator*> by_key;
    for (const Indicator& ind : gpu.indicators) by_key[{ind.step, ind.iteration, ind.ray_index, ind.kind}] = &ind;
    std::size_t identical = 0;
    for (const Indicator& c : cpu.indicators) {
      auto it = by_key.find({c.step, c.iteration, c.ray_index, c.kind});
      if (it == by_key.end()) continue;
      const Indicator& g = *it->second;
      bool same = c.kind == g.kind && c.source_id == g.source_id && c.bounces == g.bounces &&
                  c.penetrations == g.penetrations && c.diffractions == g.diffractions &&
                  std::abs(c.energy - g.energy) <= 1e-4f &&
                  glm::length(sp::to_glm(c.position) - sp::to_glm(g.position)) <= 1e-4f &&
                  std::abs(c.size - g.size) <= 1e-4f && c.intensity == g.intensity &&
                  std::abs(c.heard_energy - g.heard_energy) <= 1e-4f && std::abs(c.toward - g.toward) <= 1e-4f &&
                  glm::length(sp::to_glm(c.arrival) - sp::to_glm(g.arrival)) <= 1e-4f;
      identical += same;
    }
    const double fraction = double(identical) / double(cpu.indicators.size());
    EXPECT_GE(fraction, 0.999) << identical << " of " << cpu.indicators.size() << " identical";
    // The ring admits the same spots (sp_admission.h): but for a diverged
    // ray's, every live CPU indicator is live on the GPU too.
    std::set<Key> gpu_live;
    for (const Indicator& ind : gpu.live) gpu_live.insert({ind.step, ind.iteration, ind.ray_index, ind.kind});
    std::size_t live_shared = 0;
    for (const Indicator& c : cpu.live) live_shared += gpu_live.count({c.step, c.iteration, c.ray_index, c.kind});
    ASSERT_FALSE(cpu.live.empty());
    EXPECT_GE(double(live_shared), 0.99 * double(cpu.live.size())) << live_shared << " of " << cpu.live.size();
    EXPECT_NEAR(double(gpu.live.size()), double(cpu.live.size()), 0.01 * double(cpu.live.size()) + 1);
    // Counts: equal but for the rare ray whose path diverged (see fraction).
    const double tolerance = 0.001 * double(cpu.indicators.size()) + 1;
    EXPECT_NEAR(double(gpu.indicators.size()), double(cpu.indicators.size()), tolerance);
    EXPECT_EQ(gpu.stats.indicators, gpu.indicators.size());
    EXPECT_EQ(gpu.stats.rays_emitted, cpu.stats.rays_emitted);
    EXPECT_EQ(gpu.stats.steps, cpu.stats.steps);
    EXPECT_NEAR(double(gpu.stats.casts), double(cpu.stats.casts), 0.001 * double(cpu.stats.casts) + 1);
    ASSERT_EQ(gpu.stats.layers.size(), cpu.stats.layers.size());
    for (std::size_t l = 0; l < cpu.stats.layers.size(); ++l) {
      const auto& a = cpu.stats.layers[l];
      const auto& b = gpu.stats.layers[l];
      EXPECT_NEAR(double(b.hits), double(a.hits), 0.001 * double(a.hits) + 1) << l;
      EXPECT_NEAR(double(b.reflections), double(a.reflections), 0.001 * double(a.reflections) + 1) << l;
      EXPECT_NEAR(double(b.penetrations), double(a.penetrations), 0.001 * double(a.penetrations) + 1) << l;
      EXPECT_NEAR(double(b.no_way_out), double(a.no_way_out), 0.001 * double(a.no_way_out) + 1) << l;
      EXPECT_NEAR(double(b.back_face_hits), double(a.back_face_hits), 0.001 * double(a.back_face_hits) + 1) << l;
      EXPECT_NEAR(double(b.diffractions), double(a.diffractions), 0.001 * double(a.diffractions) + 1) << l;
    }
  }
};

Config base_config() {
  Config c;
  c.listener_position = glm::vec3(0, 1.5f, 0);
  c.ray_budget = 400;
  c.max_bounces = 4;
  c.seed = 11;
  return c;
}

TEST_F(GpuParity, ReflectingRoom) {
  Scene scene = test::closed_room();
  Config config = base_config();
  config.layers["concrete"] = {0.95f, 4.0f};
  expect_parity(scene, config, 3);
}

TEST_F(GpuParity, PenetratingWallsAndFurniture) {
  Scene scene;
  test::add_closed_room(scene, {-6, 0, -3}, {6, 3, 3}, 0.2f, "brick");
  test::add_box(scene, {-0.05f, 0, -3}, {0.05f, 3, -0.5f}, "wood");  // dividing wall with a door gap
  test::add_box(scene, {-0.05f, 0, 0.5f}, {0.05f, 3, 3}, "wood");
  test::add_box(scene, {2, 0, 1}, {3, 1, 2}, "metal");
  test::add_box(scene, {-4, 0, -2}, {-3.5f, 0.8f, 1}, "carpet");
  scene.sources.push_back(test::source_at({3, 1.5f, -1}));
  Config config = base_config();
  config.layers["wood"] = {0.3f, 1.0f};
  config.layers["brick"] = {0.6f, 2.0f};
  config.max_wall_thickness = 0.4f;
  expect_parity(scene, config, 3);
}

TEST_F(GpuParity, ThickWallsAbsorb) {
  Scene scene;
  test::add_closed_room(scene, {-3, 0, -3}, {3, 3, 3}, 1.0f, "concrete");
  scene.sources.push_back(test::source_at({0, 1.5f, 0}));
  Config config = base_config();
  config.layers["concrete"] = {0.5f, 1.0f};
  config.max_wall_thickness = 0.5f;
  expect_parity(scene, config, 3);
}

TEST_F(GpuParity, ManySourcesWithProximityWeighting) {
  Scene scene;
  test::add_closed_room(scene, {-8, 0, -8}, {8, 4, 8}, 0.2f, "concrete");
  test::add_box(scene, {-1, 0, -1}, {1, 2, 1}, "wood");
  for (int k = 0; k < 12; ++k) {
    SourceDesc s =
        test::source_at({-7.0f + 1.2f * float(k), 1.0f + 0.1f * float(k % 3), -5.0f + 0.8f * float(k)}, 25.0f);
    s.interval = 0.05;
    s.duration = 0.02 + 0.005 * k;
    scene.sources.push_back(s);
  }
  Config config = base_config();
  config.listener_position = glm::vec3(0, 1.5f, 4);
  config.budget_weighting = BudgetWeighting::Proximity;
  config.ray_budget = 997;
  config.air_attenuation = 0.03f;
  expect_parity(scene, config, 6);
}

TEST_F(GpuParity, ThinScreensDiffractAtTheirFreeEdges) {
  // A closed screen 1 or 2 cm thick (support/thin_screen.h): the GPU turns
  // rays round its free edge into the shadow as the CPU does, ray for ray.
  for (float thickness : {0.01f, 0.02f}) {
    SCOPED_TRACE(thickness);
    const Scene scene = test::thin_screen_level(thickness);
    const Config config = test::thin_screen_config(true);
    const Trace cpu = run(scene, config, Backend::Cpu, 2);
    const Trace gpu = run(scene, config, Backend::Gpu, 2);
    expect_parity(cpu, gpu);
    std::size_t shadow[2] = {0, 0}, shadow_turned[2] = {0, 0};
    for (const Trace* trace : {&cpu, &gpu}) {
      for (const Indicator& ind : trace->indicators) {
        if (!test::in_free_edge_shadow(ind)) continue;
        shadow[trace == &gpu] += 1;
        shadow_turned[trace == &gpu] += ind.diffractions == 1u;
      }
    }
    EXPECT_GT(shadow[1], 20u);
    EXPECT_EQ(shadow_turned[1], shadow[1]);  // reached round the edge only
    EXPECT_NEAR(double(shadow[1]), double(shadow[0]), 0.01 * double(shadow[0]) + 1);
    ASSERT_EQ(gpu.stats.layers.size(), 3u);
    EXPECT_GT(gpu.stats.layers[1].diffractions, 0u);  // layer 1: the screen
  }
}

TEST_F(GpuParity, BundledLevel) {
  Scene scene = load_scene(std::string(SP_SCENES_DIR) + "/two_rooms.gltf").value();
  Config config = base_config();
  config.listener_position.reset();
  expect_parity(scene, config, 4);
}

}  // namespace
}  // namespace sp
