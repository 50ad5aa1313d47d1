#include "core/glm_interop.h"
#include "draw/display_sources.h"

#include <algorithm>
#include <string>

#include <glm/glm.hpp>

#include "display/categories.h"
#include "soundpaint/result.h"
#include "sp_types.h"

namespace sp::draw {

std::vector<shader::DisplaySource> make_display_sources(const World& world, const DisplaySettings& settings) {
  // The world's categories, numbered as its sources know them.
  CategoryTable categories;
  for (const std::string& name : world.category_names) (void)categories.index_of(name);
  std::vector<shader::DisplaySource> table(world.sources.size());
  for (std::size_t id = 0; id < world.sources.size(); ++id) {
    const std::uint32_t category = id < world.source_categories.size() ? world.source_categories[id] : 0u;
    shader::DisplaySource& entry = table[id];
    entry.position = world.sources[id].position;
    entry.category = category;
    entry.color = id < world.source_colors.size() ? to_glm(world.source_colors[id]) : glm::vec3(1.0f);
    const std::string& name = category < categories.size() ? categories.name(category) : world.sources[id].category;
    entry.shape_flags =
        static_cast<std::uint32_t>(categories.shape_of(std::min(category, categories.size() - 1), settings.shapes));
    const bool hidden = std::find(settings.hide_categories.begin(), settings.hide_categories.end(), name) !=
                        settings.hide_categories.end();
    if (hidden) entry.shape_flags |= SP_SOURCE_HIDDEN;
    if (id < world.source_active.size() && world.source_active[id]) entry.shape_flags |= SP_SOURCE_PRESENT;
  }
  return table;
}

}  // namespace sp::draw
