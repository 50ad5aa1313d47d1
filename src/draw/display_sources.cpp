#include "core/glm_interop.h"
#include "draw/display_sources.h"

#include <string>
#include <string_view>
#include <unordered_set>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "display/categories.h"
#include "sim/world_geometry.h"
#include "sp_draw_types.h"
#include "soundpaint/result.h"
#include "sp_types.h"

namespace sp::draw {

// Every list is hashed or numbered once, and each source then costs O(1):
// a frame costs O(hide_categories + categories + sources), not their
// product. (Issue 38: 1e6 hidden names over 10,000 sources, searched per
// source, took 35 s a frame; the lists are bounded too, display.h.)
std::vector<shader::DisplaySource> make_display_sources(const World& world, const DisplaySettings& settings) {
  // The world's categories, numbered as its sources know them.
  CategoryTable categories;
  for (const std::string& name : world.category_names) (void)categories.index_of(name);
  const std::unordered_set<std::string_view> hidden(settings.hide_categories.begin(), settings.hide_categories.end());
  // Each category's shape, and whether it is hidden, worked out once for all its sources.
  std::vector<std::uint32_t> category_flags(categories.size());
  for (std::uint32_t category = 0; category < categories.size(); ++category) {
    category_flags[category] = static_cast<std::uint32_t>(categories.shape_of(category, settings.shapes));
    if (hidden.contains(categories.name(category))) category_flags[category] |= SP_SOURCE_HIDDEN;
  }
  std::vector<shader::DisplaySource> table(world.sources.size());
  for (std::size_t id = 0; id < world.sources.size(); ++id) {
    const std::uint32_t category = id < world.source_categories.size() ? world.source_categories[id] : 0u;
    shader::DisplaySource& entry = table[id];
    entry.position = world.sources[id].position;
    entry.category = category;
    entry.color = id < world.source_colors.size() ? to_glm(world.source_colors[id]) : glm::vec3(1.0f);
    if (category < categories.size()) {
      entry.shape_flags = category_flags[category];
    } else {
      // A category the world has not numbered: the last one's shape, hidden by the source's own name.
      entry.shape_flags = static_cast<std::uint32_t>(categories.shape_of(categories.size() - 1, settings.shapes));
      if (hidden.contains(world.sources[id].category)) entry.shape_flags |= SP_SOURCE_HIDDEN;
    }
    if (id < world.source_active.size() && world.source_active[id]) entry.shape_flags |= SP_SOURCE_PRESENT;
  }
  return table;
}

std::vector<std::uint32_t> make_source_cues(const World& world) {
  std::vector<std::uint32_t> cues(world.sources.size(), 0u);
  const Bvh& bvh = world.geometry->bvh;
  if (bvh.nodes.empty()) return cues;
  const glm::vec3 listener = to_glm(world.listener);
  for (std::size_t id = 0; id < world.sources.size(); ++id) {
    if (id >= world.source_active.size() || !world.source_active[id]) continue;
    const glm::vec3 to = to_glm(world.sources[id].position) - listener;
    const float distance = glm::length(to);
    // A source standing on a surface is not hidden by it: the cast stops a
    // centimetre short.
    const float reach = distance - 0.01f;
    if (!(reach > 0.0f)) continue;
    const HitInfo hit = closest_hit(bvh, listener, to / distance, 0.0f, reach);
    if (hit.triangle != SP_INVALID || hit.cut_short != 0u) cues[id] |= SP_SOURCE_CUE_OCCLUDED;
  }
  return cues;
}

}  // namespace sp::draw
