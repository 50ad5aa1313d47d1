// Loudness from the signal on both backends (docs/model.md#loudness-from-the-signal):
// a tone burst's first hits carry the E0 the law gives, less the air's
// loss, silence emits no ray and paints nothing, a whisper's spots stop
// where its energy runs out, and the two backends agree.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "soundpaint/signal.h"
#include "support/backend_cases.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

// Step levels (one per 1/60 s, looping): burst, silence, whisper, silence.
constexpr float kBurstDb = -6.0f, kWhisperDb = -40.0f;
const double kBurstE0 = (60.0 + kBurstDb) / 60.0;      // 0.9
const double kWhisperE0 = (60.0 + kWhisperDb) / 60.0;  // 1/3

Config signal_config() {
  Config c;
  c.listener_position = Vec3(-2.0f, 1.5f, 0.0f);
  c.ray_budget = 300;
  c.air_attenuation = 0.1f;  // a whisper's rays reach (1/3 - 0.05) / 0.1 = 2.83 m
  c.min_energy = 0.05f;
  c.max_bounces = 2;
  return c;
}

World signal_world() {
  const float inf = std::numeric_limits<float>::infinity();
  const float levels[] = {kBurstDb, -inf, kWhisperDb, -inf};
  Scene scene = test::closed_room();
  scene.sources[0].signal = std::make_shared<const Signal>(Signal::from_levels(levels, 1.0 / 60.0).value());
  scene.sources[0].loop = true;
  return make_world(scene, signal_config()).value();
}

class SignalBackends : public test::GpuTest, public ::testing::WithParamInterface<test::BackendCase> {};

// Per step of the loop: the indicators it made and the rays it emitted.
struct StepRecord {
  std::vector<Indicator> indicators;
  std::uint64_t rays = 0;
};

std::vector<StepRecord> record(Simulator& sim, int steps) {
  std::vector<StepRecord> out;
  std::uint64_t rays = 0;
  for (int n = 0; n < steps; ++n) {
    EXPECT_TRUE(sim.step().ok());
    const std::uint64_t total = sim.stats().value().rays_emitted;
    out.push_back({sim.last_step_indicators().value(), total - rays});
    rays = total;
  }
  return out;
}

TEST_P(SignalBackends, BurstWhisperAndSilenceFollowTheLaw) {
  World world = signal_world();
  world.config.cpu_traversal = GetParam().traversal;
  auto sim = make_simulator(std::move(world), GetParam().backend);
  const std::vector<StepRecord> steps = record(*sim, 8);
  const float alpha = signal_config().air_attenuation;
  const float reach = static_cast<float>((kWhisperE0 - 0.05) / alpha);
  for (int n = 0; n < 8; ++n) {
    SCOPED_TRACE(n);
    const StepRecord& step = steps[static_cast<std::size_t>(n)];
    if (n % 2 == 1) {  // silence: no ray, no spot
      EXPECT_EQ(step.rays, 0u);
      EXPECT_TRUE(step.indicators.empty());
      continue;
    }
    EXPECT_EQ(step.rays, 300u);
    const double e0 = n % 4 == 0 ? kBurstE0 : kWhisperE0;
    std::size_t first_hits = 0;
    float farthest = 0.0f;
    for (const Indicator& i : step.indicators) {
      farthest = std::max(farthest, i.path_length);
      EXPECT_LE(i.energy, e0 + 1e-6);
      if (i.kind != kIndicatorHit || i.bounces != 0 || i.penetrations != 0) continue;
      ++first_hits;
      // E = E0 - t alpha_air at the first hit, t its distance.
      EXPECT_NEAR(i.energy, e0 - double(i.path_length) * alpha, 2e-6);
      EXPECT_NEAR(i.size, sim->world().config.indicator_size * i.energy / float(e0), 1e-6);
    }
    EXPECT_GT(first_hits, 100u);
    // A whisper's rays die where (E0 - tau_min) / alpha_air runs out; the
    // burst's go farther.
    if (n % 4 == 2) EXPECT_LE(farthest, reach + 1e-4f);
    else EXPECT_GT(farthest, reach + 0.5f);
  }
  // A burst paints more than a whisper.
  EXPECT_GT(steps[0].indicators.size(), steps[2].indicators.size());
}

INSTANTIATE_TEST_SUITE_P(Backends, SignalBackends, ::testing::ValuesIn(test::backend_cases()), test::backend_case_name);

class SignalParity : public test::GpuTest {};

TEST_F(SignalParity, BothBackendsPaintTheSameSpots) {
  test::Recorded cpu = test::run_steps(*make_simulator(signal_world(), Backend::Cpu), 8);
  test::Recorded gpu = test::run_steps(*make_simulator(signal_world(), Backend::Gpu), 8);
  EXPECT_EQ(gpu.stats.rays_emitted, cpu.stats.rays_emitted);
  ASSERT_GT(cpu.indicators.size(), 100u);
  ASSERT_NEAR(double(gpu.indicators.size()), double(cpu.indicators.size()), 0.002 * double(cpu.indicators.size()));
  std::size_t identical = 0;
  for (std::size_t k = 0; k < std::min(cpu.indicators.size(), gpu.indicators.size()); ++k) {
    const Indicator& a = cpu.indicators[k];
    const Indicator& b = gpu.indicators[k];
    identical += a.step == b.step && a.ray_index == b.ray_index && a.energy == b.energy &&
                 a.position.x == b.position.x && a.position.y == b.position.y && a.position.z == b.position.z;
  }
  EXPECT_GE(double(identical), 0.999 * double(cpu.indicators.size()));
}

}  // namespace
}  // namespace sp
