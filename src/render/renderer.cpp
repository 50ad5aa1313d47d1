#include "render/renderer.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "draw/display_sources.h"

#include "sim/indicator_convert.h"
#include "sp_types.h"
#include "vk/barriers.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::draw {

Renderer::Renderer(vk::Context& context, const World& world, const RenderSettings& settings)
    : context_(context),
      listener_(world.listener),
      target_(context, settings.width, settings.height),
      scene_(context, build_scene_mesh(world, settings.markers), RenderTarget::kColorFormat,
             RenderTarget::kDepthFormat),
      indicators_(context, DrawTarget{RenderTarget::kColorFormat, RenderTarget::kDepthFormat},
                  std::max<std::uint32_t>(kDefaultSourceCapacity, static_cast<std::uint32_t>(world.sources.size()))) {
  scene_depth_ = indicators_.scene_depths().add(target_.depth_view());
  // Timestamps are optional; this limit promises them on every graphics and
  // compute queue, so the context's queue family need not be asked.
  if (context_.properties().limits.timestampComputeAndGraphics)
    timestamps_ = vk::create_timestamp_pool(context_, kQueries, "render timestamps");
}

RgbaImage Renderer::render(const ViewCamera& camera, Simulator& simulator) {
  const World& world = simulator.world();
  // Which sources the listener cannot see, for their arrows in view.
  indicators_.set_source_cues(make_source_cues(world));
  if (auto view = gpu::indicator_view(simulator); view && view->context == &context_)
    return render(camera, *view, world, simulator.steps_run());
  // Another backend (or another device): the indicators come through the host.
  if (!host_indicators_) host_indicators_.emplace(context_);
  host_indicators_->upload(to_shader(simulator.live_indicators().value()));
  return render(camera, host_indicators_->view(), world, simulator.steps_run());
}

RgbaImage Renderer::render(const ViewCamera& camera, const gpu::IndicatorView& indicators, const World& world,
                           std::uint64_t steps_run) {
  indicators_.bind(indicators);  // the previous frame has finished: the set is free to update
  const DisplayFrame frame = DisplayFrame::from(world, steps_run, world.config.display, /*arrows_by_default=*/true);
  const std::vector<shader::DisplaySource> sources = make_display_sources(world, world.config.display);
  const DrawView view =
      DrawView::from(camera.view, camera.projection, glm::vec2(float(target_.width()), float(target_.height())));
  // One command buffer per frame, submitted and waited for: a picture is
  // read back right away, so there is nothing to overlap.
  context_.submit_and_wait([&](VkCommandBuffer cmd) {
    const VkQueryPool queries = timestamps_.get();
    if (queries != VK_NULL_HANDLE) {
      vkCmdResetQueryPool(cmd, queries, 0, kQueries);
      vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, queries, 0);
    }
    // RAW: the ring and the VkDrawIndirectCommand were written by a compute
    // step in an earlier submission; its fence told the host it finished,
    // but only a barrier makes those writes visible to this frame's vertex
    // shader and indirect-argument read. (Host-written rings need nothing: a
    // submit makes earlier host writes to coherent memory visible.)
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                           VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    indicators_.record_prepare(cmd, sources, frame);
    target_.begin(cmd, ScenePass::kClearColor);
    scene_.record(cmd, camera, listener_);
    if (queries != VK_NULL_HANDLE) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 1);
    target_.begin_overlays(cmd);
    indicators_.record(cmd, view, frame, scene_depth_);
    indicators_.record_arrows(cmd, view, frame);
    if (queries != VK_NULL_HANDLE) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 2);
    target_.end_and_copy(cmd);
    if (queries != VK_NULL_HANDLE) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries, 3);
  });
  read_timestamps();
  return target_.read();
}

void Renderer::read_timestamps() {
  if (!timestamps_) return;
  std::uint64_t ticks[kQueries] = {};
  SP_VK_CHECK(vkGetQueryPoolResults(context_.device(), timestamps_.get(), 0, kQueries, sizeof ticks, ticks,
                                    sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const double ms_per_tick = context_.properties().limits.timestampPeriod * 1e-6;
  auto between = [&](int from, int to) { return static_cast<double>(ticks[to] - ticks[from]) * ms_per_tick; };
  last_timings_ = FrameTimings{between(0, 1), between(1, 2), between(0, 3)};
}

}  // namespace sp::draw
