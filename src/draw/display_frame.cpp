#include "draw/display_frame.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
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
  // The camera's frame in world space: columns of the inverse view; it
  // looks along its -Z.
  const glm::mat4 camera = glm::inverse(view);
  v.heading = view_heading(-glm::vec3(camera[2]), glm::vec3(camera[1]));
  return v;
}

glm::vec2 view_heading(glm::vec3 forward, glm::vec3 up) {
  // Below this, forward's projection is rounding noise: the camera looks
  // straight up or down (a float's error in a unit vector is ~1e-7).
  constexpr float kVertical = 1.0e-5f;
  const glm::vec2 ahead(forward.x, forward.z);
  if (glm::length(ahead) > kVertical) return glm::normalize(ahead);
  // Pitched by p from heading h with no roll, up is (-sin(p) h, cos(p)):
  // it leans back when looking up, forward when looking down.
  const glm::vec2 lean = (forward.y > 0.0f ? -1.0f : 1.0f) * glm::vec2(up.x, up.z);
  if (glm::length(lean) > kVertical) return glm::normalize(lean);
  return {0.0f, -1.0f};
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
