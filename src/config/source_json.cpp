#include "config/source_json.h"

#include <array>
#include <string>
#include <string_view>

namespace sp::json_fields {

void read_source(const nlohmann::json& value, const JsonPath& at, SourcePosition position, SourceDesc& source) {
  static constexpr std::array<std::string_view, 9> kWithPosition = {
      "name", "position", "color", "category", "max_distance", "loudness", "duration", "interval", "phase"};
  // The same keys without "position", for sources placed by a scene node.
  static constexpr std::array<std::string_view, 8> kWithoutPosition = {
      "name", "color", "category", "max_distance", "loudness", "duration", "interval", "phase"};
  const auto& object = position == SourcePosition::Required ? expect_object(value, at, kWithPosition)
                                                            : expect_object(value, at, kWithoutPosition);
  if (position == SourcePosition::Required && !object.contains("position")) {
    at.fail("missing required key \"position\" ([x, y, z] in metres)");
  }

  for (const auto& [key, field] : object) {
    const JsonPath field_at = at.key(key);
    if (key == "name") {
      source.name = read_string(field, field_at);
    } else if (key == "position") {
      source.position = read_vec3(field, field_at);
    } else if (key == "color") {
      source.color = read_vec3(field, field_at, kUnitInterval);
    } else if (key == "category") {
      source.category = read_string(field, field_at);
    } else if (key == "max_distance") {
      source.max_distance = read_float(field, field_at, kNonNegative);
    } else if (key == "loudness") {
      source.loudness = read_float(field, field_at, kNonNegative);
    } else if (key == "duration") {
      source.duration = read_double(field, field_at, kNonNegative);
    } else if (key == "interval") {
      source.interval = read_double(field, field_at, kPositive);
    } else if (key == "phase") {
      source.phase = read_double(field, field_at, kNonNegative);
    }
  }
}

}  // namespace sp::json_fields
