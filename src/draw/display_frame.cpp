#include "draw/display_frame.h"

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "sim/indicator_ring.h"

namespace sp::draw {

DrawView DrawView::from(const glm::mat4& view, const glm::mat4& projection, glm::vec2 viewport) {
  DrawView v;
  v.view_projection = projection * view;
  v.eye = glm::vec3(glm::inverse(view)[3]);
  v.viewport = viewport;
  // |.|: most Vulkan projections flip y, which makes projection[1][1] < 0.
  v.pixel_scale = std::abs(projection[1][1]) * viewport.y * 0.5f;
  v.depth_a = projection[2][2];
  v.depth_b = projection[3][2];
  return v;
}

DisplayFrame DisplayFrame::from(const World& world, std::uint64_t steps_run, const DisplaySettings& settings,
                                bool arrows_by_default) {
  DisplayFrame frame;
  // The step and lifetime with which live_indicators() decides (is_live).
  frame.current_step = shown_step(steps_run);
  frame.dt = static_cast<float>(world.config.dt);
  frame.lifetime = display_lifetime(world.config);
  frame.inv_indicator_size = inverse_indicator_size(world.config);
  frame.source_count = static_cast<std::uint32_t>(world.sources.size());
  frame.category_count = static_cast<std::uint32_t>(world.category_names.size());
  frame.settings = settings;
  frame.offscreen_arrows = settings.offscreen_arrows.value_or(arrows_by_default);
  return frame;
}

}  // namespace sp::draw
