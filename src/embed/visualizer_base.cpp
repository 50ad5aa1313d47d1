#include "embed/visualizer_base.h"

#include <cmath>

#include <glm/matrix.hpp>

#include "core/finite.h"

namespace sp::embed {
namespace {

Error invalid(std::string message) { return Error{ErrorCode::InvalidArgument, std::move(message), 0}; }

}  // namespace

VisualizerBase::VisualizerBase(std::unique_ptr<vk::Context> context, const DrawTarget& target, World world,
                               const VisualizerSettings& settings, bool simulation_on_graphics_queue)
    : context_(std::move(context)),
      scene_(std::move(world)),
      clock_(scene_.world().config.dt, settings.max_steps_per_frame),
      simulation_on_graphics_queue_(simulation_on_graphics_queue),
      pass_(*context_, target) {}

Result<bool> VisualizerBase::check_simulation_args(VkCommandBuffer cmd, double dt) const {
  if (cmd == VK_NULL_HANDLE) return invalid("record_simulation: the command buffer is VK_NULL_HANDLE");
  if (!(dt >= 0.0) || !std::isfinite(dt)) return invalid("record_simulation: dt must be finite and >= 0");
  return true;
}

Result<bool> VisualizerBase::record_draw(VkCommandBuffer cmd, const glm::mat4& view, const glm::mat4& projection,
                                         const VkRect2D* area) {
  if (cmd == VK_NULL_HANDLE) return invalid("record_draw: the command buffer is VK_NULL_HANDLE");
  if (!all_finite(view) || !all_finite(projection)) return invalid("record_draw: view and projection must be finite");
  if (area != nullptr && (area->extent.width == 0 || area->extent.height == 0))
    return invalid("record_draw: the area is empty");
  if (!ready_to_draw())
    return invalid("record_draw: record_simulation must be recorded (and submitted first) before the first draw");
  return capture_errors([&] {
    const gpu::IndicatorView indicators = indicator_view();
    if (!pass_bound_) {
      pass_.bind(indicators);  // the ring never moves: bound once
      pass_bound_ = true;
    }
    if (area != nullptr) {
      VkViewport viewport{};
      viewport.x = static_cast<float>(area->offset.x);
      viewport.y = static_cast<float>(area->offset.y);
      viewport.width = static_cast<float>(area->extent.width);
      viewport.height = static_cast<float>(area->extent.height);
      viewport.maxDepth = 1.0f;
      vkCmdSetViewport(cmd, 0, 1, &viewport);
      vkCmdSetScissor(cmd, 0, 1, area);
    }
    const World& world = scene_.world();
    draw::IndicatorClock clock;
    clock.current_step = steps_run() == 0 ? 0u : static_cast<std::uint32_t>(steps_run() - 1);
    clock.dt = static_cast<float>(world.config.dt);
    clock.lifetime = world.config.indicator_lifetime;
    const glm::vec3 eye(glm::inverse(view)[3]);
    pass_.record(cmd, projection * view, eye, indicators, clock);
    return true;
  });
}

}  // namespace sp::embed
