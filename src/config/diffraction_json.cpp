#include "config/diffraction_json.h"

#include <array>
#include <string_view>

namespace sp::json_fields {
namespace {

constexpr std::array<std::string_view, 5> kDiffractionKeys = {"enabled", "edge_angle", "frequency", "reach", "gain"};
// A turn of 0 degrees is a flat surface, which nothing bends round.
constexpr NumberRange kEdgeAngle{0.0, 180.0, true, false};

}  // namespace

void read_diffraction(const nlohmann::json& value, const JsonPath& at, DiffractionSettings& diffraction) {
  for (const auto& [key, field] : expect_object(value, at, kDiffractionKeys)) {
    const JsonPath field_at = at.key(key);
    if (key == "enabled") {
      diffraction.enabled = read_bool(field, field_at);
    } else if (key == "edge_angle") {
      diffraction.edge_angle = read_float(field, field_at, kEdgeAngle);
    } else if (key == "frequency") {
      diffraction.frequency = read_float(field, field_at, kPositive);
    } else if (key == "reach") {
      diffraction.reach = read_float(field, field_at, kPositive);
    } else if (key == "gain") {
      diffraction.gain = read_float(field, field_at, kUnitInterval);
    }
  }
}

}  // namespace sp::json_fields
