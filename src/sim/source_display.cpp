#include "sim/source_display.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "display/categories.h"
#include "display/palette.h"

namespace sp {
namespace {

// CategoryTable's numbering over the World's own list of names.
std::uint32_t category_index(World& world, const std::string& name) {
  const auto found = std::find(world.category_names.begin(), world.category_names.end(), name);
  if (found != world.category_names.end()) return static_cast<std::uint32_t>(found - world.category_names.begin());
  world.category_names.push_back(name);
  return static_cast<std::uint32_t>(world.category_names.size() - 1);
}

}  // namespace

void resolve_all_source_display(World& world) {
  const CategoryTable builtins;
  world.category_names.clear();
  for (std::uint32_t i = 0; i < builtins.size(); ++i) world.category_names.push_back(builtins.name(i));
  world.source_categories.clear();
  world.source_colors.clear();
  for (std::uint32_t id = 0; id < world.sources.size(); ++id) resolve_source_display(world, id);
}

void resolve_source_display(World& world, std::uint32_t id) {
  if (world.source_categories.size() <= id) {
    world.source_categories.resize(id + 1, 0);
    world.source_colors.resize(id + 1, glm::vec3(1.0f));
  }
  const SourceDesc& source = world.sources[id];
  const std::uint32_t category = category_index(world, source.category);
  world.source_categories[id] = category;
  world.source_colors[id] = source.color ? *source.color : Vec3(category_color(category, world.config.display.palette));
}

}  // namespace sp
