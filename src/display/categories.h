// Categories of sound, numbered, with their shape and palette colour: a
// source's own colour wins, else its category's colour in the display
// palette (docs/accessibility.md, "Colour").
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/vec3.hpp>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "soundpaint/display.h"

namespace sp {

// How many categories builtin_categories() lists: they own palette entries
// 0 .. kBuiltinCategoryCount - 1, in that order.
inline constexpr std::uint32_t kBuiltinCategoryCount = 8;

// Numbers category names: the built-ins first (index = position in
// builtin_categories()), then other names in order of first appearance.
// Names match exactly (case and spaces count). Not thread-safe: index_of
// adds names; a const table may be read from any thread.
class CategoryTable {
 public:
  CategoryTable();

  // The name's index, adding the name if it is new. Hashed: numbering n
  // names costs O(n), as a world of thousands of categories needs.
  std::uint32_t index_of(std::string_view name);

  // Precondition: index < size().
  const std::string& name(std::uint32_t index) const { return names_.at(index); }
  std::uint32_t size() const { return static_cast<std::uint32_t>(names_.size()); }

  // The shape `overrides` (the config's display.shapes) gives the name, else
  // the built-in's shape, else Shape::Disc. Precondition: index < size().
  Shape shape_of(std::uint32_t index, const std::map<std::string, Shape>& overrides) const;

 private:
  // Looks a std::string_view up without building a std::string.
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view name) const noexcept { return std::hash<std::string_view>{}(name); }
  };

  std::vector<std::string> names_;
  std::unordered_map<std::string, std::uint32_t, NameHash, std::equal_to<>> indices_;  // name -> index in names_
};

// The palette entry of the category with this index, in a palette of
// palette_size entries (> kBuiltinCategoryCount): a built-in's own entry;
// other categories take the entries after the built-ins' in order of first
// appearance, then cycle over the whole palette.
std::uint32_t palette_entry_of(std::uint32_t category_index, std::size_t palette_size);

// The linear RGB colour of the category with this index in `palette`.
glm::vec3 category_color(std::uint32_t category_index, Palette palette);

}  // namespace sp
