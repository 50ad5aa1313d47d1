#include "config/cues_json.h"

#include "config/config_rules.h"

#include <array>
#include <string_view>

namespace sp::json_fields {
namespace {

constexpr std::array<std::string_view, 3> kCueKeys = {"listen", "guide_share", "toward_angle"};

}  // namespace

void read_cues(const nlohmann::json& value, const JsonPath& at, CueSettings& cues) {
  for (const auto& [key, field] : expect_object(value, at, kCueKeys)) {
    const JsonPath field_at = at.key(key);
    if (key == "listen") {
      cues.listen = read_bool(field, field_at);
    } else if (key == "guide_share") {
      cues.guide_share = read_float(field, field_at, config_rules::kGuideShare);
    } else if (key == "toward_angle") {
      cues.toward_angle = read_float(field, field_at, config_rules::kTowardAngle);
    }
  }
}

}  // namespace sp::json_fields
