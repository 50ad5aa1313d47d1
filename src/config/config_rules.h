// The accepted range of every number in a Config: one table, read by the
// JSON reader (config_parser.cpp and the *_json.cpp readers name these
// ranges) and checked once more on a Config made in code (make_world,
// create_*_simulator, the C API), so that a host filling a Config by hand
// gets the error a config file with the same value gets.
#pragma once

#include <string_view>

#include "config/json_fields.h"
#include "soundpaint/config.h"

namespace sp::config_rules {

using json_fields::NumberRange;

inline constexpr NumberRange kNonNegative = json_fields::kNonNegative;
inline constexpr NumberRange kPositive = json_fields::kPositive;
inline constexpr NumberRange kUnitInterval = json_fields::kUnitInterval;
// An angle of 0 degrees would be no turn (an edge) or no lobe (a cue).
inline constexpr NumberRange kAngle{0.0, 180.0, true, false};

inline constexpr NumberRange kScanRadius = kNonNegative;
inline constexpr NumberRange kBounceEnergyLoss = kUnitInterval;
inline constexpr NumberRange kMaxWallThickness = kPositive;
inline constexpr NumberRange kMinEnergy = kNonNegative;
inline constexpr NumberRange kAirAttenuation = kNonNegative;
inline constexpr NumberRange kIndicatorSize = kNonNegative;
inline constexpr NumberRange kIndicatorLifetime = kPositive;
inline constexpr NumberRange kDt = kPositive;
inline constexpr NumberRange kReflectProbability = kUnitInterval;
inline constexpr NumberRange kAttenuation = kNonNegative;
inline constexpr NumberRange kSheetThickness = kNonNegative;
inline constexpr NumberRange kEdgeAngle = kAngle;
inline constexpr NumberRange kFrequency = kPositive;
inline constexpr NumberRange kReach = kPositive;
inline constexpr NumberRange kDiffractionGain = kUnitInterval;
inline constexpr NumberRange kGuideShare = kUnitInterval;
inline constexpr NumberRange kTowardAngle = kAngle;

// Checks every number of `config` above (and the counts against their
// limits, listener.position for finiteness) as the JSON reader would have;
// throws sp::Exception(InvalidConfig) naming the key path, in the reader's
// words: `<origin>: key "diffraction.frequency": must be a number > 0, got 0`.
void check_numbers(const Config& config, std::string_view origin = "config");

}  // namespace sp::config_rules
