// JSON configuration (contract: README.md, "Configuration (JSON)") ->
// sp::Config, with strict validation: unknown keys, wrong types, non-finite
// numbers and out-of-range values are errors whose one-line message names the
// origin and the key path.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/build_features.h"
#include "config/config_rules.h"
#include "config/cues_json.h"
#include "config/diffraction_json.h"
#include "config/signal_json.h"
#include "config/display_json.h"
#include "config/json_fields.h"
#include "config/layer_names.h"
#include "config/source_json.h"
#include "core/regular_file.h"
#include "soundpaint/config.h"

namespace sp {
namespace {

using nlohmann::json;
using namespace json_fields;

// One top-level key: its name and how it is read into the Config.
struct KeyReader {
  std::string_view name;
  void (*read)(const json& value, const JsonPath& at, Config& config);
};

// A layer entry as written: either field may be omitted.
struct LayerEntry {
  std::optional<float> reflect_probability;
  std::optional<float> attenuation;
  std::optional<float> sheet_thickness;

  LayerProperties over(const LayerProperties& base) const {
    return {reflect_probability.value_or(base.reflect_probability), attenuation.value_or(base.attenuation),
            sheet_thickness.value_or(base.sheet_thickness)};
  }
};

LayerEntry read_layer_entry(const json& value, const JsonPath& at) {
  const auto& object = expect_object(value, at, {"reflect_probability", "attenuation", "sheet_thickness"});
  LayerEntry entry;
  if (const auto it = object.find("reflect_probability"); it != object.end()) {
    entry.reflect_probability =
        read_float(it->second, at.key("reflect_probability"), config_rules::kReflectProbability);
  }
  if (const auto it = object.find("attenuation"); it != object.end()) {
    entry.attenuation = read_float(it->second, at.key("attenuation"), config_rules::kAttenuation);
  }
  if (const auto it = object.find("sheet_thickness"); it != object.end()) {
    entry.sheet_thickness = read_float(it->second, at.key("sheet_thickness"), config_rules::kSheetThickness);
  }
  return entry;
}

// Stores every entry with both fields filled in. An omitted field is taken
// from what the layer would resolve to without its entry: the preset of that
// name if there is one, else the config's "default" entry, else the "default"
// preset. So {"default": {...}, "curtain": {"attenuation": 1}} gives the
// curtain the configured default's reflect_probability, as an unlisted layer
// would get.
void read_layers(const json& value, const JsonPath& at, Config& config) {
  const auto& object = expect_any_object(value, at);
  std::vector<std::pair<std::string, LayerEntry>> others;
  for (const auto& [name, entry_json] : object) {
    if (name.empty()) at.fail("layer names must not be empty");
    const LayerEntry entry = read_layer_entry(entry_json, at.key(name));
    if (layer_names::normalise(name) == "default") {
      config.layers[name] = entry.over(layer_presets().at("default"));
    } else {
      others.emplace_back(name, entry);
    }
  }
  // Only the "default" entries are in config.layers yet, so resolve_layer()
  // yields exactly the fallback described above.
  for (const auto& [name, entry] : others) config.layers[name] = entry.over(resolve_layer(config, name));
}

void read_listener(const json& value, const JsonPath& at, Config& config) {
  const auto& object = expect_object(value, at, {"position"});
  const auto it = object.find("position");
  if (it == object.end()) at.fail("missing required key \"position\" ([x, y, z] in metres)");
  config.listener_position = read_vec3(it->second, at.key("position"));
}

void read_sources(const json& value, const JsonPath& at, Config& config) {
  if (!value.is_array()) at.fail("must be an array of source objects", value);
  config.sources.clear();
  config.sources.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) {
    SourceDesc source;
    read_source(value[i], at.index(i), SourcePosition::Required, source);
    config.sources.push_back(std::move(source));
  }
}

BudgetWeighting read_budget_weighting(const json& value, const JsonPath& at) {
  if (value.is_string()) {
    const auto& text = value.get_ref<const std::string&>();
    if (text == "even") return BudgetWeighting::Even;
    if (text == "proximity") return BudgetWeighting::Proximity;
  }
  at.fail(R"(must be "even" or "proximity")", value);
}

CpuTraversal read_cpu_traversal(const json& value, const JsonPath& at) {
  if (value.is_string()) {
    const auto& text = value.get_ref<const std::string&>();
    if (text == "soundpaint") return CpuTraversal::Soundpaint;
    if (text == "embree") {
      if (!embree_available())
        at.fail(std::string(R"("embree" )") + kEmbreeBuildHint + R"(; this build has only "soundpaint")", value);
      return CpuTraversal::Embree;
    }
  }
  at.fail(R"(must be "soundpaint" or "embree")", value);
}

constexpr KeyReader kKeyReaders[] = {
    {"scan_radius", [](const json& v, const JsonPath& at,
                       Config& c) { c.scan_radius = read_float(v, at, config_rules::kScanRadius); }},
    {"ray_budget",
     [](const json& v, const JsonPath& at, Config& c) { c.ray_budget = read_uint32(v, at, 0, kMaxRayBudget); }},
    {"max_indicators", [](const json& v, const JsonPath& at,
                          Config& c) { c.max_indicators = read_uint32(v, at, 1, kMaxIndicatorsLimit); }},
    {"budget_weighting",
     [](const json& v, const JsonPath& at, Config& c) { c.budget_weighting = read_budget_weighting(v, at); }},
    {"cpu_traversal",
     [](const json& v, const JsonPath& at, Config& c) { c.cpu_traversal = read_cpu_traversal(v, at); }},
    {"max_bounces",
     [](const json& v, const JsonPath& at, Config& c) { c.max_bounces = read_uint32(v, at, 0, kMaxBouncesLimit); }},
    {"bounce_energy_loss",
     [](const json& v, const JsonPath& at, Config& c) {
       c.bounce_energy_loss = read_float(v, at, config_rules::kBounceEnergyLoss);
     }},
    {"max_wall_thickness",
     [](const json& v, const JsonPath& at, Config& c) {
       c.max_wall_thickness = read_float(v, at, config_rules::kMaxWallThickness);
     }},
    {"min_energy",
     [](const json& v, const JsonPath& at, Config& c) { c.min_energy = read_float(v, at, config_rules::kMinEnergy); }},
    {"air_attenuation", [](const json& v, const JsonPath& at,
                           Config& c) { c.air_attenuation = read_float(v, at, config_rules::kAirAttenuation); }},
    {"indicator_size", [](const json& v, const JsonPath& at,
                          Config& c) { c.indicator_size = read_float(v, at, config_rules::kIndicatorSize); }},
    {"indicator_lifetime",
     [](const json& v, const JsonPath& at, Config& c) {
       c.indicator_lifetime = read_float(v, at, config_rules::kIndicatorLifetime);
     }},
    {"dt", [](const json& v, const JsonPath& at, Config& c) { c.dt = read_double(v, at, config_rules::kDt); }},
    {"seed", [](const json& v, const JsonPath& at, Config& c) { c.seed = read_uint32(v, at); }},
    {"layers", read_layers},
    {"listener", read_listener},
    {"sources", read_sources},
    {"display", [](const json& v, const JsonPath& at, Config& c) { read_display(v, at, c.display); }},
    {"diffraction", [](const json& v, const JsonPath& at, Config& c) { read_diffraction(v, at, c.diffraction); }},
    {"cues", [](const json& v, const JsonPath& at, Config& c) { read_cues(v, at, c.cues); }},
    {"signal", [](const json& v, const JsonPath& at, Config& c) { read_signal(v, at, c.signal); }},
};

Config read_config(const json& root, std::string_view origin) {
  const JsonPath top(origin);
  const auto& object = expect_any_object(root, top);
  Config config;
  for (const auto& [key, value] : object) {
    const KeyReader* reader = nullptr;
    for (const KeyReader& candidate : kKeyReaders) {
      if (candidate.name == key) reader = &candidate;
    }
    if (reader == nullptr) {
      std::vector<std::string_view> known;
      for (const KeyReader& candidate : kKeyReaders) known.push_back(candidate.name);
      fail_unknown_key(top, key, known);
    }
    reader->read(value, top.key(key), config);
  }
  return config;
}

[[noreturn]] void fail_io(const std::string& origin, const std::string& what) {
  throw Exception(ErrorCode::Io, origin + ": " + what);
}

// Configs are hand-written settings: a few kilobytes, a few megabytes with
// thousands of sources. The cap refuses a huge file before reading it.
constexpr std::uint64_t kMaxConfigFileBytes = 64ull << 20;

std::string read_text_file(const std::filesystem::path& path, const std::string& origin) {
  try {
    const std::vector<unsigned char> bytes = read_regular_file(path, kMaxConfigFileBytes, ErrorCode::Io);
    return std::string(bytes.begin(), bytes.end());
  } catch (const Exception& e) {
    fail_io(origin, "cannot read config file: " + e.error().message);
  }
}

}  // namespace

Result<Config> parse_config(std::string_view json_text, std::string_view origin) {
  return capture_errors([&] { return read_config(parse_strict(json_text, origin), origin); }, ErrorCode::InvalidConfig);
}

Result<Config> load_config(const std::filesystem::path& path) {
  const std::string origin = path.string();
  return capture_errors([&] { return read_config(parse_strict(read_text_file(path, origin), origin), origin); },
                        ErrorCode::InvalidConfig);
}

}  // namespace sp
