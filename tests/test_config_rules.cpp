// One table of ranges (src/config/config_rules.h) for a config file and a
// Config made in code: the same value out of range is refused either way,
// naming the same key in the same words (issue 36, item 1: make_world used
// to skip sheet_thickness and every diffraction field, so a C++ host's
// diffraction frequency of 0 reached the shader as an infinite width).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "soundpaint/config.h"
#include "soundpaint/simulation.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

struct BadValue {
  std::string key;                   // the key path both errors must name
  std::string json;                  // a config file's text with the value
  std::function<void(Config&)> set;  // the same value set in code
  std::string words;                 // what both say is expected
};

std::vector<BadValue> bad_values() {
  return {
      {"diffraction.frequency", R"({"diffraction": {"frequency": 0}})", [](Config& c) { c.diffraction.frequency = 0; },
       "must be a number > 0, got 0"},
      {"diffraction.edge_angle", R"({"diffraction": {"edge_angle": 200}})",
       [](Config& c) { c.diffraction.edge_angle = 200; }, "in (0, 180]"},
      {"diffraction.reach", R"({"diffraction": {"reach": -1}})", [](Config& c) { c.diffraction.reach = -1.0f; }, "> 0"},
      {"diffraction.gain", R"({"diffraction": {"gain": 1.5}})", [](Config& c) { c.diffraction.gain = 1.5f; },
       "in [0, 1]"},
      {"layers.glass.sheet_thickness", R"({"layers": {"glass": {"sheet_thickness": -0.01}}})",
       [](Config& c) { c.layers["glass"].sheet_thickness = -0.01f; }, ">= 0"},
      {"layers.wood.attenuation", R"({"layers": {"wood": {"attenuation": -1}}})",
       [](Config& c) { c.layers["wood"].attenuation = -1.0f; }, ">= 0, got -1"},
      {"cues.guide_share", R"({"cues": {"guide_share": 2}})", [](Config& c) { c.cues.guide_share = 2.0f; },
       "in [0, 1]"},
      {"cues.toward_angle", R"({"cues": {"toward_angle": 0}})", [](Config& c) { c.cues.toward_angle = 0.0f; },
       "in (0, 180]"},
      {"max_wall_thickness", R"({"max_wall_thickness": 0})", [](Config& c) { c.max_wall_thickness = 0.0f; }, "> 0"},
      {"bounce_energy_loss", R"({"bounce_energy_loss": 1.5})", [](Config& c) { c.bounce_energy_loss = 1.5f; },
       "in [0, 1]"},
      {"max_indicators", R"({"max_indicators": 0})", [](Config& c) { c.max_indicators = 0; }, "integer in [1, "},
  };
}

TEST(ConfigRules, AValueOutOfRangeIsRefusedAlikeFromAFileAndFromCode) {
  const Scene scene = test::closed_room();
  for (const BadValue& bad : bad_values()) {
    SCOPED_TRACE(bad.key);
    const auto parsed = parse_config(bad.json, "level.json");
    ASSERT_FALSE(parsed.ok());
    EXPECT_EQ(parsed.error().code, ErrorCode::InvalidConfig);
    EXPECT_NE(parsed.error().message.find("key \"" + bad.key + "\""), std::string::npos) << parsed.error().message;
    EXPECT_NE(parsed.error().message.find(bad.words), std::string::npos) << parsed.error().message;

    Config config;
    config.listener_position = Vec3{0.0f, 1.5f, 0.0f};
    bad.set(config);
    const auto world = make_world(scene, config);
    ASSERT_FALSE(world.ok());
    EXPECT_EQ(world.error().code, ErrorCode::InvalidConfig);
    EXPECT_NE(world.error().message.find("key \"" + bad.key + "\""), std::string::npos) << world.error().message;
    EXPECT_NE(world.error().message.find(bad.words), std::string::npos) << world.error().message;
  }
}

// What JSON cannot write, code can: infinities and NaN are named too.
TEST(ConfigRules, NonFiniteValuesFromCodeAreNamed) {
  Config config;
  config.listener_position = Vec3{0.0f, 1.5f, 0.0f};
  config.diffraction.frequency = INFINITY;
  auto world = make_world(test::closed_room(), config);
  ASSERT_FALSE(world.ok());
  EXPECT_NE(world.error().message.find("key \"diffraction.frequency\": must be a finite number > 0, got infinity"),
            std::string::npos)
      << world.error().message;
  config = Config{};
  config.listener_position = Vec3{0.0f, NAN, 0.0f};
  world = make_world(test::closed_room(), config);
  ASSERT_FALSE(world.ok());
  EXPECT_NE(world.error().message.find("key \"listener.position[1]\""), std::string::npos) << world.error().message;
}

}  // namespace
}  // namespace sp
