// The config's `signal` object (our keys, documented in README.md
// "Configuration" and docs/model.md#loudness-from-the-signal) -> sp::SignalSettings.
#pragma once

#include <nlohmann/json.hpp>

#include "config/json_fields.h"
#include "soundpaint/config.h"

namespace sp::json_fields {

// Reads every key of `value` (an object) into `signal`; unknown keys, wrong
// types, out-of-range values and a floor not below the reference are
// errors naming the key path.
void read_signal(const nlohmann::json& value, const JsonPath& at, SignalSettings& signal);

}  // namespace sp::json_fields
