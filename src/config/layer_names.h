// Layer-name normalisation shared by the config parser and resolve_layer().
#pragma once

#include <string>
#include <string_view>

#include "soundpaint/config.h"

namespace sp::layer_names {

// ASCII-lowercases `name` and removes one trailing Blender duplicate suffix,
// a dot followed by digits only: "Wood.001" -> "wood", "Glass.v2" -> "glass.v2".
std::string normalise(std::string_view name);

// The built-in preset whose name equals normalise(name), or nullptr.
const LayerProperties* find_preset(std::string_view name);

}  // namespace sp::layer_names
