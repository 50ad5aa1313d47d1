#include "embed/visualizer_base.h"

#include <cmath>

#include <glm/matrix.hpp>

#include "core/invalid_argument.h"
#include "core/finite.h"
#include "draw/display_sources.h"
#include "embed/viewport_check.h"
#include "sp_types.h"

namespace sp::embed {
namespace {}  // namespace

VisualizerBase::VisualizerBase(std::unique_ptr<vk::Context> context, const DrawTarget& target, World world,
                               const VisualizerSettings& settings, bool simulation_on_graphics_queue)
    : context_(std::move(context)),
      scene_(std::move(world)),
      clock_(scene_.world().config.dt, settings.max_steps_per_frame),
      simulation_on_graphics_queue_(simulation_on_graphics_queue),
      pass_(*context_, target, scene_.source_capacity()) {}

Result<bool> VisualizerBase::check_simulation_args(VkCommandBuffer cmd, double dt) const {
  if (cmd == VK_NULL_HANDLE) return invalid_argument_error("record_simulation: the command buffer is VK_NULL_HANDLE");
  if (!(dt >= 0.0) || !std::isfinite(dt))
    return invalid_argument_error("record_simulation: dt must be finite and >= 0");
  return true;
}

Result<bool> VisualizerBase::record_draw(VkCommandBuffer cmd, const Mat4& view, const Mat4& projection,
                                         const VkRect2D* area) {
  DrawOptions options;
  options.area = area;
  if (area != nullptr) {
    options.viewport_width = area->extent.width;
    options.viewport_height = area->extent.height;
  }
  return record_draw(cmd, view, projection, options);
}

Result<bool> VisualizerBase::record_draw(VkCommandBuffer cmd, const Mat4& view, const Mat4& projection,
                                         const DrawOptions& options) {
  if (cmd == VK_NULL_HANDLE) return invalid_argument_error("record_draw: the command buffer is VK_NULL_HANDLE");
  if (!all_finite(view) || !all_finite(projection))
    return invalid_argument_error("record_draw: view and projection must be finite");
  const VkRect2D* area = options.area;
  if (area != nullptr && (area->extent.width == 0 || area->extent.height == 0))
    return invalid_argument_error("record_draw: the area is empty");
  if (const std::optional<embed::FieldProblem> problem = embed::viewport_problem(options))
    return invalid_argument_error("record_draw: " + problem->field + " " + problem->what);
  const std::uint32_t origin_x = area != nullptr ? std::uint32_t(area->offset.x) : options.viewport_x;
  const std::uint32_t origin_y = area != nullptr ? std::uint32_t(area->offset.y) : options.viewport_y;
  if (options.scene_depth >= 0 && static_cast<std::size_t>(options.scene_depth) >= scene_depths_.size())
    return invalid_argument_error("record_draw: scene_depth " + std::to_string(options.scene_depth) +
                                  " is not a registered view (" + std::to_string(scene_depths_.size()) +
                                  " registered with set_scene_depth)");
  if (!ready_to_draw())
    return invalid_argument_error(
        "record_draw: record_simulation must be recorded (and submitted first) before the first draw");
  return capture_errors([&] {
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
    // No size given: the area's extent, when there is an area (visualizer.h).
    glm::vec2 size(static_cast<float>(options.viewport_width), static_cast<float>(options.viewport_height));
    if (area != nullptr && options.viewport_width == 0 && options.viewport_height == 0)
      size = glm::vec2(static_cast<float>(area->extent.width), static_cast<float>(area->extent.height));
    const bool sized = size.x > 0.0f && size.y > 0.0f;
    draw::DisplayFrame frame = draw::DisplayFrame::from(world, steps_run(), world.config.display, false);
    draw::DrawView draw_view = draw::DrawView::from(view, projection, sized ? size : glm::vec2(0.0f));
    draw_view.viewport_origin = glm::uvec2(origin_x, origin_y);
    const VkDescriptorSet depth =
        options.scene_depth >= 0 ? scene_depths_[std::size_t(options.scene_depth)] : VK_NULL_HANDLE;
    pass_.record(cmd, draw_view, frame, depth);
    if (sized) pass_.record_arrows(cmd, draw_view, frame);
    return true;
  });
}

Result<bool> VisualizerBase::set_display(const DisplaySettings& settings) {
  return capture_errors(
      [&] {
        scene_.set_display(settings).value();
        return true;
      },
      ErrorCode::InvalidConfig);
}

Result<bool> VisualizerBase::set_scene_depth(std::span<const VkImageView> views) {
  return capture_errors([&] {
    if (views.size() > 8) throw Exception(ErrorCode::LimitExceeded, "set_scene_depth: at most 8 views");
    for (VkImageView view : views)
      if (view == VK_NULL_HANDLE)
        throw Exception(ErrorCode::InvalidArgument, "set_scene_depth: a view is VK_NULL_HANDLE");
    pass_.scene_depths().clear();
    scene_depths_.clear();
    for (VkImageView view : views) scene_depths_.push_back(pass_.scene_depths().add(view));
    return true;
  });
}

Result<IndicatorRing> VisualizerBase::indicator_ring() {
  if (!ready_to_draw())
    return invalid_argument_error("indicator_ring: record_simulation must be recorded before the ring is read");
  const gpu::IndicatorView view = indicator_view();
  const World& world = scene_.world();
  const draw::DisplayFrame frame = draw::DisplayFrame::from(world, steps_run(), world.config.display, false);
  IndicatorRing ring;
  ring.buffer = view.ring;
  ring.capacity = view.ring_capacity;
  ring.stride = sizeof(Indicator);
  ring.size = VkDeviceSize{ring.capacity} * ring.stride;
  ring.draw_args = view.draw_args;
  ring.draw_args_offset = view.draw_args_offset;
  ring.current_step = frame.current_step;
  ring.dt = frame.dt;
  ring.lifetime = frame.lifetime;
  return ring;
}

void VisualizerBase::record_display(VkCommandBuffer cmd) {
  if (!pass_bound_) {
    pass_.bind(indicator_view());  // the ring never moves: bound once
    pass_bound_ = true;
  }
  const World& world = scene_.world();
  const std::vector<shader::DisplaySource> sources = draw::make_display_sources(world, world.config.display);
  pass_.set_source_cues(draw::make_source_cues(world));
  const draw::DisplayFrame frame = draw::DisplayFrame::from(world, steps_run(), world.config.display, false);
  pass_.record_prepare(cmd, sources, frame, simulation_on_graphics_queue_);
}

}  // namespace sp::embed
