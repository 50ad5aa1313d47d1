#include "display/display_checks.h"

#include <cmath>
#include <string>

#include "soundpaint/result.h"

namespace sp {

void check_display_settings(const DisplaySettings& settings) {
  auto fail = [](const std::string& key, const char* what) {
    throw Exception(ErrorCode::InvalidConfig, "display." + key + " " + what);
  };
  if (!(settings.size_scale > 0.0f) || !std::isfinite(settings.size_scale))
    fail("size_scale", "must be finite and > 0");
  if (!(settings.opacity_scale >= 0.0f) || !std::isfinite(settings.opacity_scale))
    fail("opacity_scale", "must be finite and >= 0");
  if (!(settings.min_opacity >= 0.0f && settings.min_opacity <= 1.0f)) fail("min_opacity", "must be in [0, 1]");
  if (static_cast<unsigned>(settings.palette) > static_cast<unsigned>(Palette::SingleHue))
    fail("palette", "is not a palette");
  for (const auto& [category, shape] : settings.shapes)
    if (static_cast<std::uint32_t>(shape) >= kShapeCount) fail("shapes." + category, "is not a shape");
}

}  // namespace sp
