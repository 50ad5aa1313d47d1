// The C API of signals and voices (soundpaint_signal.h): a 16-bit burst
// read at its hand-derived level, attached to a voice whose spots then carry
// the law's E0; silence paints nothing; misuse gets an error naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "soundpaint/soundpaint.h"
#include "soundpaint/soundpaint_signal.h"

namespace {

std::string last_error() { return sp_last_error_message(); }

// A quad on z = 1 in front of a voice at the origin, heard there.
const std::vector<float> kQuad = {-10, -10, 1, -10, 10, 1, 10, 10, 1, -10, -10, 1, 10, 10, 1, 10, -10, 1};
const std::uint32_t kLayers[] = {0, 0};
const char* const kLayerNames[] = {"concrete"};
const char* const kConfig = R"({
  "ray_budget": 64, "max_bounces": 0, "air_attenuation": 0, "seed": 3,
  "listener": { "position": [0, 0, 0] },
  "sources": [ { "position": [0, 0, 0], "duration": 0 } ]
})";

class CapiSignal : public ::testing::Test {
 protected:
  void SetUp() override {
    sp_scene* scene = nullptr;
    ASSERT_EQ(sp_scene_create(kQuad.data(), 2, kLayers, kLayerNames, 1, &scene), SP_OK) << last_error();
    ASSERT_EQ(sp_simulation_create(scene, kConfig, SP_BACKEND_CPU, &sim_), SP_OK) << last_error();
    sp_scene_destroy(scene);
    ASSERT_EQ(sp_simulation_scene(sim_, &sound_), SP_OK);
  }
  void TearDown() override { sp_simulation_destroy(sim_); }
  // Steps once and returns its live indicators of that step.
  std::vector<sp_indicator> step() {
    EXPECT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();
    uint32_t n = 0;
    EXPECT_EQ(sp_simulation_live_indicators(sim_, nullptr, 0, &n), SP_OK);
    std::vector<sp_indicator> all(n);
    EXPECT_EQ(sp_simulation_live_indicators(sim_, all.data(), n, &n), SP_OK);
    sp_stats stats{};
    EXPECT_EQ(sp_simulation_stats(sim_, &stats), SP_OK);
    std::vector<sp_indicator> out;
    for (const sp_indicator& i : all)
      if (i.step + 1 == stats.steps) out.push_back(i);
    return out;
  }
  sp_simulation* sim_ = nullptr;
  sp_sound_scene* sound_ = nullptr;
};

TEST_F(CapiSignal, BurstThroughAVoiceCarriesTheLawsEnergy) {
  // 50 ms of a quarter-scale 16-bit square wave (8192 of 32768): -12.04 dB.
  std::vector<int16_t> burst(2400);
  for (std::size_t i = 0; i < burst.size(); ++i) burst[i] = static_cast<int16_t>(i % 2 == 0 ? 8192 : -8192);
  sp_signal* signal = nullptr;
  ASSERT_EQ(sp_signal_create_s16(burst.data(), burst.size(), 48000.0, 1, &signal), SP_OK) << last_error();
  double seconds = 0.0, level = 0.0;
  ASSERT_EQ(sp_signal_duration(signal, &seconds), SP_OK);
  EXPECT_NEAR(seconds, 0.05, 1e-12);
  ASSERT_EQ(sp_signal_level_db(signal, 0.0, 0.01, 0, &level), SP_OK);
  EXPECT_NEAR(level, 20.0 * std::log10(0.25), 1e-9);
  ASSERT_EQ(sp_sound_scene_set_signal(sound_, 0, signal, 0), SP_OK) << last_error();
  ASSERT_EQ(sp_signal_destroy(signal), SP_OK);  // the source keeps its own

  EXPECT_TRUE(step().empty());  // not playing yet
  sp_voice_state state;
  sp_voice_state_init(&state);
  EXPECT_EQ(state.gain, 1.0f);
  state.playing = 1;
  ASSERT_EQ(sp_sound_scene_set_voice(sound_, 0, &state), SP_OK) << last_error();
  const std::vector<sp_indicator> spots = step();
  ASSERT_FALSE(spots.empty());
  const double e0 = (60.0 + 20.0 * std::log10(0.25)) / 60.0;  // 0.7993, no air loss
  for (const sp_indicator& i : spots) EXPECT_NEAR(i.energy, e0, 1e-6);
  // Past the burst's 50 ms the voice plays silence: nothing is painted.
  for (int n = 0; n < 3; ++n) step();
  EXPECT_TRUE(step().empty());
  // A level fed from samples overrides the signal; silence stops it again.
  const float half[] = {0.5f, -0.5f, 0.5f, -0.5f};
  ASSERT_EQ(sp_sound_scene_feed_voice(sound_, 0, half, 4), SP_OK) << last_error();
  const std::vector<sp_indicator> fed = step();
  ASSERT_FALSE(fed.empty());
  EXPECT_NEAR(fed[0].energy, (60.0 + 20.0 * std::log10(0.5)) / 60.0, 1e-6);
  ASSERT_EQ(sp_sound_scene_set_voice_level(sound_, 0, -std::numeric_limits<double>::infinity()), SP_OK);
  EXPECT_TRUE(step().empty());
}

TEST_F(CapiSignal, MisuseIsRefusedNamingTheProblem) {
  sp_signal* signal = nullptr;
  const float samples[] = {0.1f, 0.2f};
  EXPECT_EQ(sp_signal_create_f32(samples, 2, 10.0, 1, &signal), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sample_rate must be in [1000, 768000]"), std::string::npos) << last_error();
  EXPECT_EQ(sp_signal_create_f32(nullptr, 2, 48000.0, 1, &signal), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "sp_signal_create_f32: samples is NULL");
  EXPECT_EQ(signal, nullptr);
  ASSERT_EQ(sp_signal_create_f32(samples, 2, 48000.0, 1, &signal), SP_OK);
  ASSERT_EQ(sp_signal_destroy(signal), SP_OK);
  double seconds = 0.0;
  EXPECT_EQ(sp_signal_duration(signal, &seconds), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("signal handle is not live"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_set_voice(sound_, 0, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "sp_sound_scene_set_voice: state is NULL");
  sp_voice_state state;
  sp_voice_state_init(&state);
  state.position[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(sp_sound_scene_set_voice(sound_, 0, &state), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "set_voice: position must be finite");
  EXPECT_EQ(sp_sound_scene_set_voice_level(sound_, 9, -6.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("unknown source id 9"), std::string::npos) << last_error();
  EXPECT_EQ(sp_signal_destroy(nullptr), SP_OK);
}

}  // namespace
