// Reading a sound source (contract: README.md, "Configuration (JSON)",
// `sources`; docs/model.md#registry) from JSON. Shared by the config's
// "sources" array and, if it wishes, the scene loader's `extras.sound_source`.
#pragma once

#include <nlohmann/json.hpp>

#include "config/json_fields.h"
#include "soundpaint/config.h"

namespace sp::json_fields {

enum class SourcePosition {
  Required,  // "position": [x, y, z] must be present (config sources)
  FromNode,  // the position comes from elsewhere; a "position" key is an error
};

// Reads a source object into `source`, keeping its current values for absent
// keys. Accepted keys: name, position, color, category, max_distance,
// loudness, duration, interval, phase. Throws InvalidConfig naming the key.
void read_source(const nlohmann::json& value, const JsonPath& at, SourcePosition position, SourceDesc& source);

}  // namespace sp::json_fields
