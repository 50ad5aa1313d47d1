#include "display/display_checks.h"

#include <cmath>
#include <string>

#include "soundpaint/result.h"

namespace sp {

void check_display_settings(const DisplaySettings& settings) {
  auto fail = [](const std::string& key, const std::string& what) {
    throw Exception(ErrorCode::InvalidConfig, "display." + key + " " + what);
  };
  if (!(settings.size_scale > 0.0f) || !std::isfinite(settings.size_scale))
    fail("size_scale", "must be finite and > 0");
  if (!(settings.opacity_scale >= 0.0f) || !std::isfinite(settings.opacity_scale))
    fail("opacity_scale", "must be finite and >= 0");
  if (!(settings.min_opacity >= 0.0f && settings.min_opacity <= 1.0f)) fail("min_opacity", "must be in [0, 1]");
  if (static_cast<unsigned>(settings.palette) > static_cast<unsigned>(Palette::SingleHue))
    fail("palette", "is not a palette");
  // The lists' lengths first, before a name is read (kMaxDisplayCategories).
  const std::string at_most = "at most " + std::to_string(kMaxDisplayCategories);
  if (settings.hide_categories.size() > kMaxDisplayCategories)
    fail("hide_categories", "has " + std::to_string(settings.hide_categories.size()) + " entries, " + at_most);
  if (settings.shapes.size() > kMaxDisplayCategories)
    fail("shapes", "has " + std::to_string(settings.shapes.size()) + " entries, " + at_most);
  const std::string name_limit = "at most " + std::to_string(kMaxCategoryNameBytes);
  for (std::size_t i = 0; i < settings.hide_categories.size(); ++i)
    if (settings.hide_categories[i].size() > kMaxCategoryNameBytes)
      fail("hide_categories[" + std::to_string(i) + "]",
           "is " + std::to_string(settings.hide_categories[i].size()) + " bytes long, " + name_limit);
  for (const auto& [category, shape] : settings.shapes) {
    // A name this long is not printed: the message stays one short line.
    if (category.size() > kMaxCategoryNameBytes)
      fail("shapes", "has a category name " + std::to_string(category.size()) + " bytes long, " + name_limit);
    if (static_cast<std::uint32_t>(shape) >= kShapeCount) fail("shapes." + category, "is not a shape");
  }
}

}  // namespace sp
