// Loudness from the signal (docs/model.md#loudness-from-the-signal), with
// levels derived by hand: a square wave of amplitude A reads 20 log10(A) dB,
// a full-scale sine -3.01 dB; the law maps a level to E0; silence plans no
// rays; a loop repeats its envelope; rays follow energy; voices start,
// stop and take their level from the samples they are fed.
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "sim/step_plan.h"
#include "soundpaint/signal.h"
#include "soundpaint/simulation.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<float> square(double amplitude, double seconds, double rate = 48000.0) {
  std::vector<float> out(static_cast<std::size_t>(std::lround(seconds * rate)));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(i % 2 == 0 ? amplitude : -amplitude);
  return out;
}

std::shared_ptr<const Signal> shared(Result<Signal> made) {
  EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error().message);
  return std::make_shared<const Signal>(std::move(made).value());
}

TEST(SignalLevel, SquareWaveReadsTwentyLogItsAmplitude) {
  const Signal s = Signal::from_pcm(square(0.5, 0.1), 48000.0).value();
  EXPECT_NEAR(s.duration(), 0.1, 1e-12);
  EXPECT_NEAR(s.block_seconds(), 0.001, 1e-12);                                    // 48 samples
  EXPECT_NEAR(s.level_db(0.02, 1.0 / 60.0, false), 20.0 * std::log10(0.5), 1e-9);  // -6.0206 dB
  // 16-bit: full scale 32768, so 16384 is half of it.
  std::vector<std::int16_t> s16(4800);
  for (std::size_t i = 0; i < s16.size(); ++i) s16[i] = static_cast<std::int16_t>(i % 2 == 0 ? 16384 : -16384);
  EXPECT_NEAR(Signal::from_pcm16(s16, 48000.0).value().level_db(0.0, 0.01, false), -6.0206, 1e-4);
  // 8-bit unsigned: 128 +- 64 is half scale too.
  std::vector<std::uint8_t> u8(800);
  for (std::size_t i = 0; i < u8.size(); ++i) u8[i] = static_cast<std::uint8_t>(i % 2 == 0 ? 192 : 64);
  EXPECT_NEAR(Signal::from_pcm8(u8, 8000.0).value().level_db(0.0, 0.01, false), -6.0206, 1e-4);
}

TEST(SignalLevel, FullScaleSineIsMinusThreeDecibels) {
  // 1 kHz at 48 kHz: a 10 ms window holds exactly ten periods, whose mean
  // square is 1/2.
  std::vector<float> sine(4800);
  for (std::size_t i = 0; i < sine.size(); ++i)
    sine[i] = static_cast<float>(std::sin(2.0 * std::numbers::pi * 1000.0 * static_cast<double>(i) / 48000.0));
  EXPECT_NEAR(Signal::from_pcm(sine, 48000.0).value().level_db(0.03, 0.01, false), -3.0103, 1e-4);
}

TEST(SignalLevel, WindowAveragesPowerAndPastTheEndIsSilenceUnlessLooping) {
  // 20 ms of A = 0.5, then 20 ms of silence.
  std::vector<float> burst = square(0.5, 0.02);
  burst.resize(burst.size() * 2, 0.0f);
  const Signal s = Signal::from_pcm(burst, 48000.0).value();
  // A window half in the burst holds half its power: -6.02 - 3.01 dB.
  EXPECT_NEAR(s.level_db(0.01, 0.02, false), 10.0 * std::log10(0.25 / 2.0), 1e-9);
  EXPECT_EQ(s.level_db(0.025, 0.01, false), -kInf);
  EXPECT_EQ(s.level_db(0.05, 0.01, false), -kInf);  // past the end
  EXPECT_EQ(s.level_db(-0.01, 0.005, false), -kInf);
  // Looping: 40 ms later, the burst again.
  EXPECT_NEAR(s.level_db(0.045, 0.01, true), s.level_db(0.005, 0.01, false), 1e-12);
  // A window running past the end wraps to the start.
  EXPECT_NEAR(s.level_db(0.03, 0.02, true), 10.0 * std::log10(0.25 / 2.0), 1e-9);
}

TEST(SignalLevel, EnvelopeGivenAsLevels) {
  const float levels[] = {-6.0f, -static_cast<float>(kInf), -20.0f};
  const Signal s = Signal::from_levels(levels, 0.01).value();
  EXPECT_NEAR(s.duration(), 0.03, 1e-12);
  EXPECT_NEAR(s.level_db(0.0, 0.01, false), -6.0, 1e-5);
  EXPECT_EQ(s.level_db(0.01, 0.01, false), -kInf);
  EXPECT_NEAR(s.level_db(0.02, 0.01, false), -20.0, 1e-5);
}

TEST(SignalLevel, BadInputIsRefusedNamingTheProblem) {
  const float nan_sample[] = {0.0f, std::numeric_limits<float>::quiet_NaN()};
  auto error = [](const Result<Signal>& r) { return r.ok() ? std::string("accepted") : r.error().message; };
  EXPECT_EQ(error(Signal::from_pcm(nan_sample, 48000.0)), "Signal::from_pcm: sample 1 is not finite");
  EXPECT_NE(error(Signal::from_pcm(square(0.5, 0.01), 100.0)).find("sample_rate must be in [1000, 768000]"),
            std::string::npos);
  EXPECT_EQ(error(Signal::from_pcm({}, 48000.0)), "Signal::from_pcm: no samples");
  EXPECT_NE(error(Signal::from_pcm(nan_sample, 48000.0, 3)).find("not a whole number of 3-channel frames"),
            std::string::npos);
  // A position or window no caller should give reads as silence, and a
  // huge window over a loop is its mean, not an overflow.
  const Signal half = Signal::from_pcm(square(0.5, 0.01), 48000.0).value();
  EXPECT_EQ(half.level_db(std::numeric_limits<double>::quiet_NaN(), 0.01, true), -kInf);
  EXPECT_EQ(half.level_db(0.0, -1.0, false), -kInf);
  EXPECT_NEAR(half.level_db(0.0, 1e300, true), 20.0 * std::log10(0.5), 1e-6);
  const float bad_level[] = {std::numeric_limits<float>::infinity()};
  EXPECT_NE(error(Signal::from_levels(bad_level, 0.01)).find("level 0 must be"), std::string::npos);
  EXPECT_NE(error(Signal::from_levels(bad_level, 0.0)).find("hop_seconds"), std::string::npos);
}

TEST(SignalLaw, GainIsLinearInDecibelsBetweenFloorAndReference) {
  const SignalSettings law;                                                             // floor -60 dB, reference 0 dB
  EXPECT_NEAR(signal_gain(20.0 * std::log10(0.5), law), (60.0 - 6.0206) / 60.0, 1e-5);  // 0.89966
  EXPECT_EQ(signal_gain(-60.0, law), 0.0);
  EXPECT_EQ(signal_gain(-kInf, law), 0.0);
  EXPECT_EQ(signal_gain(3.0, law), 1.0);
  EXPECT_NEAR(signal_gain(-30.0, {std::nullopt, -40.0f, -10.0f}), 1.0 / 3.0, 1e-12);
}

// A closed room with one source at its centre, heard from a corner.
World room_world(std::vector<SourceDesc> sources, Config config = {}) {
  Scene scene = test::closed_room();
  scene.sources = std::move(sources);
  config.listener_position = Vec3(-2.0f, 1.5f, 0.0f);
  return make_world(scene, config).value();
}

SourceDesc with_signal(std::shared_ptr<const Signal> signal, bool loop, float loudness = 1.0f) {
  SourceDesc s = test::source_at({0.0f, 1.5f, 0.0f});
  s.loudness = loudness;
  s.signal = std::move(signal);
  s.loop = loop;
  return s;
}

TEST(SignalPlan, ToneBurstGivesTheLawsEnergyAndSilencePlansNoRay) {
  // 0.1 s of A = 0.5 then 0.1 s of silence; the source plays by its
  // pattern (always, interval 1 s), so its position is t.
  std::vector<float> samples = square(0.5, 0.1);
  samples.resize(samples.size() * 2, 0.0f);
  const World world = room_world({with_signal(shared(Signal::from_pcm(samples, 48000.0)), false, 2.0f)});
  const std::vector<PlayWindow> none(1);
  const StepPlan burst = plan_step(world, 3, world.listener, none);  // t = 0.05 s
  ASSERT_EQ(burst.sources.size(), 1u);
  EXPECT_NEAR(burst.sources[0].loudness, 2.0 * (60.0 + 20.0 * std::log10(0.5)) / 60.0, 1e-6);
  EXPECT_EQ(burst.sources[0].ray_count, world.config.ray_budget);
  // t = 0.15 s: silence. No rays at all, so no spots.
  const StepPlan quiet = plan_step(world, 9, world.listener, none);
  EXPECT_TRUE(quiet.sources.empty());
  EXPECT_EQ(quiet.total_rays, 0u);
}

TEST(SignalPlan, LoopRepeatsItsEnvelope) {
  // One level per step: loud, silent, quiet, looping.
  const float levels[] = {-6.0f, -static_cast<float>(kInf), -30.0f};
  const World world = room_world({with_signal(shared(Signal::from_levels(levels, 1.0 / 60.0)), true)});
  const std::vector<PlayWindow> none(1);
  const float loud = static_cast<float>(54.0 / 60.0), quiet = 0.5f;
  for (std::uint64_t step = 0; step < 9; ++step) {
    const StepPlan plan = plan_step(world, step, world.listener, none);
    SCOPED_TRACE(step);
    if (step % 3 == 1) {
      EXPECT_TRUE(plan.sources.empty());
    } else {
      ASSERT_EQ(plan.sources.size(), 1u);
      EXPECT_NEAR(plan.sources[0].loudness, step % 3 == 0 ? loud : quiet, 1e-6f);
    }
  }
  // Without the loop, the envelope plays once.
  const World once = room_world({with_signal(shared(Signal::from_levels(levels, 1.0 / 60.0)), false)});
  EXPECT_TRUE(plan_step(once, 3, once.listener, none).sources.empty());
}

TEST(SignalPlan, BelowTheFloorOrAtMinEnergyNothingIsEmitted) {
  const float levels[] = {-59.0f};
  Config config;
  config.min_energy = 0.05f;  // E0 = 1/60 at -59 dB: under tau_min
  const World world = room_world({with_signal(shared(Signal::from_levels(levels, 0.01)), true)}, config);
  EXPECT_TRUE(plan_step(world, 0, world.listener, std::vector<PlayWindow>(1)).sources.empty());
  config.min_energy = 0.0f;  // now it emits, at E0 = 1/60
  const World faint = room_world({with_signal(shared(Signal::from_levels(levels, 0.01)), true)}, config);
  const StepPlan plan = plan_step(faint, 0, faint.listener, std::vector<PlayWindow>(1));
  ASSERT_EQ(plan.sources.size(), 1u);
  EXPECT_NEAR(plan.sources[0].loudness, 1.0f / 60.0f, 1e-7f);
}

TEST(SignalPlan, RayCountFollowsEnergyWithinTheBudget) {
  const float burst[] = {-6.0f}, whisper[] = {-40.0f};
  Config config;
  config.ray_budget = 100;
  const World world = room_world({with_signal(shared(Signal::from_levels(burst, 0.01)), true),
                                  with_signal(shared(Signal::from_levels(whisper, 0.01)), true)},
                                 config);
  const StepPlan plan = plan_step(world, 0, world.listener, std::vector<PlayWindow>(2));
  ASSERT_EQ(plan.sources.size(), 2u);
  // Shares 0.9 : 1/3 of 100 rays: floor(72.97) = 72 and floor(27.03) = 27,
  // the one left over to the lowest id.
  EXPECT_EQ(plan.sources[0].ray_count, 73u);
  EXPECT_EQ(plan.sources[1].ray_count, 27u);
}

// Voices, through a CPU simulator: what a step emits.
class Voices : public ::testing::Test {
 protected:
  void SetUp() override {
    SourceDesc voice = test::source_at({0.0f, 1.5f, 0.0f});
    voice.duration = 0.0;  // silent by pattern: the host says when it plays
    Config config;
    config.ray_budget = 50;
    sim_ = create_cpu_simulator(room_world({voice}, config), CpuSettings{1}).value();
  }
  // Rays the next step emits.
  std::uint64_t step_rays() {
    const std::uint64_t before = sim_->stats().value().rays_emitted;
    EXPECT_TRUE(sim_->step().ok());
    return sim_->stats().value().rays_emitted - before;
  }
  std::unique_ptr<Simulator> sim_;
};

TEST_F(Voices, PlayFromStartToStopAtTheirLevel) {
  SoundScene& scene = sim_->scene();
  EXPECT_EQ(step_rays(), 0u);
  VoiceState state;
  state.position = Vec3(0.5f, 1.5f, 0.0f);
  state.playing = true;
  ASSERT_TRUE(scene.set_voice(0, state).ok());
  EXPECT_EQ(step_rays(), 50u);  // no level given: its plain loudness
  EXPECT_EQ(step_rays(), 50u);  // until told otherwise
  // Fed a block of a half-scale square wave: E0 = 0.8997.
  ASSERT_TRUE(scene.feed_voice(0, square(0.5, 0.01)).ok());
  EXPECT_EQ(step_rays(), 50u);
  for (const Indicator& i : sim_->last_step_indicators().value()) {
    if (i.bounces == 0 && i.penetrations == 0) {
      EXPECT_NEAR(i.energy + i.path_length * sim_->world().config.air_attenuation, 0.89966f, 1e-4f);
    }
  }
  // Silence fed: nothing emitted; then its gain at 0.5 on -6 dB: -12 dB.
  ASSERT_TRUE(scene.feed_voice(0, std::vector<float>(480, 0.0f)).ok());
  EXPECT_EQ(step_rays(), 0u);
  ASSERT_TRUE(scene.set_voice_level(0, 20.0 * std::log10(0.5)).ok());
  state.gain = 0.5f;
  ASSERT_TRUE(scene.set_voice(0, state).ok());
  EXPECT_EQ(step_rays(), 50u);
  for (const Indicator& i : sim_->last_step_indicators().value()) {
    if (i.bounces == 0 && i.penetrations == 0) {
      EXPECT_NEAR(i.energy + i.path_length * sim_->world().config.air_attenuation, (60.0 - 12.0412) / 60.0, 1e-4);
    }
  }
  // Stopped: nothing from the next step on.
  state.playing = false;
  ASSERT_TRUE(scene.set_voice(0, state).ok());
  EXPECT_EQ(step_rays(), 0u);
  EXPECT_EQ(step_rays(), 0u);
}

TEST_F(Voices, SignalPositionPlacesTheEnvelope) {
  // Silent for 0.1 s, then loud: a voice placed at 0.1 s emits at once.
  std::vector<float> samples(4800, 0.0f);
  const std::vector<float> loud = square(0.5, 0.1);
  samples.insert(samples.end(), loud.begin(), loud.end());
  ASSERT_TRUE(sim_->scene().set_signal(0, shared(Signal::from_pcm(samples, 48000.0)), false).ok());
  VoiceState state;
  state.position = Vec3(0.0f, 1.5f, 0.0f);
  state.playing = true;
  ASSERT_TRUE(sim_->scene().set_voice(0, state).ok());
  EXPECT_EQ(step_rays(), 0u);  // at 0 s: silence
  state.signal_position = 0.1;
  ASSERT_TRUE(sim_->scene().set_voice(0, state).ok());
  EXPECT_EQ(step_rays(), 50u);
}

TEST_F(Voices, BadArgumentsAreRefusedNamingThem) {
  SoundScene& scene = sim_->scene();
  VoiceState state;
  state.gain = -1.0f;
  EXPECT_EQ(scene.set_voice(0, state).error().message, "set_voice: gain must be finite and >= 0, got -1.000000");
  EXPECT_NE(scene.set_voice(7, VoiceState{}).error().message.find("unknown source id 7"), std::string::npos);
  EXPECT_FALSE(scene.set_voice_level(0, kInf).ok());
  const float nan_block[] = {0.0f, std::numeric_limits<float>::quiet_NaN()};
  EXPECT_EQ(scene.feed_voice(0, nan_block).error().message, "feed_voice: sample 1 is not finite");
  EXPECT_NE(scene.set_signal(3, nullptr, false).error().message.find("set_signal: unknown source id 3"),
            std::string::npos);
}

TEST(SignalConfig, LawKeysAreParsedAndCheckedNamingThem) {
  const Config c = parse_config(R"({"signal": {"window": 0.01, "floor": -50, "reference": -10}})").value();
  EXPECT_EQ(*c.signal.window, 0.01);
  EXPECT_EQ(c.signal.floor_db, -50.0f);
  EXPECT_EQ(c.signal.reference_db, -10.0f);
  EXPECT_NE(parse_config(R"({"signal": {"floor": 0}})").error().message.find("key \"signal.floor\": must be below"),
            std::string::npos);
  EXPECT_NE(parse_config(R"({"signal": {"window": 2}})").error().message.find("signal.window"), std::string::npos);
  EXPECT_NE(parse_config(R"({"signal": {"gain": 2}})").error().message.find("gain"), std::string::npos);
}

}  // namespace
}  // namespace sp
