// Diffraction at exposed edges (docs/model.md#diffraction): single rays
// against hand-derived distributions, and both backends on scenes where
// only diffraction can reach a place (a half-plane screen's shadow, a thin
// screen's, an L-shaped corridor's far leg) or where nothing may leak (a
// closed room of touching slabs). Which edges are exposed:
// test_diffraction_edges.cpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "bvh/diffraction_edges.h"
#include "core/glm_interop.h"
#include "sim/cpu_tracer.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "soundpaint/config.h"
#include "sp_diffraction.h"
#include "sp_ray_model.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"
#include "support/thin_screen.h"

namespace sp {
namespace {

using test::add_box;
using test::add_quad;

constexpr double kPi = std::numbers::pi;

TEST(DiffractionModel, SinAndCosPolynomialsAreAccurateOnZeroToPi) {
  double worst = 0.0;
  for (int k = 0; k <= 10000; ++k) {
    const float x = static_cast<float>(kPi * k / 10000.0);
    const glm::vec2 sc = shader::sp_sin_cos(x);
    worst = std::max({worst, std::abs(sc.x - std::sin(double(x))), std::abs(sc.y - std::cos(double(x)))});
  }
  EXPECT_LT(worst, 1e-6);
}

// ----------------------------------------------------- a half-plane screen

// A screen in the plane z = 0 over x <= 0 (front +z) with its free edge
// along x = 0, and a receiving floor at z = -1 behind it. Both are sheets
// that absorb whatever enters them. Rays fall straight down onto the screen
// from z = 1, so the shadow boundary at the edge points straight down, and
// a floor hit at x < 0 was turned by atan(-x / 1) into the shadow.
struct HalfPlane {
  Scene scene;
  Config config;
  World world;
  std::vector<shader::LayerAcoustics> layers;
  shader::StepSource source{};

  explicit HalfPlane(bool diffraction, float gain = 1.0f) {
    add_quad(scene, {-5, -5, 0}, {0, -5, 0}, {0, 5, 0}, {-5, 5, 0}, "screen");
    add_quad(scene, {-200, -200, -1}, {200, -200, -1}, {200, 200, -1}, {-200, 200, -1}, "floor");
    config.layers["screen"] = {0.0f, 1000.0f, 0.01f};
    config.layers["floor"] = {0.0f, 1000.0f, 0.01f};
    config.air_attenuation = 0.0f;
    config.min_energy = 0.01f;
    config.max_bounces = 4;
    config.listener_position = glm::vec3(0, 0, 5);
    config.diffraction.enabled = diffraction;
    config.diffraction.gain = gain;
    world = make_world(scene, config).value();
    layers = make_layer_table(world);
    source.max_distance = 1000.0f;
    source.loudness = 1.0f;
    source.intensity = 1.0f;
  }

  // Ray `index` falling straight down onto the screen a metres from its edge.
  std::vector<shader::Indicator> drop(float a, std::uint32_t index, TraceCounters& counters) const {
    TraceContext context{&world.geometry->bvh, layers, {&source, 1}, make_sim_params(config, 0, world.listener)};
    shader::RayState ray = shader::sp_emit_ray(source, 0, index, glm::vec3(0.0f, 0.0f, -1.0f), 0u);
    ray.origin = glm::vec3(-a, 0.0f, 1.0f);
    ray.dir = glm::vec3(0.0f, 0.0f, -1.0f);
    counters.layers.assign(world.layer_names.size(), {});
    DefaultInitVector<shader::Indicator> out;
    trace_ray(context, ray, out, counters);
    return {out.begin(), out.end()};
  }
};

// P(theta > x) for a ray struck a metres from the edge (the model's law,
// derived by hand from its definition, not from the code).
double tail(double a, double x, const DiffractionSettings& d) {
  const double width = kSpeedOfSound / (4.0 * kPi * d.frequency);
  const double sigma = std::min(kPi / 2.0, width / std::max(a, 1e-3));
  return sigma / (sigma + x);
}

TEST(DiffractionHalfPlane, ShadowHitsFollowTheAngleLawAndOnlyWithDiffractionOn) {
  const int n = 4000;
  const double bins[] = {0.0, 30.0, 60.0, 85.0};  // degrees into the shadow
  for (bool on : {false, true}) {
    HalfPlane scene(on);
    const float reach = diffraction_reach(scene.config.diffraction);
    ASSERT_NEAR(reach, 0.343f, 1e-6f);
    double expected[3] = {0, 0, 0}, variance[3] = {0, 0, 0}, expected_turns = 0.0;
    int observed[3] = {0, 0, 0}, shadow_hits = 0;
    std::uint64_t turns = 0;
    for (int j = 0; j < n; ++j) {
      const double a = reach * (j + 0.5) / n;
      const double turn = 1.0 - a / reach;
      expected_turns += turn * (1.0 - tail(a, kPi / 2.0, scene.config.diffraction));
      for (int b = 0; b < 3; ++b) {
        const double p = turn * (tail(a, bins[b] * kPi / 180.0, scene.config.diffraction) -
                                 tail(a, bins[b + 1] * kPi / 180.0, scene.config.diffraction));
        expected[b] += p;
        variance[b] += p * (1.0 - p);
      }
      TraceCounters counters;
      const auto out = scene.drop(static_cast<float>(a), static_cast<std::uint32_t>(j), counters);
      turns += counters.layers[0].diffractions;
      ASSERT_GE(out.size(), 1u);
      EXPECT_EQ(out[0].diffractions, 0u);  // the screen near its edge gets its cue first
      for (std::size_t k = 1; k < out.size(); ++k) {
        const shader::Indicator& hit = out[k];
        ASSERT_EQ(hit.diffractions, 1u);
        EXPECT_NEAR(hit.position.z, -1.0f, 1e-4f);
        EXPECT_NEAR(hit.dir.y, 0.0f, 1e-6f);  // Keller's cone: nothing along the edge before, nothing after
        if (hit.position.x < 0.0f) ++shadow_hits;
        const double theta = std::atan2(SP_DIFFRACTION_OFFSET - hit.position.x, 1.0) * 180.0 / kPi;
        for (int b = 0; b < 3; ++b) observed[b] += theta >= bins[b] && theta < bins[b + 1];
      }
    }
    if (!on) {
      EXPECT_EQ(shadow_hits, 0);
      EXPECT_EQ(turns, 0u);
      continue;
    }
    EXPECT_NEAR(double(turns), expected_turns, 5.0 * std::sqrt(expected_turns) + 1.0);
    for (int b = 0; b < 3; ++b) {
      EXPECT_NEAR(observed[b], expected[b], 5.0 * std::sqrt(variance[b]) + 1.0) << "bin " << bins[b];
    }
    EXPECT_GT(observed[0], observed[1]);  // what reaches the shadow falls with the angle
    EXPECT_GT(observed[1], observed[2]);
    EXPECT_GT(shadow_hits, n / 4);
  }
}

TEST(DiffractionHalfPlane, ATurnedRayCarriesAtMostGainTimesItsEnergy) {
  // No air loss: a floor hit after a turn carries exactly gain * E0, and its
  // path is the drop, the way to the edge and on to the floor.
  HalfPlane scene(true, 0.5f);
  int turned = 0;
  for (std::uint32_t j = 0; j < 500; ++j) {
    TraceCounters counters;
    const float a = 0.3f * (static_cast<float>(j) + 0.5f) / 500.0f;
    const auto out = scene.drop(a, j, counters);
    for (std::size_t k = 1; k < out.size(); ++k) {
      ++turned;
      EXPECT_FLOAT_EQ(out[k].energy, 0.5f);
      EXPECT_FLOAT_EQ(out[k].size, 0.5f * scene.config.indicator_size);
      const glm::vec3 edge(0.0f, 0.0f, 0.0f);
      const float expected = 1.0f + a + glm::distance(edge, sp::to_glm(out[k].position));
      EXPECT_NEAR(out[k].path_length, expected, 2e-3f);
    }
  }
  EXPECT_GT(turned, 100);
}

// ------------------------------------------------ both backends, whole runs

// Walls that swallow what enters them: nothing reflects, nothing gets
// through, so a place out of the source's sight is reached by turning only.
void absorbing(Config& config, const std::string& layer) { config.layers[layer] = {0.0f, 100.0f}; }

// An L-shaped corridor, 2 m wide and 100 m tall (so that nothing goes over
// the top within reach of a source at mid-height): leg one along +x
// (x in [0, 10], z in [0, 2]), leg two along +z (x in [8, 10], z in [2, 10]).
// The block between them has its convex corner edge at x = 8, z = 2.
// The source at (6, 0, 0.5) sees the block's corner face at about 37
// degrees; its sight past the corner ends at z = 0.5 + (10 - 6) * 1.5 / 2
// = 3.5 on the outer wall, so the far leg (z > 4.5) is out of its sight.
Scene l_corridor() {
  Scene scene;
  add_box(scene, {0, -50, 2}, {8, 50, 10}, "block");
  add_box(scene, {-0.3f, -50, -0.3f}, {10.3f, 50, 0}, "walls");  // leg one's outer wall
  add_box(scene, {10, -50, 0}, {10.3f, 50, 10.3f}, "walls");     // the outer corner's wall
  add_box(scene, {-0.3f, -50, 0}, {0, 50, 2}, "walls");          // leg one's end
  add_box(scene, {8, -50, 10}, {10, 50, 10.3f}, "walls");        // leg two's end
  scene.sources.push_back(test::source_at({6, 0, 0.5f}));
  return scene;
}

Config l_corridor_config(bool diffraction) {
  Config config;
  absorbing(config, "block");
  absorbing(config, "walls");
  config.listener_position = glm::vec3(9, 0, 9);
  config.ray_budget = 6000;
  config.max_wall_thickness = 0.5f;
  config.diffraction.enabled = diffraction;
  return config;
}

class DiffractionBackends : public test::GpuTest, public ::testing::WithParamInterface<Backend> {};
class DiffractionMovingParts : public test::GpuTest {};

TEST_P(DiffractionBackends, TheCornerGetsCuesAndTheFarLegOnlyByTurning) {
  for (bool on : {false, true}) {
    World world = make_world(l_corridor(), l_corridor_config(on)).value();
    auto sim = make_simulator(std::move(world), GetParam());
    const test::Recorded out = test::run_steps(*sim, 4);
    int corner = 0, far_leg = 0, far_leg_turned = 0;
    std::uint64_t turned_indicators = 0;
    for (const Indicator& ind : out.indicators) {
      const glm::vec2 from_corner(ind.position.x - 8.0f, ind.position.z - 2.0f);
      if (glm::length(from_corner) < 0.5f && ind.diffractions == 0u) ++corner;
      if (ind.position.z > 4.5f) {
        ++far_leg;
        far_leg_turned += ind.diffractions > 0u;
      }
      turned_indicators += ind.diffractions > 0u;
    }
    std::uint64_t diffractions = 0;
    for (const LayerCounters& layer : out.stats.layers) diffractions += layer.diffractions;
    EXPECT_GT(corner, 5) << "on " << on;
    if (!on) {
      EXPECT_EQ(far_leg, 0);
      EXPECT_EQ(diffractions, 0u);
      EXPECT_EQ(turned_indicators, 0u);
    } else {
      EXPECT_GT(far_leg, 15);
      EXPECT_EQ(far_leg_turned, far_leg);  // every cue there came round an edge
      EXPECT_GT(diffractions, 0u);
      EXPECT_LE(out.stats.rays_emitted, 4u * 6000u);  // the budget holds: nothing spawned
    }
  }
}

TEST_P(DiffractionBackends, AClosedRoomOfTouchingSlabsLeaksNothing) {
  // Every edge of the room's inside is buried where slabs touch, so nothing
  // turns, and with walls that reflect everything nothing gets out.
  Scene scene = test::closed_room();
  Config config;
  config.layers["concrete"] = {1.0f, 2.0f};
  config.listener_position = glm::vec3(0, 1.5f, 0);
  config.ray_budget = 3000;
  config.max_bounces = 8;
  config.diffraction.enabled = true;
  config.diffraction.reach = 1.0f;
  World world = make_world(scene, config).value();
  auto sim = make_simulator(std::move(world), GetParam());
  const test::Recorded out = test::run_steps(*sim, 2);
  ASSERT_GT(out.indicators.size(), 1000u);
  for (const Indicator& ind : out.indicators) {
    EXPECT_EQ(ind.diffractions, 0u);
    const glm::vec3 p = ind.position;
    const float e = 1e-3f;  // positions on a face are a rounding off it
    EXPECT_TRUE(p.x >= -3 - e && p.x <= 3 + e && p.y >= -e && p.y <= 3 + e && p.z >= -2.5f - e && p.z <= 2.5f + e)
        << p.x << ", " << p.y << ", " << p.z;
  }
}

TEST_P(DiffractionBackends, ThinScreensTurnRaysRoundTheirFreeEdgeIntoTheShadow) {
  // support/thin_screen.h: the window on the back wall is out of the
  // source's sight and reached only round the screen's free edge.
  for (float thickness : {0.01f, 0.02f}) {
    for (bool on : {false, true}) {
      SCOPED_TRACE(testing::Message() << thickness << " m, diffraction " << on);
      World world = make_world(test::thin_screen_level(thickness), test::thin_screen_config(on)).value();
      const auto screen = static_cast<std::size_t>(
          std::find(world.layer_names.begin(), world.layer_names.end(), "screen") - world.layer_names.begin());
      auto sim = make_simulator(std::move(world), GetParam());
      const test::Recorded out = test::run_steps(*sim, 2);
      int shadow = 0, shadow_turned = 0, direct = 0;
      for (const Indicator& ind : out.indicators) {
        if (test::in_free_edge_shadow(ind)) {
          ++shadow;
          shadow_turned += ind.diffractions == 1u;
        }
        direct += test::in_direct_sight(ind) && ind.diffractions == 0u;
      }
      EXPECT_GT(direct, 20);  // the source reaches the wall past the screen, either way
      ASSERT_LT(screen, out.stats.layers.size());
      const std::uint64_t turns = out.stats.layers[screen].diffractions;
      if (!on) {
        EXPECT_EQ(shadow, 0);
        EXPECT_EQ(turns, 0u);
      } else {
        EXPECT_GT(shadow, 20);
        EXPECT_EQ(shadow_turned, shadow);  // every cue there came round the edge, once
        EXPECT_GE(turns, std::uint64_t(shadow));
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, DiffractionBackends, ::testing::Values(Backend::Cpu, Backend::Gpu),
                         [](const ::testing::TestParamInfo<Backend>& param_info) {
                           return param_info.param == Backend::Cpu ? "Cpu" : "Gpu";
                         });

// The two backends write the same indicators, diffractions included, with
// diffraction on and off.
class DiffractionParity : public test::GpuTest, public ::testing::WithParamInterface<bool> {};

TEST_P(DiffractionParity, CpuAndGpuAgreeIndicatorForIndicator) {
  std::vector<Indicator> lists[2];
  for (Backend backend : {Backend::Cpu, Backend::Gpu}) {
    Scene scene = l_corridor();
    Config config = l_corridor_config(GetParam());
    // Some reflection, so that turned rays bounce on and turn again.
    config.layers["block"] = {0.5f, 100.0f};
    config.max_bounces = 6;
    World world = make_world(scene, config).value();
    auto sim = make_simulator(std::move(world), backend);
    lists[backend == Backend::Gpu] = test::run_steps(*sim, 2).indicators;
  }
  ASSERT_EQ(lists[0].size(), lists[1].size());
  std::size_t differing = 0, turned = 0;
  for (std::size_t k = 0; k < lists[0].size(); ++k) {
    const Indicator& c = lists[0][k];
    const Indicator& g = lists[1][k];
    const bool same = c.kind == g.kind && c.ray_index == g.ray_index && c.iteration == g.iteration &&
                      c.diffractions == g.diffractions && c.bounces == g.bounces &&
                      std::abs(c.energy - g.energy) <= 1e-5f &&
                      glm::distance(sp::to_glm(c.position), sp::to_glm(g.position)) <= 1e-5f;
    differing += !same;
    turned += c.diffractions > 0u;
  }
  EXPECT_EQ(differing, 0u) << "of " << lists[0].size();
  if (GetParam()) {
    EXPECT_GT(turned, 20u);
  } else {
    EXPECT_EQ(turned, 0u);
  }
}

// The CPU's and the GPU's spots, in the same order: of the same kind, ray
// and turns, at the same place.
void expect_same_spots(const std::vector<Indicator>& cpu, const std::vector<Indicator>& gpu) {
  ASSERT_EQ(cpu.size(), gpu.size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < cpu.size(); ++k) {
    const Indicator& c = cpu[k];
    const Indicator& g = gpu[k];
    differing += !(c.kind == g.kind && c.ray_index == g.ray_index && c.diffractions == g.diffractions &&
                   glm::distance(sp::to_glm(c.position), sp::to_glm(g.position)) <= 1e-5f);
  }
  EXPECT_EQ(differing, 0u) << "of " << cpu.size();
}

// A moving part changes which edges are exposed: the block between the
// legs, lifted out of the corridor, uncovers the walls' ends it buried.
// Both backends must find them again (the GPU uploads the changed entries)
// and keep agreeing.
TEST_F(DiffractionMovingParts, BothBackendsFollowTheEdgesAMovedPartUncovers) {
  std::vector<Indicator> lists[2];
  std::uint64_t wall_turns[2] = {0, 0};
  for (Backend backend : {Backend::Cpu, Backend::Gpu}) {
    Scene scene = l_corridor();
    scene.instance_names = {"block"};
    scene.triangle_instances.assign(scene.triangle_count(), kStaticInstance);
    for (std::size_t t = 0; t < 12; ++t) scene.triangle_instances[t] = 0;  // the block is the first box
    Config config = l_corridor_config(true);
    config.diffraction.reach = 1.0f;
    World world = make_world(scene, config).value();
    const std::uint32_t walls = world.layer_names[0] == "walls" ? 0u : 1u;
    auto sim = make_simulator(std::move(world), backend);
    test::Recorded before = test::run_steps(*sim, 1);
    ASSERT_TRUE(sim->scene().set_instance_transform(0, glm::translate(glm::mat4(1.0f), {0, 1000, 0})).ok());
    test::Recorded after = test::run_steps(*sim, 2);
    lists[backend == Backend::Gpu] = before.indicators;
    lists[backend == Backend::Gpu].insert(lists[backend == Backend::Gpu].end(), after.indicators.begin(),
                                          after.indicators.end());
    wall_turns[backend == Backend::Gpu] =
        after.stats.layers[walls].diffractions - before.stats.layers[walls].diffractions;
  }
  EXPECT_GT(wall_turns[0], 0u);
  EXPECT_EQ(wall_turns[0], wall_turns[1]);
  expect_same_spots(lists[0], lists[1]);
}

// Diffraction switched on, then off, by set_config: the GPU's resolve
// kernel, whose code is built with or without diffraction, follows, and the
// two backends keep agreeing.
TEST_F(DiffractionMovingParts, BothBackendsFollowDiffractionSwitchedOnAndOff) {
  std::vector<Indicator> lists[2];
  std::uint64_t turns[2][3] = {};  // per backend: diffractions after each phase
  for (Backend backend : {Backend::Cpu, Backend::Gpu}) {
    World world = make_world(l_corridor(), l_corridor_config(false)).value();
    auto sim = make_simulator(std::move(world), backend);
    const bool gpu = backend == Backend::Gpu;
    for (int phase = 0; phase < 3; ++phase) {
      if (phase > 0) {
        ASSERT_TRUE(sim->set_config(l_corridor_config(phase == 1)).ok());
      }
      test::Recorded steps = test::run_steps(*sim, 2);
      lists[gpu].insert(lists[gpu].end(), steps.indicators.begin(), steps.indicators.end());
      for (const LayerCounters& layer : steps.stats.layers) turns[gpu][phase] += layer.diffractions;
    }
  }
  EXPECT_EQ(turns[0][0], 0u);
  EXPECT_GT(turns[0][1], 20u);
  EXPECT_EQ(turns[0][2], turns[0][1]);  // totals: none added once it is off
  for (int phase = 0; phase < 3; ++phase) EXPECT_EQ(turns[1][phase], turns[0][phase]) << phase;
  expect_same_spots(lists[0], lists[1]);
}

INSTANTIATE_TEST_SUITE_P(OnAndOff, DiffractionParity, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& param_info) {
                           return param_info.param ? "On" : "Off";
                         });

}  // namespace
}  // namespace sp
