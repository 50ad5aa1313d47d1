// The names of shapes and palettes that the config's `display` object uses
// (include/soundpaint/display.h).
#include <array>
#include <cstddef>

#include "soundpaint/display.h"
#include "sp_shapes.h"

namespace sp {
namespace {

// Indexed by the enum's value: the shader's SP_SHAPE_* ids.
constexpr std::array<const char*, kShapeCount> kShapeNames = {"disc",     "ring",   "diamond", "cross",   "plus",
                                                              "triangle", "square", "star",    "hexagon", "clover"};

// Shape's values are the shader's ids: one definition checked against the other.
static_assert(kShapeCount == SP_SHAPE_COUNT);
static_assert(static_cast<std::uint32_t>(Shape::Disc) == SP_SHAPE_DISC);
static_assert(static_cast<std::uint32_t>(Shape::Ring) == SP_SHAPE_RING);
static_assert(static_cast<std::uint32_t>(Shape::Diamond) == SP_SHAPE_DIAMOND);
static_assert(static_cast<std::uint32_t>(Shape::Cross) == SP_SHAPE_CROSS);
static_assert(static_cast<std::uint32_t>(Shape::Plus) == SP_SHAPE_PLUS);
static_assert(static_cast<std::uint32_t>(Shape::Triangle) == SP_SHAPE_TRIANGLE);
static_assert(static_cast<std::uint32_t>(Shape::Square) == SP_SHAPE_SQUARE);
static_assert(static_cast<std::uint32_t>(Shape::Star) == SP_SHAPE_STAR);
static_assert(static_cast<std::uint32_t>(Shape::Hexagon) == SP_SHAPE_HEXAGON);
static_assert(static_cast<std::uint32_t>(Shape::Clover) == SP_SHAPE_CLOVER);

struct PaletteName {
  Palette palette;
  const char* name;
};
constexpr std::array<PaletteName, 3> kPaletteNames = {{
    {Palette::OkabeIto, "okabe-ito"},
    {Palette::HighContrast, "high-contrast"},
    {Palette::SingleHue, "single-hue"},
}};

}  // namespace

const char* shape_name(Shape shape) {
  const auto id = static_cast<std::size_t>(shape);
  return id < kShapeNames.size() ? kShapeNames[id] : "unknown";
}

std::optional<Shape> shape_from_name(std::string_view name) {
  for (std::uint32_t id = 0; id < kShapeCount; ++id)
    if (name == kShapeNames[id]) return Shape(id);
  return std::nullopt;
}

const char* palette_name(Palette palette) {
  for (const PaletteName& entry : kPaletteNames)
    if (entry.palette == palette) return entry.name;
  return "unknown";
}

std::optional<Palette> palette_from_name(std::string_view name) {
  for (const PaletteName& entry : kPaletteNames)
    if (name == entry.name) return entry.palette;
  return std::nullopt;
}

}  // namespace sp
