// Simulator::set_config (issue 36, item 1): other settings between steps,
// on both backends, with expectations derived by hand. The level is never
// built again (bvh_builds), the scene's sources and the ring's spots stay,
// what the config decides follows the new values from the next step on,
// and a refused config leaves the simulator stepping exactly as a twin that
// never got it.
#include <algorithm>
#include <cstring>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "bvh/bvh.h"
#include "core/glm_interop.h"
#include "gpu/gpu_simulator.h"
#include "sim/memory_estimate.h"
#include "support/backend_cases.h"
#include "support/gpu_environment.h"
#include "support/scene_builder.h"
#include "support/thin_screen.h"

namespace sp {
namespace {

using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
Key key(const Indicator& ind) { return {ind.step, ind.iteration, ind.ray_index, ind.kind}; }

bool same_bits(const Indicator& a, const Indicator& b) { return std::memcmp(&a, &b, sizeof(Indicator)) == 0; }

// Whether the lists are equal indicator for indicator, bit for bit.
::testing::AssertionResult same_bits(const std::vector<Indicator>& a, const std::vector<Indicator>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << a.size() << " vs " << b.size() << " indicators";
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same_bits(a[i], b[i])) return ::testing::AssertionFailure() << "indicator " << i << " differs";
  return ::testing::AssertionSuccess();
}

// The closed room's source alone within reach of a listener in the room.
Config base_config() {
  Config c;
  c.listener_position = glm::vec3(0, 1.5f, 0);
  c.ray_budget = 200;
  c.min_energy = 0.001f;
  c.seed = 5;
  return c;
}

// Other values of most keys a host would change, none of them the default.
Config other_config() {
  Config c = base_config();
  c.ray_budget = 350;
  c.max_bounces = 3;
  c.max_indicators = 300;
  c.air_attenuation = 0.03f;
  c.seed = 9;
  c.layers["concrete"] = {0.7f, 3.0f};
  c.cues.guide_share = 0.8f;
  c.indicator_lifetime = 0.5f;
  return c;
}

class SetConfig : public test::GpuTest, public ::testing::WithParamInterface<test::BackendCase> {
 protected:
  // `config` with the case's CPU traversal: set_config keeps it that way.
  Config with_case(Config config) const { return test::with_traversal(std::move(config), GetParam()); }
  std::unique_ptr<Simulator> make(const Scene& scene, const Config& config) {
    return make_simulator(make_world(scene, with_case(config)).value(), GetParam().backend);
  }
  void set(Simulator& sim, const Config& config) {
    const Result<bool> done = sim.set_config(with_case(config));
    ASSERT_TRUE(done.ok()) << done.error().message;
  }
  static void step(Simulator& sim, int steps = 1) {
    for (int n = 0; n < steps; ++n) ASSERT_TRUE(sim.step().ok());
  }
  // Steps both and expects the same indicators and totals, bit for bit:
  // both backends are deterministic for the same world and steps.
  static void expect_twins(Simulator& sim, Simulator& twin, int steps) {
    for (int n = 0; n < steps; ++n) {
      step(sim);
      step(twin);
      EXPECT_TRUE(same_bits(sim.last_step_indicators().value(), twin.last_step_indicators().value())) << "step " << n;
    }
    EXPECT_TRUE(same_bits(sim.live_indicators().value(), twin.live_indicators().value()));
    const SimulationStats a = sim.stats().value();
    const SimulationStats b = twin.stats().value();
    EXPECT_EQ(a.steps, b.steps);
    EXPECT_EQ(a.rays_emitted, b.rays_emitted);
    EXPECT_EQ(a.casts, b.casts);
    EXPECT_EQ(a.indicators, b.indicators);
  }
};

TEST_P(SetConfig, ARayBudgetFromZeroToAHundredEmitsExactlyAHundredWithoutBuildingTheLevel) {
  Config config = base_config();
  config.ray_budget = 0;
  auto sim = make(test::closed_room(), config);
  const std::uint64_t builds = bvh_builds();
  step(*sim, 2);
  EXPECT_EQ(sim->stats().value().rays_emitted, 0u);
  EXPECT_TRUE(sim->live_indicators().value().empty());

  config.ray_budget = 100;
  set(*sim, config);
  step(*sim);
  // The room's one source, always playing and within reach, takes the
  // whole budget.
  const SimulationStats stats = sim->stats().value();
  EXPECT_EQ(stats.rays_emitted, 100u);
  EXPECT_EQ(stats.steps, 3u);
  EXPECT_FALSE(sim->last_step_indicators().value().empty());
  EXPECT_FALSE(sim->live_indicators().value().empty());
  EXPECT_EQ(sim->world().config.ray_budget, 100u);
  EXPECT_EQ(bvh_builds(), builds) << "set_config built the level again";
}

TEST_P(SetConfig, SourcesTheHostAddedAndMovedKeepEmittingAndConfigSourcesAreNotRead) {
  auto sim = make(test::closed_room(), base_config());
  const std::uint32_t added = sim->scene().add_source(test::source_at({-1.5f, 1.0f, -1.0f})).value();
  step(*sim);
  // Queued when set_config comes: applied with it, in call order.
  const std::uint32_t queued = sim->scene().add_source(test::source_at({2.0f, 2.0f, 1.5f})).value();
  ASSERT_TRUE(sim->scene().move_source(added, {-2.0f, 1.0f, -1.0f}).ok());

  Config config = base_config();
  config.ray_budget = 300;
  config.sources.push_back(test::source_at({0.0f, 2.5f, 0.0f}));  // seeds a new World only
  set(*sim, config);
  EXPECT_EQ(sim->scene().source_slot_count(), 3u);
  step(*sim);

  std::set<std::uint32_t> emitting;
  for (const Indicator& ind : sim->last_step_indicators().value()) emitting.insert(ind.source_id);
  EXPECT_EQ(emitting, (std::set<std::uint32_t>{0u, added, queued}));
  EXPECT_EQ(sim->stats().value().rays_emitted, 200u + 300u);
  const World& world = sim->world();
  ASSERT_EQ(world.sources.size(), 3u);
  EXPECT_EQ(world.sources[added].position, Vec3(-2.0f, 1.0f, -1.0f));
  EXPECT_TRUE(world.config.sources.empty()) << "world().config keeps the sources it was made with";
  EXPECT_EQ(world.config.ray_budget, 300u);
}

using test::room_with_movable_wall;

TEST_P(SetConfig, VoicesPlayWindowsTheListenerAndAMovedWallStay) {
  Config config = base_config();
  config.listener_position = glm::vec3(-2, 1.5f, 0);
  config.max_bounces = 3;
  config.layers["concrete"] = {1.0f, 5.0f};
  config.layers["door"] = {1.0f, 5.0f};
  auto sim = make(room_with_movable_wall(), config);
  SoundScene& scene = sim->scene();
  SourceDesc silent = test::source_at({-2.0f, 1.0f, 1.0f});
  silent.duration = 0.0;  // sounds only when the host says so
  const std::uint32_t voice = scene.add_source(silent).value();
  ASSERT_TRUE(scene.set_voice(voice, VoiceState{{-2.5f, 1.0f, 1.0f}, true}).ok());
  silent.position = {-1.0f, 1.0f, -1.0f};
  const std::uint32_t played = scene.add_source(silent).value();
  ASSERT_TRUE(scene.play(played, 10.0).ok());
  ASSERT_TRUE(scene.set_listener({-1.0f, 1.5f, 0.5f}).ok());
  // Slid 10 m up, above the ceiling: rays cross x = 1 to the far wall at x = 3.
  const Mat4 slid_up = glm::translate(glm::mat4(1.0f), {0, 10, 0});
  ASSERT_TRUE(scene.set_instance_transform(0, slid_up).ok());
  step(*sim);  // applies all of it (and refits the BVH)
  const std::uint64_t builds = bvh_builds();

  config.ray_budget = 300;
  config.air_attenuation = 0.005f;
  set(*sim, config);
  std::set<std::uint32_t> emitting;
  std::size_t beyond_the_wall = 0;
  for (int n = 0; n < 2; ++n) {
    step(*sim);
    for (const Indicator& ind : sim->last_step_indicators().value()) {
      emitting.insert(ind.source_id);
      beyond_the_wall += ind.position.x > 1.1f ? 1 : 0;
    }
  }
  EXPECT_EQ(emitting, (std::set<std::uint32_t>{0u, voice, played}));
  EXPECT_GT(beyond_the_wall, 20u);
  const World& world = sim->world();
  EXPECT_EQ(world.listener, Vec3(-1.0f, 1.5f, 0.5f));
  EXPECT_EQ(world.sources[voice].position, Vec3(-2.5f, 1.0f, 1.0f));
  ASSERT_EQ(world.instance_transforms.size(), 1u);
  EXPECT_EQ(world.instance_transforms[0], slid_up);
  EXPECT_EQ(bvh_builds(), builds);
}

TEST_P(SetConfig, AShrunkRingKeepsTheNewestSpotsThatFitAndAGrownOneKeepsThemAll) {
  Config config = base_config();
  auto sim = make(test::closed_room(), config);
  step(*sim, 3);
  const std::vector<Indicator> before = sim->live_indicators().value();
  constexpr std::uint32_t kSmall = 10;
  ASSERT_GT(before.size(), kSmall);

  config.max_indicators = kSmall;
  set(*sim, config);
  const std::vector<Indicator> kept = sim->live_indicators().value();
  ASSERT_EQ(kept.size(), kSmall);
  const std::vector<Indicator> newest(before.end() - kSmall, before.end());
  EXPECT_TRUE(same_bits(kept, newest));

  config.max_indicators = 50;
  set(*sim, config);
  EXPECT_TRUE(same_bits(sim->live_indicators().value(), newest)) << "a larger ring keeps every spot";

  config.max_indicators = kSmall;
  set(*sim, config);
  for (int n = 0; n < 3; ++n) {
    step(*sim);
    EXPECT_LE(sim->live_indicators().value().size(), kSmall) << "step " << n;
  }
}

TEST_P(SetConfig, EnergyFollowsTheNewAirAttenuationAndCastsTheNewBounces) {
  // A closed mirror room: every hit reflects and no energy is lost at a
  // bounce, so each ray hits max_bounces + 1 times and an indicator at path
  // length d carries E0 - alpha * d (docs/model.md: air costs alpha_air of
  // energy per metre), E0 = 1.
  Config config = base_config();
  config.layers["concrete"] = {1.0f, 5.0f};
  config.bounce_energy_loss = 0.0f;
  config.air_attenuation = 0.01f;
  config.max_bounces = 5;
  config.ray_budget = 100;
  auto sim = make(test::closed_room(), config);
  step(*sim);
  const std::uint64_t casts = sim->stats().value().casts;
  EXPECT_EQ(casts, 100u * 6u);

  // Three segments of at most the room's diagonal (8.4 m) cost at most
  // 0.03 * 25.1 = 0.75: no ray dies before its third hit.
  config.air_attenuation = 0.03f;
  config.max_bounces = 2;
  set(*sim, config);
  step(*sim);
  EXPECT_EQ(sim->stats().value().casts - casts, 100u * 3u);
  const std::vector<Indicator> step1 = sim->last_step_indicators().value();
  ASSERT_EQ(step1.size(), 100u * 3u);
  for (const Indicator& ind : step1) {
    EXPECT_EQ(ind.step, 1u);
    EXPECT_NEAR(ind.energy, 1.0f - 0.03f * ind.path_length, 5e-5f);
  }
}

TEST_P(SetConfig, LayersTakeTheirNewAcoustics) {
  // rho_ref 1: every hit reflects; then rho_ref 0: every hit penetrates.
  Config config = base_config();
  config.layers["concrete"] = {1.0f, 5.0f};
  auto sim = make(test::closed_room(), config);
  step(*sim);
  const LayerCounters first = sim->stats().value().layers.at(0);
  EXPECT_GT(first.reflections, 0u);
  EXPECT_EQ(first.penetrations, 0u);

  config.layers["concrete"] = {0.0f, 5.0f};
  set(*sim, config);
  step(*sim);
  const LayerCounters both = sim->stats().value().layers.at(0);
  EXPECT_EQ(both.reflections, first.reflections);
  EXPECT_GT(both.hits, first.hits);
  EXPECT_EQ(both.penetrations, both.hits - first.hits);
}

TEST_P(SetConfig, DiffractionSwitchedOnTurnsRaysIntoTheShadowWithoutBuildingTheLevel) {
  // support/thin_screen.h: only rays turned round the screen's free edge
  // reach the window on the back wall.
  auto sim = make(test::thin_screen_level(0.01f), test::thin_screen_config(false));
  const std::uint64_t builds = bvh_builds();
  step(*sim);
  for (const Indicator& ind : sim->last_step_indicators().value()) EXPECT_FALSE(test::in_free_edge_shadow(ind));

  set(*sim, test::thin_screen_config(true));
  int shadow = 0, turned = 0;
  for (int n = 0; n < 2; ++n) {
    step(*sim);
    for (const Indicator& ind : sim->last_step_indicators().value()) {
      if (!test::in_free_edge_shadow(ind)) continue;
      ++shadow;
      turned += ind.diffractions == 1u;
    }
  }
  EXPECT_GT(shadow, 20);
  EXPECT_EQ(turned, shadow);
  EXPECT_EQ(bvh_builds(), builds) << "finding the edges is not a build of the level";
}

TEST_P(SetConfig, AnInvalidValueNamesItsKeyAndChangesNothing) {
  auto sim = make(test::closed_room(), base_config());
  auto twin = make(test::closed_room(), base_config());
  step(*sim, 2);
  step(*twin, 2);

  struct Bad {
    const char* key;
    void (*spoil)(Config&);
  };
  const Bad bad[] = {
      {"ray_budget", [](Config& c) { c.ray_budget = kMaxRayBudget + 1; }},
      {"diffraction.frequency", [](Config& c) { c.diffraction.frequency = 0.0f; }},
      {"max_indicators", [](Config& c) { c.max_indicators = 0; }},
      {"layers.concrete.reflect_probability",
       [](Config& c) {
         c.layers["concrete"] = {1.5f, 2.0f};
       }},
      // Step n runs at n * dt: a running simulation keeps its dt.
      {"dt", [](Config& c) { c.dt = 1.0 / 30.0; }},
  };
  for (const Bad& b : bad) {
    Config config = other_config();  // every other key changes too, and none may take
    b.spoil(config);
    const Result<bool> refused = sim->set_config(with_case(config));
    ASSERT_FALSE(refused.ok()) << b.key;
    EXPECT_EQ(refused.error().code, ErrorCode::InvalidConfig) << b.key;
    EXPECT_NE(refused.error().message.find(std::string("\"") + b.key + "\""), std::string::npos)
        << refused.error().message;
  }
  EXPECT_EQ(sim->world().config.ray_budget, base_config().ray_budget);
  expect_twins(*sim, *twin, 3);
}

TEST_P(SetConfig, OverTheMemoryBudgetIsALimitErrorNamingTheKeysAndChangesNothing) {
  // The estimate grows with ray_budget: a budget the first config fits
  // exactly refuses twice its rays.
  const Config config = with_case(base_config());
  const std::uint64_t budget = estimate_memory(config, GetParam().backend).total();
  auto make_budgeted = [&] {
    World world = make_world(test::closed_room(), config).value();
    if (GetParam().backend == Backend::Cpu)
      return create_cpu_simulator(std::move(world), CpuSettings{2, budget}).value();
    return gpu::create_simulator(std::move(world), *test::GpuEnvironment::context(), budget).value();
  };
  auto sim = make_budgeted();
  auto twin = make_budgeted();
  step(*sim);
  step(*twin);

  Config bigger = config;
  bigger.ray_budget *= 2;
  const Result<bool> refused = sim->set_config(bigger);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::LimitExceeded);
  for (const char* knob : {"ray_budget", "max_bounces", "max_indicators"})
    EXPECT_NE(refused.error().message.find(knob), std::string::npos) << refused.error().message;
  expect_twins(*sim, *twin, 2);
}

TEST_P(SetConfig, BeforeTheFirstStepItStepsAsASimulatorCreatedWithTheConfig) {
  auto sim = make(test::closed_room(), base_config());
  auto fresh = make(test::closed_room(), other_config());
  set(*sim, other_config());
  expect_twins(*sim, *fresh, 4);
}

TEST_P(SetConfig, AfterStepsAStepMatchesAFreshSimulatorsWhenNothingLearnedIsRead) {
  // A step's indicators follow from the config, the sources and the step's
  // index; the one thing earlier steps teach it is each source's guide,
  // which guide_share 0 never reads. (The ring differs: it holds the
  // earlier steps' spots.)
  Config first = base_config();
  first.cues.guide_share = 0.0f;
  Config second = other_config();
  second.cues.guide_share = 0.0f;
  auto sim = make(test::closed_room(), first);
  auto fresh = make(test::closed_room(), second);
  step(*sim, 3);
  step(*fresh, 3);
  set(*sim, second);
  for (int n = 0; n < 2; ++n) {
    step(*sim);
    step(*fresh);
    EXPECT_TRUE(same_bits(sim->last_step_indicators().value(), fresh->last_step_indicators().value()))
        << "step " << 3 + n;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, SetConfig, ::testing::ValuesIn(test::backend_cases()), test::backend_case_name);

// The GPU against the CPU reference after the same set_config, by the
// parity suite's measure (test_gpu_parity.cpp): all but the rare ray whose
// path diverged in the last float bit give the same indicator.
class SetConfigParity : public test::GpuTest {};

TEST_F(SetConfigParity, CpuAndGpuAgreeAfterTheSameChange) {
  struct Trace {
    std::vector<Indicator> indicators;
    std::vector<Indicator> live;
    SimulationStats stats;
  };
  auto run = [&](Backend backend) {
    auto sim = make_simulator(make_world(test::closed_room(), base_config()).value(), backend);
    Trace trace;
    auto steps = [&](int n) {
      for (int k = 0; k < n; ++k) {
        EXPECT_TRUE(sim->step().ok());
        const std::vector<Indicator> step = sim->last_step_indicators().value();
        trace.indicators.insert(trace.indicators.end(), step.begin(), step.end());
      }
    };
    steps(2);
    EXPECT_TRUE(sim->set_config(other_config()).ok());
    steps(2);
    trace.live = sim->live_indicators().value();
    trace.stats = sim->stats().value();
    return trace;
  };
  const Trace cpu = run(Backend::Cpu);
  const Trace gpu = run(Backend::Gpu);
  ASSERT_GT(cpu.indicators.size(), 100u);
  std::vector<std::pair<Key, const Indicator*>> by_key;
  for (const Indicator& g : gpu.indicators) by_key.emplace_back(key(g), &g);
  std::sort(by_key.begin(), by_key.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::size_t identical = 0;
  for (const Indicator& c : cpu.indicators) {
    const auto it = std::lower_bound(by_key.begin(), by_key.end(), key(c),
                                     [](const auto& entry, const Key& k) { return entry.first < k; });
    if (it == by_key.end() || it->first != key(c)) continue;
    const Indicator& g = *it->second;
    identical += c.source_id == g.source_id && c.bounces == g.bounces && c.penetrations == g.penetrations &&
                 std::abs(c.energy - g.energy) <= 1e-4f &&
                 glm::length(to_glm(c.position) - to_glm(g.position)) <= 1e-4f &&
                 std::abs(c.heard_energy - g.heard_energy) <= 1e-4f;
  }
  EXPECT_GE(double(identical), 0.999 * double(cpu.indicators.size())) << identical << " of " << cpu.indicators.size();
  EXPECT_EQ(gpu.stats.rays_emitted, cpu.stats.rays_emitted);
  EXPECT_EQ(cpu.stats.rays_emitted, 2u * 200u + 2u * 350u);
  EXPECT_NEAR(double(gpu.live.size()), double(cpu.live.size()), 0.01 * double(cpu.live.size()) + 1);
  std::set<Key> gpu_live;
  for (const Indicator& g : gpu.live) gpu_live.insert(key(g));
  std::size_t shared = 0;
  for (const Indicator& c : cpu.live) shared += gpu_live.count(key(c));
  ASSERT_FALSE(cpu.live.empty());
  EXPECT_GE(double(shared), 0.99 * double(cpu.live.size())) << shared << " of " << cpu.live.size();
}

}  // namespace
}  // namespace sp
