// The config's `display` object (contract: README.md, "Cues a player can read";
// docs/accessibility.md, section 4) -> sp::DisplaySettings.
#pragma once

#include <nlohmann/json.hpp>

#include "config/json_fields.h"
#include "soundpaint/display.h"

namespace sp::json_fields {

// Reads every key of `value` (an object) into `display`; unknown keys, wrong
// types and out-of-range values are errors naming the key path.
void read_display(const nlohmann::json& value, const JsonPath& at, DisplaySettings& display);

}  // namespace sp::json_fields
