// How indicators are drawn so that a player who cannot hear reads where a
// sound is, what it is and how close: the display settings of the config's
// `display` object, the shapes and palettes they choose from, and the
// built-in categories. Display settings never change the simulation (the
// one exception: a source without its own colour takes its category's
// palette colour, which the indicators carry). docs/accessibility.md says
// which guideline each setting answers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// Shapes drawn procedurally (signed distance functions in
// shaders/shared/sp_shapes.h), one per kind of sound. The numeric values
// are the shader's SP_SHAPE_* ids.
enum class Shape : std::uint32_t {
  Disc = 0,
  Ring = 1,
  Diamond = 2,
  Cross = 3,  // a diagonal cross, x
  Plus = 4,   // an upright cross, +
  Triangle = 5,
  Square = 6,
  Star = 7,
  Hexagon = 8,
  Clover = 9,  // three small discs
};
inline constexpr std::uint32_t kShapeCount = 10;

// "disc", "ring", ...: the names the config's display.shapes uses.
const char* shape_name(Shape shape);
std::optional<Shape> shape_from_name(std::string_view name);

enum class Palette {
  OkabeIto,      // colour-blind safe (Okabe & Ito), the default
  HighContrast,  // saturated colours that stand out against dark and light levels
  SingleHue,     // one hue for every category: shapes alone tell them apart
};
const char* palette_name(Palette palette);
std::optional<Palette> palette_from_name(std::string_view name);

// A category every game has, with its shape and its entry of every palette.
// Other categories draw as discs and take the palette entries after the
// built-ins' in order of first appearance, then cycle.
struct BuiltinCategory {
  const char* name;  // "footsteps", "gunfire", ...
  Shape shape;
  std::uint32_t palette_entry;  // index into every palette (all have more entries than built-ins)
};
std::span<const BuiltinCategory> builtin_categories();

// Bounds on the display's category lists. Configs come from players
// (README "Security"), and a frame's display work grows with these lists
// and the sources together; bounded, a list that asks for too much is an
// error that names its key rather than a slow frame. Real configs hide and
// reshape a handful of categories, with names of a word or two.
//
// At most this many entries in hide_categories, and as many in shapes.
inline constexpr std::size_t kMaxDisplayCategories = 4096;
// At most this many bytes (UTF-8) in each category name either list gives.
inline constexpr std::size_t kMaxCategoryNameBytes = 256;

// The config's `display` object (contract: README.md, "Cues a player can read";
// docs/accessibility.md, section 4). Units: size_scale and opacity_scale
// multiply; min_opacity is an opacity in [0, 1]. shapes and hide_categories
// hold at most kMaxDisplayCategories entries each, of names at most
// kMaxCategoryNameBytes long: make_world, set_display and the config parser
// reject more (InvalidConfig, naming the key).
struct DisplaySettings {
  Palette palette = Palette::OkabeIto;
  std::map<std::string, Shape> shapes;            // category -> shape, over the built-in map
  bool direction = true;                          // spots elongated along the ray's direction
  bool outline = true;                            // a two-tone halo: >= 3:1 contrast on any surface
  float size_scale = 1.0f;                        // > 0
  float opacity_scale = 1.0f;                     // >= 0
  float min_opacity = 0.0f;                       // in [0, 1]: live spots are never fainter
  std::vector<std::string> hide_categories;       // not drawn (e.g. the player's own footsteps)
  std::optional<std::uint32_t> max_per_category;  // at most this many drawn per category, most energetic first
  // An arrow on a ring near the screen's edge, at its bearing, for each
  // source heard but out of view, or in view but occluded
  // (docs/accessibility.md). false hides them all. Empty: the front end
  // decides (render and the viewer: on; the embedded Visualizer: off unless
  // asked).
  std::optional<bool> offscreen_arrows;
};

}  // namespace sp

SP_CPP_API_END
