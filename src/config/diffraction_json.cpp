#include "config/diffraction_json.h"

#include "config/config_rules.h"

#include <array>
#include <string_view>

namespace sp::json_fields {
namespace {

constexpr std::array<std::string_view, 5> kDiffractionKeys = {"enabled", "edge_angle", "frequency", "reach", "gain"};

}  // namespace

void read_diffraction(const nlohmann::json& value, const JsonPath& at, DiffractionSettings& diffraction) {
  for (const auto& [key, field] : expect_object(value, at, kDiffractionKeys)) {
    const JsonPath field_at = at.key(key);
    if (key == "enabled") {
      diffraction.enabled = read_bool(field, field_at);
    } else if (key == "edge_angle") {
      diffraction.edge_angle = read_float(field, field_at, config_rules::kEdgeAngle);
    } else if (key == "frequency") {
      diffraction.frequency = read_float(field, field_at, config_rules::kFrequency);
    } else if (key == "reach") {
      diffraction.reach = read_float(field, field_at, config_rules::kReach);
    } else if (key == "gain") {
      diffraction.gain = read_float(field, field_at, config_rules::kDiffractionGain);
    }
  }
}

}  // namespace sp::json_fields
