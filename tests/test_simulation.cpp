// The CPU simulator end to end: registry, distribution, statistics,
// determinism. Expectations are derived by hand from SPEC section 1. The
// physics shared with the GPU backend lives in test_backends.cpp.
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "sim/cpu_ring.h"
#include "sim/cpu_step_runner.h"
#include "sim/indicator_ring.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"
#include "sp_random.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

using test::closed_room;
using SimRun = test::Recorded;

SimRun simulate(const Scene& scene, const Config& config, std::uint64_t steps, unsigned threads = 2) {
  auto sim = create_cpu_simulator(make_world(scene, config).value(), CpuSettings{threads}).value();
  return test::run_steps(*sim, steps);
}

Config quiet_config() {
  Config c;
  c.listener_position = glm::vec3(0, 1.5f, 0);
  c.ray_budget = 200;
  c.min_energy = 0.001f;
  return c;
}

TEST(Simulation, ReflectionFractionMatchesReflectProbability) {
  Config config = quiet_config();
  config.layers["concrete"] = {0.3f, 0.0f};
  config.max_wall_thickness = 0.1f;  // walls are 0.3 m: penetrations are absorbed
  config.air_attenuation = 0.0f;
  config.bounce_energy_loss = 0.0f;
  config.max_bounces = 10;
  config.ray_budget = 5000;
  SimRun run = simulate(closed_room(), config, 2);
  const auto& layer = run.stats.layers[0];
  double decisions = double(layer.reflections + layer.penetrations);
  ASSERT_GT(decisions, 5000.0);
  double fraction = double(layer.reflections) / decisions;
  double sigma = std::sqrt(0.3 * 0.7 / decisions);
  EXPECT_NEAR(fraction, 0.3, 4 * sigma);
  // Slabs meet at the room's edges, so a ray entering near an edge can find
  // the neighbouring slab's face within W_max: most, not all, are absorbed.
  EXPECT_LE(layer.no_way_out, layer.penetrations);
  EXPECT_GT(layer.no_way_out, layer.penetrations * 9 / 10);
}

TEST(Simulation, SourceBeyondItsMaxDistanceFromListenerEmitsNothing) {
  Scene scene = closed_room();
  scene.sources[0].max_distance = 2.0f;
  Config config = quiet_config();
  config.listener_position = glm::vec3(-2.5f, 1.5f, 0.2f);  // 3 m away
  EXPECT_EQ(simulate(scene, config, 2).stats.rays_emitted, 0u);
}

TEST(StepPlan, EvenSplitGivesRemainderToLowestIds) {
  EXPECT_EQ(split_budget(10, {1, 1, 1}), (std::vector<std::uint32_t>{4, 3, 3}));
  EXPECT_EQ(split_budget(11, {1, 1, 1}), (std::vector<std::uint32_t>{4, 4, 3}));
  EXPECT_EQ(split_budget(2, {1, 1, 1, 1}), (std::vector<std::uint32_t>{1, 1, 0, 0}));
  EXPECT_EQ(split_budget(0, {1, 1}), (std::vector<std::uint32_t>{0, 0}));
  EXPECT_TRUE(split_budget(5, {}).empty());
}

TEST(StepPlan, ProximitySplitIsProportionalToOneMinusDistanceOverRange) {
  // weights 0.75 and 0.25 of 100 rays -> 75 and 25
  EXPECT_EQ(split_budget(100, {0.75, 0.25}), (std::vector<std::uint32_t>{75, 25}));
  // 10 rays by weights 0.5, 0.3, 0.2 -> floors 5, 3, 2
  EXPECT_EQ(split_budget(10, {0.5, 0.3, 0.2}), (std::vector<std::uint32_t>{5, 3, 2}));
  // all weights zero -> even
  EXPECT_EQ(split_budget(3, {0, 0}), (std::vector<std::uint32_t>{2, 1}));
}

TEST(StepPlan, RegistryAppliesPatternRadiusAndWeighting) {
  Scene scene = closed_room();
  scene.sources.clear();
  SourceDesc near = test::source_at({1, 1.5f, 0}, 10.0f);  // d_ls 1 -> weight 0.9
  SourceDesc far = test::source_at({-2, 1.5f, 0}, 10.0f);  // d_ls 2 -> weight 0.8
  SourceDesc pulsed = test::source_at({0, 1.5f, 1}, 10.0f);
  // binary fractions, so the pattern's arithmetic is exact
  pulsed.interval = 0.25;
  pulsed.duration = 0.125;
  pulsed.phase = 0.0625;
  scene.sources = {near, far, pulsed};
  Config config = quiet_config();
  config.listener_position = glm::vec3(0, 1.5f, 0);
  config.ray_budget = 17;
  config.budget_weighting = BudgetWeighting::Proximity;
  config.dt = 0.0625;
  World world = make_world(scene, config).value();
  std::vector<PlayWindow> none(3);
  // step 0 (t = 0): the pulsed source waits for its phase
  StepPlan plan = plan_step(world, 0, world.listener, none);
  ASSERT_EQ(plan.sources.size(), 2u);
  EXPECT_EQ(plan.sources[0].ray_count + plan.sources[1].ray_count, 17u);
  EXPECT_EQ(plan.sources[0].ray_count, 9u);  // floor(17*.9/1.7) = 9, floor(17*.8/1.7) = 8
  EXPECT_EQ(plan.sources[1].first_ray, 9u);
  EXPECT_FLOAT_EQ(plan.sources[1].intensity, 0.8f);
  // t = 0.0625: plays (0 < 0.125); t = 0.1875: 0.125 is not < 0.125;
  // t = 0.3125: the next period starts
  EXPECT_EQ(plan_step(world, 1, world.listener, none).sources.size(), 3u);
  EXPECT_EQ(plan_step(world, 2, world.listener, none).sources.size(), 3u);
  EXPECT_EQ(plan_step(world, 3, world.listener, none).sources.size(), 2u);
  EXPECT_EQ(plan_step(world, 5, world.listener, none).sources.size(), 3u);
  // a host play() window makes it play regardless of the pattern
  std::vector<PlayWindow> played(3);
  played[2] = {0.0, 0.01};
  EXPECT_EQ(plan_step(world, 0, world.listener, played).sources.size(), 3u);
}

TEST(Simulation, SameSeedSameIndicatorsWhateverTheThreadCount) {
  Config config = quiet_config();
  config.ray_budget = 500;
  config.layers["concrete"] = {0.6f, 1.0f};
  config.max_wall_thickness = 0.5f;
  auto key = [](const SimRun& run) {
    std::vector<std::tuple<std::uint32_t, std::uint32_t, float, float, float, float>> k;
    for (const auto& i : run.indicators)
      k.emplace_back(i.step, i.ray_index, i.position.x, i.position.y, i.position.z, i.energy);
    return k;
  };
  SimRun one = simulate(closed_room(), config, 4, 1);
  SimRun four = simulate(closed_room(), config, 4, 4);
  ASSERT_FALSE(one.indicators.empty());
  EXPECT_EQ(key(one), key(four));
  EXPECT_EQ(one.stats.casts, four.stats.casts);
  config.seed = 2;
  EXPECT_NE(key(one), key(simulate(closed_room(), config, 4, 4)));
}

TEST(Simulation, IndicatorsComeInCanonicalOrder) {
  Config config = quiet_config();
  SimRun run = simulate(closed_room(), config, 2, 3);
  for (std::size_t k = 1; k < run.indicators.size(); ++k) {
    const auto& a = run.indicators[k - 1];
    const auto& b = run.indicators[k];
    EXPECT_LE(std::tie(a.step, a.iteration, a.ray_index), std::tie(b.step, b.iteration, b.ray_index));
  }
}

TEST(Random, EmissionDirectionsAreUnitAndUniform) {
  int octants[8] = {};
  glm::dvec3 mean(0.0);
  const int n = 80000;
  for (int i = 0; i < n; ++i) {
    glm::vec3 d = shader::sp_emission_direction(7u, 3u, static_cast<std::uint32_t>(i));
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-6f);
    octants[(d.x > 0) + 2 * (d.y > 0) + 4 * (d.z > 0)] += 1;
    mean += glm::dvec3(d);
  }
  for (int count : octants) EXPECT_NEAR(count, n / 8, 5 * std::sqrt(n / 8.0));
  EXPECT_LT(glm::length(mean / double(n)), 0.02);
}

TEST(Random, DecisionsAreUniformAndKeyedByAllInputs) {
  int below_third = 0;
  const int n = 60000;
  for (int i = 0; i < n; ++i)
    below_third += shader::sp_decision_random(1u, 2u, static_cast<std::uint32_t>(i), 0u) < 1.0f / 3.0f;
  EXPECT_NEAR(below_third, n / 3, 5 * std::sqrt(n * 2.0 / 9.0));
  float base = shader::sp_decision_random(1u, 2u, 3u, 4u);
  EXPECT_NE(base, shader::sp_decision_random(2u, 2u, 3u, 4u));
  EXPECT_NE(base, shader::sp_decision_random(1u, 3u, 3u, 4u));
  EXPECT_NE(base, shader::sp_decision_random(1u, 2u, 4u, 4u));
  EXPECT_NE(base, shader::sp_decision_random(1u, 2u, 3u, 5u));
}

TEST(CpuRing, KeepsTheNewestAndDropsExpired) {
  Config config;
  config.max_indicators = 4;
  config.dt = 1.0;
  config.indicator_lifetime = 10.0f;
  CpuRing ring(config);
  std::vector<shader::Indicator> batch(6);
  for (std::uint32_t k = 0; k < 6; ++k) {
    batch[k].step = k;
    batch[k].ray_index = k;
  }
  ring.place(std::span(batch).first(3));
  ring.place(std::span(batch).subspan(3));
  EXPECT_EQ(ring.writer().written(), 6u);
  auto live = ring.live(6, config);  // step 5 shown
  ASSERT_EQ(live.size(), 4u);
  EXPECT_EQ(live.front().ray_index, 2u);  // oldest surviving first
  EXPECT_EQ(live.back().ray_index, 5u);
  // dt 1 s, lifetime 2.5 s at step 5: ages 3,2,1,0 -> steps 3,4,5 live
  config.indicator_lifetime = 2.5f;
  EXPECT_EQ(ring.live(6, config).size(), 3u);
  EXPECT_TRUE(ring.live(0, config).empty());  // before the first step
  config.max_indicators = 2;
  config.indicator_lifetime = 100.0f;
  CpuRing small(config);
  small.place(batch);  // more than capacity at once
  auto kept = small.live(6, config);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].ray_index, 4u);
}

// The one writer lays each step after the last, in runs of slots that
// never wrap: what the CPU visualizer uploads and the simulator copies.
TEST(CpuRing, WriterLaysRunsThatWrapAtTheCapacity) {
  Config config;
  config.max_indicators = 5;
  RingWriter writer(config);
  std::vector<shader::Indicator> batch(12);
  for (std::uint32_t k = 0; k < 12; ++k) batch[k].ray_index = k;
  std::vector<std::pair<std::uint32_t, std::vector<std::uint32_t>>> runs;
  auto record = [&](std::uint32_t slot, std::span<const shader::Indicator> run) {
    std::vector<std::uint32_t> rays;
    for (const shader::Indicator& ind : run) rays.push_back(ind.ray_index);
    runs.emplace_back(slot, rays);
  };
  using Runs = decltype(runs);
  writer.place(std::span(batch).first(3), record);
  EXPECT_EQ(runs, (Runs{{0u, {0, 1, 2}}}));
  runs.clear();
  writer.place(std::span(batch).subspan(3, 4), record);
  EXPECT_EQ(runs, (Runs{{3u, {3, 4}}, {0u, {5, 6}}}));
  EXPECT_EQ(writer.written(), 7u);
  EXPECT_EQ(writer.filled(), 5u);
  runs.clear();
  writer.place(std::span(batch).subspan(0, 8), record);  // more than the ring: the newest 5, from slot 10 % 5
  EXPECT_EQ(runs, (Runs{{0u, {3, 4, 5, 6, 7}}}));
  EXPECT_EQ(writer.written(), 15u);
}

shader::Indicator spot(std::uint32_t ray, float size, bool direct) {
  shader::Indicator ind{};
  ind.kind = SP_INDICATOR_HIT;
  ind.ray_index = ray;
  ind.size = size;
  ind.bounces = direct ? 0u : 1u;
  return ind;
}

TEST(Simulation, RingAdmitsDirectSoundFirstThenTheMostEnergetic) {
  // indicator_size 1, so size is E / E0. A quota of 4 gives direct sound
  // 2, sound through walls 1, reflections 1; nothing went through a wall,
  // so its share goes to reflections: both direct hits, however faint,
  // then the two strongest reflections.
  std::vector<shader::Indicator> step = {spot(0, 0.9f, false), spot(1, 0.05f, true), spot(2, 0.2f, false),
                                         spot(3, 0.7f, false), spot(4, 0.1f, true),  spot(5, 0.3f, false)};
  auto admitted = admit(step, 4, 1.0f);
  std::set<std::uint32_t> rays;
  for (const shader::Indicator& ind : admitted) rays.insert(ind.ray_index);
  EXPECT_EQ(rays, (std::set<std::uint32_t>{0, 1, 3, 4}));
  EXPECT_EQ(admit(step, 10, 1.0f).size(), step.size()) << "under the quota, all are admitted";
}

TEST(Simulation, RingKeepsAShareForSoundThroughWalls) {
  // Ten loud direct hits and three faint exits: a quota of 6 gives each
  // class 2; the exits are shown although every direct hit is louder.
  std::vector<shader::Indicator> step;
  for (std::uint32_t r = 0; r < 10; ++r) step.push_back(spot(r, 0.9f - 0.01f * static_cast<float>(r), true));
  for (std::uint32_t r = 10; r < 13; ++r) {
    shader::Indicator exit = spot(r, 0.05f * static_cast<float>(r - 9), false);
    exit.kind = SP_INDICATOR_EXIT;
    exit.bounces = 0;
    exit.penetrations = 1;
    step.push_back(exit);
  }
  step.push_back(spot(20, 0.5f, false));
  step.push_back(spot(21, 0.4f, false));
  std::set<std::uint32_t> rays;
  for (const shader::Indicator& ind : admit(step, 6, 1.0f)) rays.insert(ind.ray_index);
  EXPECT_EQ(rays, (std::set<std::uint32_t>{0, 1, 11, 12, 20, 21}));
}

TEST(Simulation, RingAdmitsAShareOfSpotsOfEqualWorthRatherThanNone) {
  // 200 spots in one admission bin against a quota of 20: the tie-break
  // bins pick some of them, never more than the quota, the same each time.
  std::vector<shader::Indicator> step;
  for (std::uint32_t r = 0; r < 200; ++r) step.push_back(spot(r, 0.5f, true));
  auto admitted = admit(step, 20, 1.0f);
  EXPECT_GE(admitted.size(), 10u);
  EXPECT_LE(admitted.size(), 20u);
  auto again = admit(step, 20, 1.0f);
  ASSERT_EQ(again.size(), admitted.size());
  for (std::size_t i = 0; i < admitted.size(); ++i) EXPECT_EQ(again[i].ray_index, admitted[i].ray_index);
}

// The CPU step leaves its indicators in per-chunk lists and merges them
// only on request; the ring's admission works on the chunks directly, from
// the bins the workers counted. Both must give what one merged list gives:
// canonical (iteration, ray) order, and admit() of that list, at every
// quota, and at an indicator size other than the one the step binned with.
TEST(Simulation, StepOutputMergesAndAdmitsAsOneCanonicalList) {
  Config config = quiet_config();
  config.ray_budget = 1000;  // 32 chunks of 32 rays
  const World world = make_world(closed_room(), config).value();
  const StepPlan plan = plan_step(world, 0, world.listener, std::vector<PlayWindow>(world.sources.size()));
  ASSERT_EQ(plan.total_rays, 1000u);
  CpuStepRunner runner(2, world.layer_names.size());
  CpuStepOutput out;
  runner.run(world.geometry->bvh, make_layer_table(world), plan, make_sim_params(config, 0, plan.listener), 1.0f, out);

  const std::vector<shader::Indicator> all = out.canonical();
  ASSERT_EQ(all.size(), out.indicator_count());
  ASSERT_GT(all.size(), 1000u) << "every ray leaves one indicator at least, most several";
  std::set<std::uint32_t> iterations = {all[0].iteration};
  for (std::size_t i = 1; i < all.size(); ++i) {
    iterations.insert(all[i].iteration);
    const auto before = std::make_tuple(all[i - 1].iteration, all[i - 1].ray_index);
    const auto after = std::make_tuple(all[i].iteration, all[i].ray_index);
    ASSERT_LE(before, after) << "indicator " << i << " out of canonical order";
  }
  EXPECT_GT(iterations.size(), 2u) << "rays bounce: later iterations interleave the chunks";

  auto same = [](const shader::Indicator& a, const shader::Indicator& b) {
    return std::memcmp(&a, &b, sizeof(a)) == 0;
  };
  const auto count = static_cast<std::uint32_t>(all.size());
  for (const float inverse_size : {1.0f, 2.5f}) {
    for (std::uint32_t quota : {1u, 7u, 334u, count / 2u, count - 1u, count, count + 9u}) {
      const std::vector<shader::Indicator> expected = admit(all, quota, inverse_size);
      const std::vector<shader::Indicator> admitted = out.admitted(quota, inverse_size);
      ASSERT_EQ(admitted.size(), expected.size()) << "quota " << quota << ", inverse size " << inverse_size;
      for (std::size_t i = 0; i < admitted.size(); ++i)
        ASSERT_TRUE(same(admitted[i], expected[i]))
            << "quota " << quota << ", inverse size " << inverse_size << ", admitted indicator " << i;
    }
  }

  // The same output reused for a smaller step (fewer chunks than before)
  // holds that step's indicators and bins alone.
  StepPlan small = plan;
  small.total_rays = 300;
  std::uint32_t first = 0;
  for (shader::StepSource& source : small.sources) {
    source.first_ray = first;
    source.ray_count = std::min(source.ray_count, small.total_rays - first);
    first += source.ray_count;
  }
  runner.run(world.geometry->bvh, make_layer_table(world), small, make_sim_params(config, 1, small.listener), 1.0f,
             out);
  const std::vector<shader::Indicator> fewer = out.canonical();
  ASSERT_EQ(fewer.size(), out.indicator_count());
  ASSERT_LT(fewer.size(), all.size());
  for (std::uint32_t quota : {1u, 50u, static_cast<std::uint32_t>(fewer.size() / 2u)}) {
    const std::vector<shader::Indicator> expected = admit(fewer, quota, 1.0f);
    const std::vector<shader::Indicator> admitted = out.admitted(quota, 1.0f);
    ASSERT_EQ(admitted.size(), expected.size()) << "smaller step, quota " << quota;
    for (std::size_t i = 0; i < admitted.size(); ++i)
      ASSERT_TRUE(same(admitted[i], expected[i])) << "smaller step, quota " << quota << ", admitted indicator " << i;
  }
}

TEST(Simulation, RingQuotaTurnsTheRingOverOncePerLifetime) {
  Config config;
  config.max_indicators = 20000;
  config.indicator_lifetime = 1.0f;
  config.dt = 1.0 / 60.0;
  EXPECT_EQ(ring_quota(config), 334u);  // ceil(20000 / 60)
  config.indicator_lifetime = 0.1f;     // shown for 1/3 s at least: ceil(20000 / 20)
  EXPECT_EQ(ring_quota(config), 1000u);
  config.max_indicators = 50;
  config.indicator_lifetime = 100.0f;
  EXPECT_EQ(ring_quota(config), 1u);
}

TEST(Simulation, RingBufferHoldsAtMostMaxIndicators) {
  Config config = quiet_config();
  config.max_indicators = 60;
  config.indicator_lifetime = 0.5f;
  config.dt = 0.1;  // quota ceil(60 * 0.1 / 0.5) = 12 a step, alive 5 steps
  auto sim = create_cpu_simulator(make_world(closed_room(), config).value()).value();
  for (int n = 0; n < 8; ++n) ASSERT_TRUE(sim->step().ok());
  auto live = sim->live_indicators().value();
  EXPECT_LE(live.size(), 60u);
  EXPECT_GE(live.size(), 40u);
  std::map<std::uint32_t, std::uint32_t> per_step;
  for (const Indicator& ind : live) per_step[ind.step] += 1;
  for (auto [step, count] : per_step) {
    EXPECT_GE(step, 3u) << "older than the lifetime";
    EXPECT_LE(count, 12u) << "step " << step << " admitted more than its quota";
  }
}

// A burst at step 0 only, in steps of 1/16 s (exact in binary): its spots
// are (now - 0) / 16 s old at step `now`.
Config burst_config(float lifetime) {
  Config config = quiet_config();
  config.dt = 1.0 / 16.0;
  config.indicator_lifetime = lifetime;
  return config;
}
Scene burst_room() {
  Scene scene = closed_room();
  scene.sources[0].duration = 0.01;
  scene.sources[0].interval = 1000.0;
  return scene;
}

// What live_indicators() returns is what the display draws: a spot lives
// for the display's lifetime, max(indicator_lifetime, 1/3 s), the flash
// limit (sp_indicator_live). A 0.3 s spot is live at 5/16 = 0.3125 s, as it
// is drawn, and neither at 6/16 = 0.375 s; a 1 s spot, at 15/16 s and not at 1 s.
TEST(Simulation, LiveIndicatorsAreThoseTheDisplayDraws) {
  for (const auto& [lifetime, last_live_step] : {std::pair{0.3f, 5u}, std::pair{1.0f, 15u}}) {
    auto sim = create_cpu_simulator(make_world(burst_room(), burst_config(lifetime)).value()).value();
    for (std::uint32_t n = 0; n <= last_live_step; ++n) ASSERT_TRUE(sim->step().ok());
    const std::vector<Indicator> live = sim->live_indicators().value();
    EXPECT_FALSE(live.empty()) << "lifetime " << lifetime << ": the burst is " << last_live_step << "/16 s old";
    for (const Indicator& ind : live) EXPECT_EQ(ind.step, 0u);
    ASSERT_TRUE(sim->step().ok());
    EXPECT_TRUE(sim->live_indicators()->empty()) << "lifetime " << lifetime << ": past the display's lifetime";
  }
}

TEST(Simulation, ApiArgumentsAreValidated) {
  auto sim = create_cpu_simulator(make_world(closed_room(), quiet_config()).value()).value();
  EXPECT_FALSE(sim->play(1, 1.0).ok());
  EXPECT_FALSE(sim->play(0, -1.0).ok());
  EXPECT_FALSE(sim->play(0, std::nan("")).ok());
  EXPECT_TRUE(sim->play(0, 1.0).ok());
  EXPECT_FALSE(sim->set_listener({std::nanf(""), 0, 0}).ok());
  Scene no_listener = closed_room();
  EXPECT_FALSE(make_world(no_listener, Config{}).ok());
  Config bad = quiet_config();
  bad.max_bounces = 1000;
  EXPECT_FALSE(make_world(closed_room(), bad).ok());
  Scene broken = closed_room();
  broken.triangle_layers[3] = 9;
  EXPECT_FALSE(make_world(broken, quiet_config()).ok());
}

}  // namespace
}  // namespace sp
