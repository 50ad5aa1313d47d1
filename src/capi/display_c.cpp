// The C API's display settings and draw options (see capi/display_c.h):
// defaults from the C++ structs' own initialisers, so that the two cannot
// drift, and every field checked before anything is applied.
#include "capi/display_c.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "capi/capi_internal.h"
#include "embed/viewport_check.h"

namespace sp::capi {
namespace {

// The public shape ids, captured before the shader header below redefines
// them, must be sp::Shape's (which display_names.cpp checks against the
// shaders').
constexpr std::array<std::uint32_t, kShapeCount> kPublicShapeIds = {
    SP_SHAPE_DISC,     SP_SHAPE_RING,   SP_SHAPE_DIAMOND, SP_SHAPE_CROSS,   SP_SHAPE_PLUS,
    SP_SHAPE_TRIANGLE, SP_SHAPE_SQUARE, SP_SHAPE_STAR,    SP_SHAPE_HEXAGON, SP_SHAPE_CLOVER};
constexpr bool public_shapes_match() {
  for (std::uint32_t id = 0; id < kShapeCount; ++id)
    if (kPublicShapeIds[id] != id) return false;
  return true;
}
static_assert(public_shapes_match(), "SP_SHAPE_* must be sp::Shape's values, in order");
static_assert(SP_PALETTE_OKABE_ITO == static_cast<int>(Palette::OkabeIto) &&
              SP_PALETTE_HIGH_CONTRAST == static_cast<int>(Palette::HighContrast) &&
              SP_PALETTE_SINGLE_HUE == static_cast<int>(Palette::SingleHue));

}  // namespace
}  // namespace sp::capi

// soundpaint.h promises that it and the shaders' header may be included
// together: their SP_SHAPE_* definitions are identical, which the compiler
// checks here (a differing redefinition is diagnosed).
#include "sp_shapes.h"

namespace sp::capi {
namespace {

// "<function>: settings-><field> <what>" as InvalidArgument.
[[noreturn]] void bad_field(const char* function, const char* structure, const std::string& field,
                            const std::string& what) {
  throw_invalid(function, std::string(structure) + "->" + field + " " + what);
}

bool flag(int value) { return value == 0 || value == 1; }

// A category name from C: non-NULL, non-empty, copied.
std::string category(const char* name, const char* function, const std::string& field) {
  if (name == nullptr) bad_field(function, "settings", field, "is NULL");
  if (name[0] == '\0') bad_field(function, "settings", field, "is empty (category names must not be)");
  return name;
}

std::string indexed(const char* array, std::uint32_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

Palette palette(const sp_palette& in, const char* function) {
  // Read as its integer: a C caller may store any int in the enum, which
  // C++ may not load as the enum type.
  std::underlying_type_t<sp_palette> raw;
  std::memcpy(&raw, &in, sizeof raw);
  switch (raw) {
    case SP_PALETTE_OKABE_ITO:
      return Palette::OkabeIto;
    case SP_PALETTE_HIGH_CONTRAST:
      return Palette::HighContrast;
    case SP_PALETTE_SINGLE_HUE:
      return Palette::SingleHue;
    default:
      break;
  }
  bad_field(function, "settings", "palette",
            "is " + std::to_string(raw) +
                ", not SP_PALETTE_OKABE_ITO, SP_PALETTE_HIGH_CONTRAST or SP_PALETTE_SINGLE_HUE");
}

}  // namespace

DisplaySettings display_settings_from(const sp_display_settings& in, const char* function) {
  const char* s = "settings";
  DisplaySettings out;
  out.palette = palette(in.palette, function);
  if (!flag(in.direction)) bad_field(function, s, "direction", "must be 0 or 1");
  if (!flag(in.outline)) bad_field(function, s, "outline", "must be 0 or 1");
  out.direction = in.direction == 1;
  out.outline = in.outline == 1;
  // Negated comparisons so that NaN fails them.
  if (!(in.size_scale > 0.0f) || !std::isfinite(in.size_scale))
    bad_field(function, s, "size_scale", "must be finite and > 0");
  if (!(in.opacity_scale >= 0.0f) || !std::isfinite(in.opacity_scale))
    bad_field(function, s, "opacity_scale", "must be finite and >= 0");
  if (!(in.min_opacity >= 0.0f && in.min_opacity <= 1.0f)) bad_field(function, s, "min_opacity", "must be in [0, 1]");
  out.size_scale = in.size_scale;
  out.opacity_scale = in.opacity_scale;
  out.min_opacity = in.min_opacity;
  if (in.max_per_category > 0) out.max_per_category = in.max_per_category;
  if (in.offscreen_arrows != -1 && !flag(in.offscreen_arrows))
    bad_field(function, s, "offscreen_arrows", "must be -1 (the front end decides), 0 or 1");
  if (in.offscreen_arrows != -1) out.offscreen_arrows = in.offscreen_arrows == 1;

  if (in.hide_category_count > 0 && in.hide_categories == nullptr)
    bad_field(function, s, "hide_categories",
              "is NULL but hide_category_count is " + std::to_string(in.hide_category_count));
  for (std::uint32_t i = 0; i < in.hide_category_count; ++i)
    out.hide_categories.push_back(category(in.hide_categories[i], function, indexed("hide_categories", i)));

  if (in.shape_count > 0 && in.shape_categories == nullptr)
    bad_field(function, s, "shape_categories", "is NULL but shape_count is " + std::to_string(in.shape_count));
  if (in.shape_count > 0 && in.shapes == nullptr)
    bad_field(function, s, "shapes", "is NULL but shape_count is " + std::to_string(in.shape_count));
  for (std::uint32_t i = 0; i < in.shape_count; ++i) {
    std::string name = category(in.shape_categories[i], function, indexed("shape_categories", i));
    if (in.shapes[i] >= kShapeCount)
      bad_field(function, s, indexed("shapes", i),
                "is " + std::to_string(in.shapes[i]) + ", not an SP_SHAPE_* (for category \"" + name + "\")");
    // Two shapes for one category is a mistake in the caller's tables, not
    // a choice: which one was meant cannot be told.
    if (out.shapes.contains(name))
      bad_field(function, s, indexed("shape_categories", i), "repeats category \"" + name + "\"");
    out.shapes.emplace(std::move(name), static_cast<Shape>(in.shapes[i]));
  }
  return out;
}

DrawOptions draw_options_from(const sp_draw_options& in, const char* function) {
  const char* o = "options";
  require_struct_size(in.struct_size, sizeof(sp_draw_options), function, o);
  DrawOptions out;
  out.area = in.area;
  if ((in.viewport_width == 0) != (in.viewport_height == 0))
    bad_field(function, o, "viewport_width", "and viewport_height must both be 0 or both > 0");
  out.viewport_width = in.viewport_width;
  out.viewport_height = in.viewport_height;
  if (in.area != nullptr) {
    const VkExtent2D extent = in.area->extent;
    if (extent.width == 0 || extent.height == 0) bad_field(function, o, "area", "is empty");
    if (in.viewport_width == 0) {
      out.viewport_width = extent.width;
      out.viewport_height = extent.height;
    } else if (in.viewport_width != extent.width || in.viewport_height != extent.height) {
      bad_field(function, o, "viewport_width",
                "x viewport_height (" + std::to_string(in.viewport_width) + " x " + std::to_string(in.viewport_height) +
                    ") must be 0 x 0 or the area's extent (" + std::to_string(extent.width) + " x " +
                    std::to_string(extent.height) + ")");
    }
  }
  out.viewport_x = in.viewport_x;
  out.viewport_y = in.viewport_y;
  if (const std::optional<embed::FieldProblem> problem = embed::viewport_problem(out))
    bad_field(function, o, problem->field, problem->what);
  if (in.scene_depth < -1) bad_field(function, o, "scene_depth", "must be -1 (none) or a registered view's index");
  out.scene_depth = in.scene_depth;
  return out;
}

}  // namespace sp::capi

extern "C" {

void sp_display_settings_init(sp_display_settings* settings) noexcept {
  if (settings == nullptr) return;
  // Cannot throw: default-constructed containers allocate nothing.
  const sp::DisplaySettings defaults;
  sp_display_settings out{};
  out.palette = static_cast<sp_palette>(defaults.palette);
  out.direction = defaults.direction ? 1 : 0;
  out.outline = defaults.outline ? 1 : 0;
  out.size_scale = defaults.size_scale;
  out.opacity_scale = defaults.opacity_scale;
  out.min_opacity = defaults.min_opacity;
  // Both optionals are empty by default (no cap; the front end decides the
  // arrows). Not read from `defaults`: GCC's -Wmaybe-uninitialized misfires
  // on an empty optional's payload in sanitizer builds. The C API test
  // compares these with sp::DisplaySettings{}, so a new default shows.
  out.max_per_category = 0;  // 0 stands for no cap
  out.offscreen_arrows = -1;
  // The default shape map and hidden list are empty (the built-ins apply).
  out.hide_categories = nullptr;
  out.hide_category_count = 0;
  out.shape_categories = nullptr;
  out.shapes = nullptr;
  out.shape_count = 0;
  *settings = out;
}

void sp_draw_options_init(sp_draw_options* options) noexcept {
  if (options == nullptr) return;
  const sp::DrawOptions defaults;
  sp_draw_options out{};
  out.struct_size = sizeof(sp_draw_options);
  out.area = defaults.area;
  out.viewport_width = defaults.viewport_width;
  out.viewport_height = defaults.viewport_height;
  out.viewport_x = defaults.viewport_x;
  out.viewport_y = defaults.viewport_y;
  out.scene_depth = defaults.scene_depth;
  *options = out;
}

}  // extern "C"
