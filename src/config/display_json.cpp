#include "config/display_json.h"

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

namespace sp::json_fields {
namespace {

constexpr std::array<std::string_view, 10> kDisplayKeys = {
    "palette",       "shapes",      "direction",       "outline",          "size_scale",
    "opacity_scale", "min_opacity", "hide_categories", "max_per_category", "offscreen_arrows"};

// The names a shape or palette may take, for messages.
std::string shape_names() {
  std::string names;
  for (std::uint32_t s = 0; s < kShapeCount; ++s) names += std::string(s ? ", " : "") + shape_name(Shape(s));
  return names;
}

Palette read_palette(const nlohmann::json& value, const JsonPath& at) {
  if (value.is_string()) {
    if (const auto palette = palette_from_name(value.get_ref<const std::string&>())) return *palette;
  }
  at.fail(R"(must be "okabe-ito", "high-contrast" or "single-hue")", value);
}

// The lists' bounds (include/soundpaint/display.h), checked before an entry
// is read: the error names the list, and a name too long to print is not
// printed.
void check_list_length(std::size_t size, const JsonPath& at, const char* entries) {
  if (size > kMaxDisplayCategories)
    at.fail("must hold at most " + std::to_string(kMaxDisplayCategories) + " " + entries + ", has " +
            std::to_string(size));
}

std::string name_limit() { return "at most " + std::to_string(kMaxCategoryNameBytes) + " bytes long"; }

std::map<std::string, Shape> read_shapes(const nlohmann::json& value, const JsonPath& at) {
  std::map<std::string, Shape> shapes;
  const auto& object = expect_any_object(value, at);
  check_list_length(object.size(), at, "categories");
  for (const auto& [category, shape] : object) {
    if (category.empty()) at.fail("category names must not be empty");
    if (category.size() > kMaxCategoryNameBytes)
      at.fail("category names must be " + name_limit() + ", one is " + std::to_string(category.size()));
    const JsonPath shape_at = at.key(category);
    const auto found = shape.is_string() ? shape_from_name(shape.get_ref<const std::string&>()) : std::nullopt;
    if (!found) shape_at.fail("must be one of " + shape_names(), shape);
    shapes[category] = *found;
  }
  return shapes;
}

std::vector<std::string> read_categories(const nlohmann::json& value, const JsonPath& at) {
  if (!value.is_array()) at.fail("must be an array of category names", value);
  check_list_length(value.size(), at, "category names");
  std::vector<std::string> categories;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const JsonPath name_at = at.index(i);
    categories.push_back(read_string(value[i], name_at));
    if (categories.back().size() > kMaxCategoryNameBytes)
      name_at.fail("must be " + name_limit() + ", is " + std::to_string(categories.back().size()));
  }
  return categories;
}

}  // namespace

void read_display(const nlohmann::json& value, const JsonPath& at, DisplaySettings& display) {
  for (const auto& [key, field] : expect_object(value, at, kDisplayKeys)) {
    const JsonPath field_at = at.key(key);
    if (key == "palette") {
      display.palette = read_palette(field, field_at);
    } else if (key == "shapes") {
      display.shapes = read_shapes(field, field_at);
    } else if (key == "direction") {
      display.direction = read_bool(field, field_at);
    } else if (key == "outline") {
      display.outline = read_bool(field, field_at);
    } else if (key == "size_scale") {
      display.size_scale = read_float(field, field_at, kPositive);
    } else if (key == "opacity_scale") {
      display.opacity_scale = read_float(field, field_at, kNonNegative);
    } else if (key == "min_opacity") {
      display.min_opacity = read_float(field, field_at, kUnitInterval);
    } else if (key == "hide_categories") {
      display.hide_categories = read_categories(field, field_at);
    } else if (key == "max_per_category") {
      display.max_per_category = read_uint32(field, field_at);
    } else if (key == "offscreen_arrows") {
      display.offscreen_arrows = read_bool(field, field_at);
    }
  }
}

}  // namespace sp::json_fields
