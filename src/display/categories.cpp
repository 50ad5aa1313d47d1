// The built-in categories and the numbering of the others.
#include "display/categories.h"

#include <array>

#include <glm/glm.hpp>

#include "display/palette.h"

namespace sp {
namespace {

// Shapes carry meaning where they can (a voice is a ring like a speech
// bubble, an explosion a burst, an alarm the warning triangle, a door its
// frame, machinery a nut, music a clover of notes, gunfire the crosshair's
// x, footsteps a narrow diamond like a footprint). Of the pairs most alike
// once small and turned, the cross's twin (the plus) is left unassigned,
// and the others are split between sounds a player would not mistake for
// each other: ring (voice) and disc (every other category), square (door)
// and hexagon (machinery).
constexpr std::array<BuiltinCategory, kBuiltinCategoryCount> kBuiltins = {{
    {"footsteps", Shape::Diamond, 0},
    {"gunfire", Shape::Cross, 1},
    {"voice", Shape::Ring, 2},
    {"explosion", Shape::Star, 3},
    {"alarm", Shape::Triangle, 4},
    {"music", Shape::Clover, 5},
    {"machinery", Shape::Hexagon, 6},
    {"door", Shape::Square, 7},
}};

// The palettes list their entries in the built-ins' order (src/display/palette.cpp).
constexpr bool entries_follow_order() {
  for (std::uint32_t i = 0; i < kBuiltins.size(); ++i)
    if (kBuiltins[i].palette_entry != i) return false;
  return true;
}
static_assert(entries_follow_order());

}  // namespace

std::span<const BuiltinCategory> builtin_categories() { return kBuiltins; }

CategoryTable::CategoryTable() {
  for (const BuiltinCategory& builtin : kBuiltins) (void)index_of(builtin.name);
}

std::uint32_t CategoryTable::index_of(std::string_view name) {
  if (const auto found = indices_.find(name); found != indices_.end()) return found->second;
  names_.emplace_back(name);
  indices_.emplace(names_.back(), size() - 1);
  return size() - 1;
}

Shape CategoryTable::shape_of(std::uint32_t index, const std::map<std::string, Shape>& overrides) const {
  const std::string& category = name(index);
  if (const auto chosen = overrides.find(category); chosen != overrides.end()) return chosen->second;
  return index < kBuiltinCategoryCount ? kBuiltins[index].shape : Shape::Disc;
}

std::uint32_t palette_entry_of(std::uint32_t category_index, std::size_t palette_size) {
  if (category_index < kBuiltinCategoryCount) return kBuiltins[category_index].palette_entry;
  // The n-th other category (n from 0) takes entry kBuiltinCategoryCount + n,
  // and past the palette's end wraps to entry 0, 1, ...: since the built-ins
  // own entries 0..7, that is category_index modulo the palette's size.
  return static_cast<std::uint32_t>(category_index % palette_size);
}

glm::vec3 category_color(std::uint32_t category_index, Palette palette) {
  const std::span<const glm::vec3> colors = palette_colors(palette);
  return colors[palette_entry_of(category_index, colors.size())];
}

}  // namespace sp
