// The config's `diffraction` object (contract key `enabled`; the others are
// ours, documented in README.md "Configuration" and docs/model.md#diffraction)
// -> sp::DiffractionSettings.
#pragma once

#include <nlohmann/json.hpp>

#include "config/json_fields.h"
#include "soundpaint/config.h"

namespace sp::json_fields {

// Reads every key of `value` (an object) into `diffraction`; unknown keys,
// wrong types and out-of-range values are errors naming the key path.
void read_diffraction(const nlohmann::json& value, const JsonPath& at, DiffractionSettings& diffraction);

}  // namespace sp::json_fields
