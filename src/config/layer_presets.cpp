// Built-in acoustic layer presets and the lookup of a layer's properties.
//
// Each preset gives rho_ref (the chance that a hit reflects rather than
// penetrates) and alpha_layer (energy lost per metre travelled inside the
// material), the paper's symbols (docs/model.md). Energies are in units of a
// source's loudness E0 = 1; rays die below min_energy (default 0.05); game
// walls are typically 0.1-0.3 m thick. The values are plausible starting points
// for games, ordered by how hard and dense the material is, not measured
// absorption data.
#include <cctype>
#include <map>
#include <string>

#include "config/layer_names.h"
#include "soundpaint/config.h"

namespace sp {
namespace layer_names {

std::string normalise(std::string_view name) {
  // Blender names duplicates "Wood.001", "Wood.002": strip one ".<digits>".
  const std::size_t dot = name.rfind('.');
  if (dot != std::string_view::npos && dot + 1 < name.size()) {
    bool digits_only = true;
    for (std::size_t i = dot + 1; i < name.size(); ++i) {
      digits_only = digits_only && std::isdigit(static_cast<unsigned char>(name[i])) != 0;
    }
    if (digits_only) name = name.substr(0, dot);
  }
  std::string lower(name);
  for (char& c : lower) {
    // ASCII only: layer names are identifiers, and locale-dependent case
    // folding would make the same scene resolve differently on two machines.
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return lower;
}

const LayerProperties* find_preset(std::string_view name) {
  const auto& presets = layer_presets();
  const auto it = presets.find(normalise(name));
  return it == presets.end() ? nullptr : &it->second;
}

}  // namespace layer_names

const std::map<std::string, LayerProperties>& layer_presets() {
  // Keys are lower case; find_preset() normalises before looking up.
  static const std::map<std::string, LayerProperties> presets = {
      // Dense, smooth and hard: reflects nearly everything. A 0.2 m wall
      // removes 0.8 E0, so only a strong ray gets through, heavily muffled.
      {"concrete", {0.9f, 4.0f}},
      // A little more porous than concrete: a 0.2 m wall removes 0.7 E0.
      {"brick", {0.85f, 3.5f}},
      // Doors and panels vibrate and pass sound on: half the hits go through,
      // and a 4 cm door removes only 0.06 E0, so footsteps behind it stay clear.
      {"wood", {0.5f, 1.5f}},
      // Hard surface that reflects well, but panes are thin: a 1 cm pane
      // removes 0.02 E0, so what does get through is barely weakened.
      {"glass", {0.7f, 2.0f}},
      // Almost total reflection (large impedance mismatch with air); the rare
      // penetrating ray loses 0.4 E0 in a 5 cm steel door.
      {"metal", {0.95f, 8.0f}},
      // Soft and porous: it rarely reflects specularly; sound that enters it
      // is absorbed quickly (a 3 cm rug removes 0.15 E0 before the floor).
      {"carpet", {0.2f, 5.0f}},
      // Unnamed layers, a generic interior wall: mostly reflective, and a
      // 0.2 m wall removes 0.4 E0, so sound through it is quieter but audible.
      // It is LayerProperties{} by construction, so the two cannot drift.
      {"default", LayerProperties{}},
  };
  return presets;
}

// Matching order, most specific first:
//   1. the config's entry of exactly this name;
//   2. a config entry whose normalised name matches the normalised layer name
//      (so a config "wood" entry also covers "Wood.001", as a preset would;
//      a user's entry must never lose to the built-in preset it overrides).
//      If several config keys normalise alike, one that is already
//      normalised ("wood") wins, else the first in key order;
//   3. the preset matched the same way;
//   4. the config's "default" entry (found by steps 1-2 for "default");
//   5. the "default" preset.
LayerProperties resolve_layer(const Config& config, std::string_view layer_name) {
  const auto find_config_entry = [&config](std::string_view name) -> const LayerProperties* {
    if (const auto exact = config.layers.find(std::string(name)); exact != config.layers.end()) {
      return &exact->second;
    }
    const std::string wanted = layer_names::normalise(name);
    if (const auto normal = config.layers.find(wanted); normal != config.layers.end()) return &normal->second;
    for (const auto& [key, properties] : config.layers) {
      if (layer_names::normalise(key) == wanted) return &properties;
    }
    return nullptr;
  };

  if (const LayerProperties* entry = find_config_entry(layer_name)) return *entry;
  if (const LayerProperties* preset = layer_names::find_preset(layer_name)) return *preset;
  if (const LayerProperties* entry = find_config_entry("default")) return *entry;
  return layer_presets().at("default");
}

}  // namespace sp
