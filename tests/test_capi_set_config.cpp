// sp_simulation_set_config (issue 36, item 1): another configuration
// between steps through the C API, with a hand-derived scene: the source
// the creation config gave keeps emitting with the new ray budget and air
// loss, and a bad config is refused through the context's log, naming the
// key, with the simulation stepping on as before.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "soundpaint/soundpaint.h"

namespace {

std::string last_error() { return sp_last_error_message(); }

struct LogRecord {
  std::vector<std::string> messages;
};

void record_log(void* user_data, sp_log_level level, const char* message) {
  if (level == SP_LOG_ERROR) static_cast<LogRecord*>(user_data)->messages.emplace_back(message);
}

// A big quad on the plane z = 1 (|x|, |y| <= 10) facing a source at the
// origin, on which the listener stands.
const std::vector<float> kQuad = {
    -10.0f, -10.0f, 1.0f, -10.0f, 10.0f, 1.0f, 10.0f, 10.0f,  1.0f,  //
    -10.0f, -10.0f, 1.0f, 10.0f,  10.0f, 1.0f, 10.0f, -10.0f, 1.0f,  //
};
const std::vector<std::uint32_t> kQuadLayers = {0, 0};
const char* const kLayerNames[] = {"concrete"};

const char* const kFirstConfig = R"({
  "ray_budget": 64, "max_bounces": 0, "air_attenuation": 0, "seed": 3,
  "listener": { "position": [0, 0, 0] },
  "sources": [ { "position": [0, 0, 0], "loudness": 1.0 } ]
})";

// No "sources" and no "listener": the running ones stay.
const char* const kSecondConfig = R"({ "ray_budget": 16, "max_bounces": 0, "air_attenuation": 0.1, "seed": 3 })";

class CapiSetConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    sp_context_settings settings;
    sp_context_settings_init(&settings);
    settings.log = record_log;
    settings.log_user_data = &log_;
    ASSERT_EQ(sp_context_create(&settings, &context_), SP_OK) << last_error();
    ASSERT_EQ(
        sp_scene_create_in(context_, kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, nullptr, nullptr, 0, &scene_),
        SP_OK)
        << last_error();
    sp_simulation_options options;
    sp_simulation_options_init(&options);
    options.backend = SP_BACKEND_CPU;
    ASSERT_EQ(sp_simulation_create_in(context_, scene_, kFirstConfig, &options, &sim_), SP_OK) << last_error();
  }
  void TearDown() override {
    EXPECT_EQ(sp_simulation_destroy(sim_), SP_OK);
    EXPECT_EQ(sp_scene_destroy(scene_), SP_OK);
    EXPECT_EQ(sp_context_destroy(context_), SP_OK);
  }
  sp_stats stats() {
    sp_stats out{};
    EXPECT_EQ(sp_simulation_stats(sim_, &out), SP_OK) << last_error();
    return out;
  }
  std::vector<sp_indicator> live() {
    std::uint32_t count = 0;
    EXPECT_EQ(sp_simulation_live_indicators(sim_, nullptr, 0, &count), SP_OK) << last_error();
    std::vector<sp_indicator> out(count);
    EXPECT_EQ(sp_simulation_live_indicators(sim_, out.data(), count, &count), SP_OK) << last_error();
    return out;
  }

  LogRecord log_;
  sp_context* context_ = nullptr;
  sp_scene* scene_ = nullptr;
  sp_simulation* sim_ = nullptr;
};

TEST_F(CapiSetConfig, TheConfigSourceEmitsTheNewBudgetWithTheNewAirLoss) {
  ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();
  EXPECT_EQ(stats().rays_emitted, 64u);

  ASSERT_EQ(sp_simulation_set_config(sim_, kSecondConfig), SP_OK) << last_error();
  std::uint32_t sources = 0;
  ASSERT_EQ(sp_simulation_source_count(sim_, &sources), SP_OK);
  EXPECT_EQ(sources, 1u);  // the creation config's source, kept
  ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();
  EXPECT_EQ(stats().rays_emitted, 64u + 16u);

  // No bounce: each ray of step 1 that meets the quad leaves one hit there,
  // its energy 1 - 0.1 * d (air costs alpha per metre), d >= 1 m.
  int step1 = 0;
  for (const sp_indicator& ind : live()) {
    if (ind.step != 1u) continue;
    ++step1;
    EXPECT_NEAR(ind.position[2], 1.0f, 1e-5f);
    EXPECT_GE(ind.path_length, 1.0f - 1e-5f);
    EXPECT_NEAR(ind.energy, 1.0f - 0.1f * ind.path_length, 1e-5f);
    EXPECT_EQ(ind.source_id, 0u);
  }
  EXPECT_GT(step1, 0);
  EXPECT_LT(step1, 16);  // the rays heading away from the quad leave nothing
  EXPECT_TRUE(log_.messages.empty());
}

TEST_F(CapiSetConfig, ABadConfigIsLoggedNamingTheKeyAndChangesNothing) {
  ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();
  EXPECT_EQ(sp_simulation_set_config(sim_, R"({ "diffraction": { "frequency": 0 } })"), SP_ERROR_INVALID_CONFIG);
  ASSERT_EQ(log_.messages.size(), 1u);
  EXPECT_NE(log_.messages[0].find("diffraction.frequency"), std::string::npos) << log_.messages[0];
  EXPECT_EQ(log_.messages[0], last_error());
  EXPECT_EQ(sp_simulation_set_config(sim_, R"({ "ray_budget": 16777217 })"), SP_ERROR_INVALID_CONFIG);
  EXPECT_NE(last_error().find("ray_budget"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_set_config(sim_, "{ not json"), SP_ERROR_INVALID_CONFIG);
  EXPECT_EQ(log_.messages.size(), 3u);

  ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();
  EXPECT_EQ(stats().rays_emitted, 2u * 64u);                           // the first config's budget still
  for (const sp_indicator& ind : live()) EXPECT_EQ(ind.energy, 1.0f);  // and no air loss
}

TEST_F(CapiSetConfig, NullAndDestroyedHandlesAreRefusedAndANullConfigIsEveryDefault) {
  EXPECT_EQ(sp_simulation_set_config(nullptr, kSecondConfig), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_simulation_set_config"), std::string::npos) << last_error();
  sp_simulation* gone = nullptr;
  ASSERT_EQ(sp_simulation_create_in(context_, scene_, kFirstConfig, nullptr, &gone), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_destroy(gone), SP_OK);
  EXPECT_EQ(sp_simulation_set_config(gone, kSecondConfig), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("not live"), std::string::npos) << last_error();
  // NULL config: every default (ray_budget 500), as at creation.
  ASSERT_EQ(sp_simulation_set_config(sim_, nullptr), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();
  EXPECT_EQ(stats().rays_emitted, 500u);
}

}  // namespace
