#include "scene/scene_sources.h"

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "config/json_fields.h"
#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

using nlohmann::json;
namespace jf = json_fields;

constexpr std::string_view kEmitterExtension = "KHR_audio_emitter";

// tinygltf keeps the original text of extras/extensions on request. Reading
// it back as nlohmann::json lets the configuration's strict readers check it,
// with the same rules and messages as a config file (tinygltf::Value would
// also squeeze every integer into an int).
json parse_kept_json(const std::string& text, std::string_view origin) {
  if (text.empty()) return json();
  return jf::parse_strict(text, origin);
}

SourceDesc read_sound_source(const json& value, const jf::JsonPath& at) {
  if (value.is_object() && value.contains("position")) {
    at.key("position").fail("is not allowed: a scene source sits at its node's position");
  }
  const json::object_t& object =
      jf::expect_object(value, at, {"color", "category", "max_distance", "loudness", "duration", "interval", "phase"});
  SourceDesc source;
  for (const auto& [key, field] : object) {
    const jf::JsonPath field_at = at.key(key);
    if (key == "color") {
      source.color = jf::read_vec3(field, field_at, jf::kUnitInterval);
    } else if (key == "category") {
      source.category = jf::read_string(field, field_at);
    } else if (key == "max_distance") {
      source.max_distance = jf::read_float(field, field_at, jf::kNonNegative);
    } else if (key == "loudness") {
      source.loudness = jf::read_float(field, field_at, jf::kNonNegative);
    } else if (key == "duration") {
      source.duration = jf::read_double(field, field_at, jf::kNonNegative);
    } else if (key == "interval") {
      source.interval = jf::read_double(field, field_at, jf::kPositive);
    } else if (key == "phase") {
      source.phase = jf::read_double(field, field_at, jf::kNonNegative);
    }
  }
  return source;
}

AudioEmitter read_emitter(const json& value, const jf::JsonPath& at) {
  // KHR_audio_emitter defines more keys (sources, cone angles, distance
  // model) than a ray source uses; only the ones read are checked.
  if (!value.is_object()) at.fail("must be an object", value);
  AudioEmitter emitter;
  const jf::JsonPath type_at = at.key("type");
  if (!value.contains("type")) type_at.fail("is required (\"positional\" or \"global\")");
  const std::string type = jf::read_string(value["type"], type_at);
  if (type != "positional" && type != "global") type_at.fail("must be \"positional\" or \"global\"", value["type"]);
  emitter.positional = type == "positional";
  if (value.contains("name")) emitter.name = jf::read_string(value["name"], at.key("name"));
  if (value.contains("gain")) emitter.gain = jf::read_float(value["gain"], at.key("gain"), jf::kNonNegative);
  if (value.contains("positional")) {
    const json& positional = value["positional"];
    const jf::JsonPath positional_at = at.key("positional");
    if (!positional.is_object()) positional_at.fail("must be an object", positional);
    if (positional.contains("maxDistance")) {
      emitter.max_distance =
          jf::read_float(positional["maxDistance"], positional_at.key("maxDistance"), jf::kNonNegative);
    }
  }
  return emitter;
}

SourceDesc emitter_source(const AudioEmitter& emitter) {
  SourceDesc source;
  if (!emitter.name.empty()) source.category = emitter.name;
  if (emitter.gain) source.loudness = *emitter.gain;
  if (emitter.max_distance) source.max_distance = *emitter.max_distance;
  return source;
}

}  // namespace

std::vector<AudioEmitter> read_audio_emitters(const tinygltf::Model& model) {
  // Root-level keys have no node to name; "root" keeps messages readable.
  const std::string_view origin = "root";
  const json extensions = parse_kept_json(model.extensions_json_string, origin);
  std::vector<AudioEmitter> emitters;
  if (!extensions.is_object() || !extensions.contains(kEmitterExtension)) return emitters;
  const jf::JsonPath at = jf::JsonPath(origin, "extensions").key(kEmitterExtension);
  const json& extension = extensions[std::string(kEmitterExtension)];
  if (!extension.is_object()) at.fail("must be an object", extension);
  if (!extension.contains("emitters")) return emitters;
  const json& list = extension["emitters"];
  const jf::JsonPath list_at = at.key("emitters");
  if (!list.is_array()) list_at.fail("must be an array", list);
  for (std::size_t i = 0; i < list.size(); ++i) emitters.push_back(read_emitter(list[i], list_at.index(i)));
  return emitters;
}

NodeAcoustics read_node_acoustics(const tinygltf::Model& model, int node_index,
                                  const std::vector<AudioEmitter>& emitters) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
  const std::string label = node_label(model, node_index);
  NodeAcoustics acoustics;

  const json extras = parse_kept_json(node.extras_json_string, label);
  if (extras.is_object()) {
    const jf::JsonPath extras_at(label, "extras");
    if (extras.contains("acoustic_layer")) {
      const jf::JsonPath layer_at = extras_at.key("acoustic_layer");
      std::string layer = jf::read_string(extras["acoustic_layer"], layer_at);
      if (layer.empty()) layer_at.fail("must be a non-empty string");
      acoustics.layer = std::move(layer);
    }
    if (extras.contains("sound_source")) {
      SourceDesc source = read_sound_source(extras["sound_source"], extras_at.key("sound_source"));
      source.name = node.name;
      acoustics.sources.push_back(std::move(source));
    }
  }

  const json extensions = parse_kept_json(node.extensions_json_string, label);
  if (extensions.is_object() && extensions.contains(kEmitterExtension)) {
    const jf::JsonPath at = jf::JsonPath(label, "extensions").key(kEmitterExtension);
    const json& reference = extensions[std::string(kEmitterExtension)];
    if (!reference.is_object()) at.fail("must be an object", reference);
    const jf::JsonPath emitter_at = at.key("emitter");
    if (!reference.contains("emitter")) emitter_at.fail("is required");
    if (emitters.empty()) emitter_at.fail("refers to an emitter, but the file defines none");
    const std::uint32_t index =
        jf::read_uint32(reference["emitter"], emitter_at, 0, static_cast<std::uint32_t>(emitters.size() - 1));
    // A global emitter has no position; KHR_audio_emitter attaches those to
    // scenes, so one on a node is ignored rather than guessed at.
    if (emitters[index].positional) {
      SourceDesc source = emitter_source(emitters[index]);
      source.name = node.name;
      acoustics.sources.push_back(std::move(source));
    }
  }
  return acoustics;
}

}  // namespace sp::scene_detail
