// The config's `cues` object (our keys, documented in README.md
// "Configuration" and docs/model.md#cues-for-the-player) -> sp::CueSettings.
#pragma once

#include <nlohmann/json.hpp>

#include "config/json_fields.h"
#include "soundpaint/config.h"

namespace sp::json_fields {

// Reads every key of `value` (an object) into `cues`; unknown keys, wrong
// types and out-of-range values are errors naming the key path.
void read_cues(const nlohmann::json& value, const JsonPath& at, CueSettings& cues);

}  // namespace sp::json_fields
