#include "config/config_rules.h"

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace sp::config_rules {
namespace {

using json_fields::JsonPath;

bool in_range(double d, const NumberRange& range) {
  const bool above_min = range.min_open ? d > range.min : d >= range.min;
  const bool below_max = range.max_open ? d < range.max : d <= range.max;
  return std::isfinite(d) && above_min && below_max;
}

// In the JSON reader's words: "must be a number > 0, got 0", or, for a
// value JSON cannot hold (NaN, infinities), "must be a finite number > 0,
// got infinity".
void check(double value, const NumberRange& range, const JsonPath& at) {
  if (in_range(value, range)) return;
  const bool finite = std::isfinite(value);
  std::string expected = finite ? "must be a number" : "must be a finite number";
  const std::string described = range.describe();
  if (!described.empty()) expected += " " + described;
  if (finite) at.fail(expected, nlohmann::json(value));
  at.fail(expected + ", got " + (std::isnan(value) ? "NaN" : value > 0 ? "infinity" : "-infinity"));
}

void check_count(std::uint64_t value, std::uint64_t min, std::uint64_t max, const JsonPath& at) {
  if (value >= min && value <= max) return;
  at.fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]", nlohmann::json(value));
}

}  // namespace

void check_numbers(const Config& c, std::string_view origin) {
  const JsonPath top(origin);
  check(c.scan_radius, kScanRadius, top.key("scan_radius"));
  check_count(c.ray_budget, 0, kMaxRayBudget, top.key("ray_budget"));
  check_count(c.max_indicators, 1, kMaxIndicatorsLimit, top.key("max_indicators"));
  check_count(c.max_bounces, 0, kMaxBouncesLimit, top.key("max_bounces"));
  check(c.bounce_energy_loss, kBounceEnergyLoss, top.key("bounce_energy_loss"));
  check(c.max_wall_thickness, kMaxWallThickness, top.key("max_wall_thickness"));
  check(c.min_energy, kMinEnergy, top.key("min_energy"));
  check(c.air_attenuation, kAirAttenuation, top.key("air_attenuation"));
  check(c.indicator_size, kIndicatorSize, top.key("indicator_size"));
  check(c.indicator_lifetime, kIndicatorLifetime, top.key("indicator_lifetime"));
  check(c.dt, kDt, top.key("dt"));
  const JsonPath layers = top.key("layers");
  for (const auto& [name, layer] : c.layers) {
    const JsonPath at = layers.key(name);
    check(layer.reflect_probability, kReflectProbability, at.key("reflect_probability"));
    check(layer.attenuation, kAttenuation, at.key("attenuation"));
    check(layer.sheet_thickness, kSheetThickness, at.key("sheet_thickness"));
  }
  if (c.listener_position) {
    const Vec3& p = *c.listener_position;
    for (std::size_t i = 0; i < 3; ++i)
      check(p[static_cast<int>(i)], json_fields::kAnyNumber, top.key("listener").key("position").index(i));
  }
  const JsonPath diffraction = top.key("diffraction");
  check(c.diffraction.edge_angle, kEdgeAngle, diffraction.key("edge_angle"));
  check(c.diffraction.frequency, kFrequency, diffraction.key("frequency"));
  if (c.diffraction.reach) check(*c.diffraction.reach, kReach, diffraction.key("reach"));
  check(c.diffraction.gain, kDiffractionGain, diffraction.key("gain"));
  const JsonPath cues = top.key("cues");
  check(c.cues.guide_share, kGuideShare, cues.key("guide_share"));
  check(c.cues.toward_angle, kTowardAngle, cues.key("toward_angle"));
}

}  // namespace sp::config_rules
