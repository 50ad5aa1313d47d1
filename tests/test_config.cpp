// Tests for the JSON configuration (SPEC section 2) and layer presets.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "soundpaint/config.h"

namespace {

using sp::BudgetWeighting;
using sp::Config;
using sp::ErrorCode;
using sp::LayerProperties;

Config parse_ok(std::string_view json) {
  auto result = sp::parse_config(json, "test.json");
  EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().message);
  return result.ok() ? result.value() : Config{};
}

// Parsing must fail with InvalidConfig, and the one-line message must start
// with the origin and contain every fragment (usually the key path).
void expect_error(std::string_view json, std::initializer_list<std::string_view> fragments) {
  SCOPED_TRACE(std::string(json));
  const auto result = sp::parse_config(json, "test.json");
  ASSERT_FALSE(result.ok());
  const sp::Error& error = result.error();
  EXPECT_EQ(error.code, ErrorCode::InvalidConfig);
  EXPECT_EQ(error.message.rfind("test.json: ", 0), 0u) << error.message;
  EXPECT_EQ(error.message.find('\n'), std::string::npos) << error.message;
  for (const std::string_view fragment : fragments) {
    EXPECT_NE(error.message.find(fragment), std::string::npos)
        << "missing \"" << fragment << "\" in: " << error.message;
  }
}

void expect_layer(const LayerProperties& actual, float reflect_probability, float attenuation) {
  EXPECT_FLOAT_EQ(actual.reflect_probability, reflect_probability);
  EXPECT_FLOAT_EQ(actual.attenuation, attenuation);
}

// ---------------------------------------------------------------- defaults

TEST(ConfigDefaults, EmptyObjectGivesDocumentedDefaults) {
  const Config config = parse_ok(" {\n} ");
  EXPECT_FLOAT_EQ(config.scan_radius, 50.0f);
  EXPECT_EQ(config.ray_budget, 500u);
  EXPECT_EQ(config.max_indicators, 4000u);                    // SPEC 2: ours to choose (config.h says why)
  EXPECT_EQ(config.budget_weighting, BudgetWeighting::Even);  // SPEC 2
  EXPECT_EQ(config.max_bounces, 4u);
  EXPECT_FLOAT_EQ(config.bounce_energy_loss, 0.2f);
  EXPECT_FLOAT_EQ(config.max_wall_thickness, 0.5f);
  EXPECT_FLOAT_EQ(config.min_energy, 0.05f);
  EXPECT_FLOAT_EQ(config.air_attenuation, 0.02f);
  EXPECT_FLOAT_EQ(config.indicator_size, 0.25f);
  EXPECT_FLOAT_EQ(config.indicator_lifetime, 1.0f);
  EXPECT_DOUBLE_EQ(config.dt, 1.0 / 60.0);  // SPEC 2
  EXPECT_EQ(config.seed, 1u);
  EXPECT_TRUE(config.layers.empty());
  EXPECT_FALSE(config.listener_position.has_value());
  EXPECT_TRUE(config.sources.empty());
}

// ---------------------------------------------------------------- every key

TEST(ConfigParse, EveryTopLevelKey) {
  const Config config = parse_ok(R"({
    "scan_radius": 12.5,
    "ray_budget": 1000,
    "max_indicators": 123,
    "budget_weighting": "proximity",
    "max_bounces": 7,
    "bounce_energy_loss": 0.35,
    "max_wall_thickness": 0.75,
    "min_energy": 0.01,
    "air_attenuation": 0,
    "indicator_size": 0.5,
    "indicator_lifetime": 2.5,
    "dt": 0.02,
    "seed": 4294967295,
    "layers": {"Stone": {"reflect_probability": 0.6, "attenuation": 3}},
    "listener": {"position": [1, 2.5, -3]},
    "sources": [{"position": [4, 5, 6]}]
  })");
  EXPECT_FLOAT_EQ(config.scan_radius, 12.5f);
  EXPECT_EQ(config.ray_budget, 1000u);
  EXPECT_EQ(config.max_indicators, 123u);
  EXPECT_EQ(config.budget_weighting, BudgetWeighting::Proximity);
  EXPECT_EQ(config.max_bounces, 7u);
  EXPECT_FLOAT_EQ(config.bounce_energy_loss, 0.35f);
  EXPECT_FLOAT_EQ(config.max_wall_thickness, 0.75f);
  EXPECT_FLOAT_EQ(config.min_energy, 0.01f);
  EXPECT_FLOAT_EQ(config.air_attenuation, 0.0f);
  EXPECT_FLOAT_EQ(config.indicator_size, 0.5f);
  EXPECT_FLOAT_EQ(config.indicator_lifetime, 2.5f);
  EXPECT_DOUBLE_EQ(config.dt, 0.02);
  EXPECT_EQ(config.seed, 4294967295u);
  ASSERT_EQ(config.layers.count("Stone"), 1u);
  expect_layer(config.layers.at("Stone"), 0.6f, 3.0f);
  ASSERT_TRUE(config.listener_position.has_value());
  EXPECT_EQ(*config.listener_position, glm::vec3(1.0f, 2.5f, -3.0f));
  ASSERT_EQ(config.sources.size(), 1u);
  EXPECT_EQ(config.sources[0].position, glm::vec3(4.0f, 5.0f, 6.0f));
}

TEST(ConfigParse, EveryBudgetWeighting) {
  EXPECT_EQ(parse_ok(R"({"budget_weighting": "even"})").budget_weighting, BudgetWeighting::Even);
  EXPECT_EQ(parse_ok(R"({"budget_weighting": "proximity"})").budget_weighting, BudgetWeighting::Proximity);
}

// The CPU backend's traversal: soundpaint's own by default; Embree only
// where the library was built with it, else an error saying how to get it.
TEST(ConfigParse, CpuTraversal) {
  EXPECT_EQ(parse_ok("{}").cpu_traversal, sp::CpuTraversal::Soundpaint);
  EXPECT_EQ(parse_ok(R"({"cpu_traversal": "soundpaint"})").cpu_traversal, sp::CpuTraversal::Soundpaint);
  expect_error(R"({"cpu_traversal": "optix"})", {"cpu_traversal", R"(must be "soundpaint" or "embree")"});
  expect_error(R"({"cpu_traversal": 1})", {"cpu_traversal", R"(must be "soundpaint" or "embree")"});
#ifdef SOUNDPAINT_HAVE_EMBREE
  EXPECT_TRUE(sp::embree_available());
  EXPECT_EQ(parse_ok(R"({"cpu_traversal": "embree"})").cpu_traversal, sp::CpuTraversal::Embree);
#else
  EXPECT_FALSE(sp::embree_available());
  expect_error(R"({"cpu_traversal": "embree"})", {"cpu_traversal", "-DSOUNDPAINT_EMBREE=ON"});
#endif
}

TEST(ConfigParse, EverySourceField) {
  const Config config = parse_ok(R"({"sources": [
    {"position": [1, 2, 3], "color": [1, 0.5, 0], "category": "footsteps", "max_distance": 12,
     "loudness": 2, "duration": 0.1, "interval": 0.25, "phase": 0.05, "name": "boots"},
    {"position": [-1, 0, 0]}
  ]})");
  ASSERT_EQ(config.sources.size(), 2u);
  const sp::SourceDesc& a = config.sources[0];
  EXPECT_EQ(a.name, "boots");
  EXPECT_EQ(a.position, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(a.color, glm::vec3(1.0f, 0.5f, 0.0f));
  EXPECT_EQ(a.category, "footsteps");
  EXPECT_FLOAT_EQ(a.max_distance, 12.0f);
  EXPECT_FLOAT_EQ(a.loudness, 2.0f);
  EXPECT_DOUBLE_EQ(a.duration, 0.1);
  EXPECT_DOUBLE_EQ(a.interval, 0.25);
  EXPECT_DOUBLE_EQ(a.phase, 0.05);

  // Omitted fields keep the SourceDesc defaults.
  const sp::SourceDesc& b = config.sources[1];
  const sp::SourceDesc defaults;
  EXPECT_EQ(b.position, glm::vec3(-1.0f, 0.0f, 0.0f));
  EXPECT_EQ(b.name, defaults.name);
  EXPECT_EQ(b.color, defaults.color);
  EXPECT_EQ(b.category, defaults.category);
  EXPECT_EQ(b.max_distance, defaults.max_distance);
  EXPECT_EQ(b.loudness, defaults.loudness);
  EXPECT_EQ(b.duration, defaults.duration);
  EXPECT_EQ(b.interval, defaults.interval);
  EXPECT_EQ(b.phase, defaults.phase);
}

TEST(ConfigParse, InclusiveBoundsAreAccepted) {
  const Config config = parse_ok(R"({"ray_budget": 0, "max_bounces": 64, "max_indicators": 16777216,
    "bounce_energy_loss": 1, "seed": 0, "scan_radius": 0, "min_energy": 0,
    "layers": {"x": {"reflect_probability": 0, "attenuation": 0}}})");
  EXPECT_EQ(config.ray_budget, 0u);
  EXPECT_EQ(config.max_bounces, sp::kMaxBouncesLimit);
  EXPECT_EQ(config.max_indicators, sp::kMaxIndicatorsLimit);
  EXPECT_EQ(parse_ok(R"({"ray_budget": 16777216})").ray_budget, sp::kMaxRayBudget);
  EXPECT_FLOAT_EQ(config.bounce_energy_loss, 1.0f);
  expect_layer(config.layers.at("x"), 0.0f, 0.0f);
}

// ---------------------------------------------------------------- errors

TEST(ConfigErrors, MessageFormatNamesOriginAndKeyPath) {
  const auto result = sp::parse_config(R"({"layers": {"wood": {"attenuation": -1}}})", "config.json");
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().message, R"(config.json: key "layers.wood.attenuation": must be a number >= 0, got -1)");
}

TEST(ConfigErrors, UnknownKeys) {
  expect_error(R"({"ray_budgte": 10})", {R"(unknown key "ray_budgte")", R"(did you mean "ray_budget")"});
  expect_error(R"({"colour_mode": 1})", {R"(unknown key "colour_mode")"});
  expect_error(R"({"layers": {"wood": {"reflectivity": 0.5}}})", {R"(unknown key "layers.wood.reflectivity")"});
  expect_error(R"({"listener": {"position": [0, 0, 0], "forward": [0, 0, 1]}})", {R"(unknown key "listener.forward")"});
  expect_error(R"({"sources": [{"position": [0, 0, 0]}, {"position": [0, 0, 0], "volume": 1}]})",
               {R"(unknown key "sources[1].volume")"});
}

TEST(ConfigErrors, WrongTypes) {
  expect_error(R"({"scan_radius": "50"})", {R"("scan_radius")", "must be a number"});
  expect_error(R"({"scan_radius": true})", {R"("scan_radius")", "must be a number", "got true"});
  expect_error(R"({"ray_budget": false})", {R"("ray_budget")", "must be an integer"});
  expect_error(R"({"min_energy": null})", {R"("min_energy")", "got null"});
  expect_error(R"({"budget_weighting": 1})", {R"("budget_weighting")"});
  expect_error(R"({"layers": []})", {R"("layers")", "must be an object"});
  expect_error(R"({"layers": {"wood": 0.5}})", {R"("layers.wood")", "must be an object"});
  expect_error(R"({"listener": [0, 0, 0]})", {R"("listener")", "must be an object"});
  expect_error(R"({"listener": {"position": [0, 0]}})", {R"("listener.position")", "3 numbers"});
  expect_error(R"({"listener": {"position": [0, "1", 0]}})", {R"("listener.position[1]")"});
  expect_error(R"({"sources": {"position": [0, 0, 0]}})", {R"("sources")", "must be an array"});
  expect_error(R"({"sources": [[0, 0, 0]]})", {R"("sources[0]")", "must be an object"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "category": 3}]})", {R"("sources[0].category")", "string"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "name": null}]})", {R"("sources[0].name")", "string"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "color": "red"}]})", {R"("sources[0].color")"});
  expect_error("[1, 2]", {"top level must be a JSON object"});
  expect_error("42", {"top level must be a JSON object"});
}

TEST(ConfigErrors, CountsMustBeIntegerLiterals) {
  expect_error(R"({"ray_budget": 5.5})", {R"("ray_budget")", "must be an integer", "got 5.5"});
  expect_error(R"({"ray_budget": 5.0})", {R"("ray_budget")", "must be an integer"});
  expect_error(R"({"max_indicators": 1e3})", {R"("max_indicators")", "must be an integer"});
  expect_error(R"({"max_bounces": 2.0})", {R"("max_bounces")", "must be an integer"});
  expect_error(R"({"seed": 7.0})", {R"("seed")", "must be an integer"});
}

TEST(ConfigErrors, NegativeWhereNonNegativeRequired) {
  expect_error(R"({"scan_radius": -1})", {R"("scan_radius")", ">= 0", "got -1"});
  expect_error(R"({"min_energy": -0.1})", {R"("min_energy")", ">= 0"});
  expect_error(R"({"air_attenuation": -0.5})", {R"("air_attenuation")", ">= 0"});
  expect_error(R"({"indicator_size": -1})", {R"("indicator_size")", ">= 0"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "loudness": -1}]})", {R"("sources[0].loudness")", ">= 0"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "max_distance": -1}]})", {R"("sources[0].max_distance")"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "duration": -1}]})", {R"("sources[0].duration")"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "phase": -0.5}]})", {R"("sources[0].phase")"});
  expect_error(R"({"ray_budget": -1})", {R"("ray_budget")", "[0, 16777216]"});
  expect_error(R"({"seed": -1})", {R"("seed")"});
}

TEST(ConfigErrors, ZeroWherePositiveRequired) {
  expect_error(R"({"dt": 0})", {R"("dt")", "> 0"});
  expect_error(R"({"max_wall_thickness": 0})", {R"("max_wall_thickness")", "> 0"});
  expect_error(R"({"indicator_lifetime": 0})", {R"("indicator_lifetime")", "> 0"});
  expect_error(R"({"max_indicators": 0})", {R"("max_indicators")"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "interval": 0}]})", {R"("sources[0].interval")", "> 0"});
  // A positive double that is 0 once stored as a float is still zero.
  expect_error(R"({"max_wall_thickness": 1e-50})", {R"("max_wall_thickness")", "> 0"});
}

TEST(ConfigErrors, AboveUpperBound) {
  expect_error(R"({"layers": {"wood": {"reflect_probability": 1.5}}})",
               {R"("layers.wood.reflect_probability")", "in [0, 1]"});
  expect_error(R"({"bounce_energy_loss": 1.01})", {R"("bounce_energy_loss")", "in [0, 1]"});
  expect_error(R"({"sources": [{"position": [0, 0, 0], "color": [1, 1.2, 1]}]})", {R"("sources[0].color[1]")"});
  expect_error(R"({"max_bounces": 65})", {R"("max_bounces")", "[0, 64]"});
  expect_error(R"({"ray_budget": 16777217})", {R"("ray_budget")"});
  expect_error(R"({"max_indicators": 16777217})", {R"("max_indicators")"});
  expect_error(R"({"seed": 4294967296})", {R"("seed")"});
}

TEST(ConfigErrors, NonFiniteAndOutOfFloatRange) {
  // nlohmann rejects overflowing literals while parsing; the key is still named.
  expect_error(R"({"scan_radius": 1e999})", {R"(key "scan_radius")", "finite", "got 1e999"});
  expect_error(R"({"dt": -1e999})", {R"(key "dt")", "finite"});
  expect_error(R"({"listener": {"position": [0, 1e999, 0]}})", {R"(key "listener.position[1]")", "finite"});
  expect_error(R"({"sources": [{"position": [0, 0, 0]}, {"position": [1e999, 0, 0]}]})",
               {R"(key "sources[1].position[0]")", "finite"});
  expect_error(R"({"layers": {"a": {"attenuation": 1}, "b": {"attenuation": 1e400}}})",
               {R"(key "layers.b.attenuation")", "finite"});
  expect_error(R"({"indicator_size": 1e300})", {R"("indicator_size")", "float range"});
  expect_error(R"({"sources": [{"position": [0, 0, -1e39]}]})", {R"("sources[0].position[2]")", "float range"});
}

TEST(ConfigErrors, BadBudgetWeighting) {
  expect_error(R"({"budget_weighting": "uniform"})", {R"("budget_weighting")", R"("even" or "proximity")"});
  expect_error(R"({"budget_weighting": "Even"})", {R"("budget_weighting")"});
}

TEST(ConfigErrors, MissingRequiredKeysAndEmptyNames) {
  expect_error(R"({"sources": [{"position": [0, 0, 0]}, {"loudness": 1}]})", {R"("sources[1]")", "position"});
  expect_error(R"({"listener": {}})", {R"("listener")", "position"});
  expect_error(R"({"layers": {"": {}}})", {R"("layers")", "empty"});
}

TEST(ConfigErrors, DuplicateKeys) {
  expect_error(R"({"ray_budget": 1, "ray_budget": 2})", {R"(duplicate key "ray_budget")"});
  expect_error(R"({"sources": [{"position": [0, 0, 0]}, {"position": [0, 0, 0], "phase": 1, "phase": 2}]})",
               {R"(duplicate key "sources[1].phase")"});
  // The same key in different objects is fine.
  parse_ok(R"({"layers": {"a": {"attenuation": 1}, "b": {"attenuation": 2}}})");
}

TEST(ConfigErrors, MalformedJson) {
  expect_error(R"({"ray_budget": })", {"malformed JSON", "line 1"});
  expect_error("{\n  \"seed\": 1,\n}", {"malformed JSON", "line 3"});
  expect_error("", {"malformed JSON"});
  expect_error(R"({"scan_radius": NaN})", {"malformed JSON"});
}

// ---------------------------------------------------------------- files

TEST(ConfigLoad, MissingFileIsIoErrorNamingPath) {
  const auto path = std::filesystem::temp_directory_path() / "soundpaint-test-config-does-not-exist.json";
  std::filesystem::remove(path);
  const auto result = sp::load_config(path);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::Io);
  EXPECT_NE(result.error().message.find(path.string()), std::string::npos) << result.error().message;
}

TEST(ConfigLoad, DirectoryIsIoError) {
  const auto result = sp::load_config(std::filesystem::temp_directory_path());
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::Io);
}

TEST(ConfigLoad, ReadsFileAndNamesItInErrors) {
  const auto path =
      std::filesystem::temp_directory_path() /
      ("soundpaint-test-config-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".json");
  { std::ofstream(path) << R"({"ray_budget": 77})"; }
  const auto good = sp::load_config(path);
  ASSERT_TRUE(good.ok()) << good.error().message;
  EXPECT_EQ(good.value().ray_budget, 77u);

  { std::ofstream(path) << R"({"ray_budget": -77})"; }
  const auto bad = sp::load_config(path);
  std::filesystem::remove(path);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ErrorCode::InvalidConfig);
  EXPECT_EQ(bad.error().message.rfind(path.string() + ": key \"ray_budget\"", 0), 0u) << bad.error().message;
}

// ---------------------------------------------------------------- presets

TEST(LayerPresets, HasTheDocumentedPresetsInRange) {
  const auto& presets = sp::layer_presets();
  for (const char* name : {"concrete", "brick", "wood", "glass", "metal", "carpet", "default"}) {
    ASSERT_EQ(presets.count(name), 1u) << name;
  }
  for (const auto& [name, properties] : presets) {
    EXPECT_GE(properties.reflect_probability, 0.0f) << name;
    EXPECT_LE(properties.reflect_probability, 1.0f) << name;
    EXPECT_GE(properties.attenuation, 0.0f) << name;
  }
  // Hard materials reflect more than soft ones.
  EXPECT_GT(presets.at("metal").reflect_probability, presets.at("wood").reflect_probability);
  EXPECT_GT(presets.at("concrete").reflect_probability, presets.at("carpet").reflect_probability);
}

TEST(LayerPresets, DefaultPresetEqualsLayerPropertiesDefaults) {
  const LayerProperties defaults;
  expect_layer(sp::layer_presets().at("default"), defaults.reflect_probability, defaults.attenuation);
  expect_layer(defaults, 0.8f, 2.0f);
}

TEST(ResolveLayer, ExactConfigEntryWins) {
  Config config;
  config.layers["Wood.001"] = {0.11f, 0.22f};
  config.layers["wood"] = {0.33f, 0.44f};
  expect_layer(sp::resolve_layer(config, "Wood.001"), 0.11f, 0.22f);
  expect_layer(sp::resolve_layer(config, "wood"), 0.33f, 0.44f);
}

TEST(ResolveLayer, PresetMatchedCaseInsensitivelyWithoutBlenderSuffix) {
  const Config config;
  const LayerProperties wood = sp::layer_presets().at("wood");
  expect_layer(sp::resolve_layer(config, "Wood.001"), wood.reflect_probability, wood.attenuation);
  expect_layer(sp::resolve_layer(config, "WOOD"), wood.reflect_probability, wood.attenuation);
  const LayerProperties metal = sp::layer_presets().at("metal");
  expect_layer(sp::resolve_layer(config, "Metal.12"), metal.reflect_probability, metal.attenuation);
  // Only ".<digits>" is a Blender suffix.
  const LayerProperties fallback = sp::layer_presets().at("default");
  expect_layer(sp::resolve_layer(config, "wood.abc"), fallback.reflect_probability, fallback.attenuation);
  expect_layer(sp::resolve_layer(config, "wood."), fallback.reflect_probability, fallback.attenuation);
  expect_layer(sp::resolve_layer(config, "woodland"), fallback.reflect_probability, fallback.attenuation);
}

TEST(ResolveLayer, ConfigEntryAlsoMatchesNormalisedName) {
  const Config config = parse_ok(R"({"layers": {"wood": {"reflect_probability": 0.05, "attenuation": 0.5}}})");
  expect_layer(sp::resolve_layer(config, "Wood.003"), 0.05f, 0.5f);
}

TEST(ResolveLayer, UnknownFallsBackToConfigDefaultThenPreset) {
  const Config with_default = parse_ok(R"({"layers": {"default": {"reflect_probability": 0.3, "attenuation": 9}}})");
  expect_layer(sp::resolve_layer(with_default, "mystery"), 0.3f, 9.0f);
  expect_layer(sp::resolve_layer(with_default, "default"), 0.3f, 9.0f);
  // Presets still beat the config's default entry.
  const LayerProperties brick = sp::layer_presets().at("brick");
  expect_layer(sp::resolve_layer(with_default, "Brick"), brick.reflect_probability, brick.attenuation);

  const Config without_default;
  const LayerProperties fallback = sp::layer_presets().at("default");
  expect_layer(sp::resolve_layer(without_default, "mystery"), fallback.reflect_probability, fallback.attenuation);
  expect_layer(sp::resolve_layer(without_default, ""), fallback.reflect_probability, fallback.attenuation);
}

TEST(ResolveLayer, PartialOverrideKeepsThePresetsOtherField) {
  const Config config = parse_ok(R"({"layers": {
    "wood": {"attenuation": 9},
    "Glass.002": {"reflect_probability": 0.1},
    "curtain": {"attenuation": 1},
    "default": {"reflect_probability": 0.4}
  }})");
  const auto& presets = sp::layer_presets();
  expect_layer(config.layers.at("wood"), presets.at("wood").reflect_probability, 9.0f);
  expect_layer(config.layers.at("Glass.002"), 0.1f, presets.at("glass").attenuation);
  // No preset named "curtain": the omitted field comes from the config's
  // default entry, which itself takes its omitted field from the preset.
  expect_layer(config.layers.at("default"), 0.4f, presets.at("default").attenuation);
  expect_layer(config.layers.at("curtain"), 0.4f, 1.0f);
  expect_layer(sp::resolve_layer(config, "wood"), presets.at("wood").reflect_probability, 9.0f);

  const Config no_default = parse_ok(R"({"layers": {"curtain": {"attenuation": 1}}})");
  expect_layer(no_default.layers.at("curtain"), presets.at("default").reflect_probability, 1.0f);
}

}  // namespace

// SPEC 1.5: the display block, every key with a value, then each bad value
// named by its key path.
TEST(ConfigDisplay, EveryKeyIsRead) {
  const Config config = parse_ok(R"({"display": {
      "palette": "high-contrast", "shapes": {"footsteps": "ring", "drone": "star"},
      "direction": false, "outline": false, "size_scale": 1.5, "opacity_scale": 0.5,
      "min_opacity": 0.2, "hide_categories": ["footsteps"], "max_per_category": 30,
      "offscreen_arrows": false}})");
  const sp::DisplaySettings& d = config.display;
  EXPECT_EQ(d.palette, sp::Palette::HighContrast);
  EXPECT_EQ(d.shapes.at("footsteps"), sp::Shape::Ring);
  EXPECT_EQ(d.shapes.at("drone"), sp::Shape::Star);
  EXPECT_FALSE(d.direction);
  EXPECT_FALSE(d.outline);
  EXPECT_FLOAT_EQ(d.size_scale, 1.5f);
  EXPECT_FLOAT_EQ(d.opacity_scale, 0.5f);
  EXPECT_FLOAT_EQ(d.min_opacity, 0.2f);
  EXPECT_EQ(d.hide_categories, std::vector<std::string>{"footsteps"});
  EXPECT_EQ(d.max_per_category, 30u);
  EXPECT_EQ(d.offscreen_arrows, false);
}

TEST(ConfigDisplay, DefaultsAreTheSpecs) {
  const sp::DisplaySettings d = parse_ok("{}").display;
  EXPECT_EQ(d.palette, sp::Palette::OkabeIto);
  EXPECT_TRUE(d.shapes.empty());
  EXPECT_TRUE(d.direction);
  EXPECT_TRUE(d.outline);
  EXPECT_EQ(d.size_scale, 1.0f);
  EXPECT_EQ(d.opacity_scale, 1.0f);
  EXPECT_EQ(d.min_opacity, 0.0f);
  EXPECT_TRUE(d.hide_categories.empty());
  EXPECT_FALSE(d.max_per_category.has_value());
  EXPECT_FALSE(d.offscreen_arrows.has_value());  // the front end decides
}

TEST(ConfigDisplay, BadValuesNameTheKey) {
  expect_error(R"({"display": 3})", {"display"});
  expect_error(R"({"display": {"palette": "rainbow"}})", {"display.palette", "okabe-ito"});
  expect_error(R"({"display": {"palette": 1}})", {"display.palette"});
  expect_error(R"({"display": {"shapes": {"footsteps": "blob"}}})", {"display.shapes.footsteps", "disc"});
  expect_error(R"({"display": {"shapes": ["disc"]}})", {"display.shapes"});
  expect_error(R"({"display": {"shapes": {"": "disc"}}})", {"display.shapes"});
  expect_error(R"({"display": {"direction": "yes"}})", {"display.direction"});
  expect_error(R"({"display": {"outline": 1}})", {"display.outline"});
  expect_error(R"({"display": {"size_scale": 0}})", {"display.size_scale"});
  expect_error(R"({"display": {"size_scale": -1}})", {"display.size_scale"});
  expect_error(R"({"display": {"opacity_scale": -0.5}})", {"display.opacity_scale"});
  expect_error(R"({"display": {"min_opacity": 1.5}})", {"display.min_opacity"});
  expect_error(R"({"display": {"min_opacity": -0.1}})", {"display.min_opacity"});
  expect_error(R"({"display": {"hide_categories": "footsteps"}})", {"display.hide_categories"});
  expect_error(R"({"display": {"hide_categories": [3]}})", {"display.hide_categories[0]"});
  expect_error(R"({"display": {"max_per_category": -1}})", {"display.max_per_category"});
  expect_error(R"({"display": {"max_per_category": 2.5}})", {"display.max_per_category"});
  expect_error(R"({"display": {"offscreen_arrows": null}})", {"display.offscreen_arrows"});
  expect_error(R"({"display": {"colour": "red"}})", {"display.colour"});
}

TEST(ConfigDiffraction, EveryKeyIsReadAndOffIsTheDefault) {
  const sp::DiffractionSettings off = parse_ok("{}").diffraction;
  EXPECT_FALSE(off.enabled);
  EXPECT_EQ(off.edge_angle, 45.0f);
  EXPECT_EQ(off.frequency, 500.0f);
  EXPECT_FALSE(off.reach.has_value());
  EXPECT_EQ(off.gain, 1.0f);
  EXPECT_FLOAT_EQ(sp::diffraction_reach(off), 343.0f / 1000.0f);  // half a wavelength at 500 Hz
  const sp::DiffractionSettings d =
      parse_ok(R"({"diffraction": {"enabled": true, "edge_angle": 80, "frequency": 250, "reach": 0.5, "gain": 0.25}})")
          .diffraction;
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.edge_angle, 80.0f);
  EXPECT_EQ(d.frequency, 250.0f);
  EXPECT_EQ(sp::diffraction_reach(d), 0.5f);
  EXPECT_EQ(d.gain, 0.25f);
}

TEST(ConfigDiffraction, BadValuesNameTheKey) {
  expect_error(R"({"diffraction": true})", {"diffraction"});
  expect_error(R"({"diffraction": {"enabled": 1}})", {"diffraction.enabled"});
  expect_error(R"({"diffraction": {"enable": true}})", {"diffraction", "enable", "enabled"});
  expect_error(R"({"diffraction": {"edge_angle": 0}})", {"diffraction.edge_angle"});
  expect_error(R"({"diffraction": {"edge_angle": 181}})", {"diffraction.edge_angle"});
  expect_error(R"({"diffraction": {"frequency": 0}})", {"diffraction.frequency"});
  expect_error(R"({"diffraction": {"reach": -1}})", {"diffraction.reach"});
  expect_error(R"({"diffraction": {"gain": 1.5}})", {"diffraction.gain"});
}
