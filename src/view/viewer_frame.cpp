// The viewer's frames: recorded (simulation, scene, spots, panel), submitted, presented.
#include "core/glm_interop.h"
#include "view/viewer_loop.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "bvh/bvh.h"
#include "core/printable_text.h"
#include "draw/image_barrier.h"
#include "draw/rendering.h"
#include "render/scene_pass.h"
#include "soundpaint/ray_query.h"
#include "soundpaint/config.h"
#include "soundpaint/display.h"
#include "soundpaint/visualizer.h"
#include "view/config_watch.h"
#include "view/fly_camera.h"
#include "view/painting.h"
#include "view/screenshot.h"
#include "view/swapchain.h"
#include "view/ui_panel.h"
#include "view/window.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/objects.h"
#include "vk/vk_check.h"


namespace sp::view {

namespace {

// The scene pass clears and writes depth; the indicator pass then tests
// against it and samples it read-only (clipping spots to surfaces).
void begin_pass(VkCommandBuffer cmd, VkImageView color_view, VkImageView depth_view, VkExtent2D extent, bool first) {
  VkRenderingAttachmentInfo color = draw::attachment({color_view, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                                      first ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD,
                                                      VK_ATTACHMENT_STORE_OP_STORE});
  // The scene pass's clear colour is linear, as the sRGB swapchain expects.
  std::memcpy(color.clearValue.color.float32, draw::ScenePass::kClearColor, sizeof(float) * 4);
  VkRenderingAttachmentInfo depth =
      draw::attachment(first ? draw::AttachmentUse{depth_view, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                                   VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE}
                             : draw::AttachmentUse{depth_view, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL,
                                                   VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_NONE});
  depth.clearValue.depthStencil = {1.0f, 0};
  draw::begin_rendering(cmd, extent, color, depth);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
                            0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace

void Viewer::read_timestamps(std::uint32_t slot) {
  if (!submitted_[slot]) return;
  SimulationTotals totals;
  std::memcpy(&totals, totals_[slot].mapped(), sizeof totals);
  stats_.casts = totals.casts;
  stats_.rays_emitted = totals.rays_emitted;
  stats_.indicators = totals.indicators;
  stats_.live_indicators = static_cast<std::uint32_t>(totals.ring_filled);
  stats_.totals_known = true;
  if (!queries_) return;
  std::array<std::uint64_t, kQueriesPerFrame> ticks{};
  const VkResult result =
      vkGetQueryPoolResults(context_->device(), queries_.get(), slot * kQueriesPerFrame, kQueriesPerFrame,
                            sizeof(ticks), ticks.data(), sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT);
  if (result != VK_SUCCESS) return;  // the fence has passed, so this is rare; keep the last figures
  stats_.simulation_ms = double(ticks[1] - ticks[0]) * timestamp_ms_;
  stats_.scene_ms = double(ticks[3] - ticks[2]) * timestamp_ms_;
  stats_.indicators_ms = double(ticks[5] - ticks[4]) * timestamp_ms_;
}

bool Viewer::record_and_present(std::uint32_t slot, bool last, double dt) {
  const VkDevice device = context_->device();
  std::uint32_t image = 0;
  VkResult acquired =
      vkAcquireNextImageKHR(device, swapchain_->handle(), UINT64_MAX, acquired_[slot].get(), VK_NULL_HANDLE, &image);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return false;  // nothing was signalled: recreate and try again
  if (acquired != VK_SUBOPTIMAL_KHR) SP_VK_CHECK(acquired);
  const VkFence fence = fences_[slot].get();
  SP_VK_CHECK(vkResetFences(device, 1, &fence));

  const VkCommandBuffer cmd = commands_[slot];
  SP_VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SP_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  const std::uint32_t query = slot * kQueriesPerFrame;
  if (queries_) vkCmdResetQueryPool(cmd, queries_.get(), query, kQueriesPerFrame);
  auto stamp = [&](std::uint32_t k, VkPipelineStageFlags2 stage) {
    if (queries_) vkCmdWriteTimestamp2(cmd, stage, queries_.get(), query + k);
  };

  Visualizer& visualizer = *painting_.visualizer;
  if (!session_.listener_pinned) (void)visualizer.scene().set_listener(camera_.eye);
  stamp(0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  // A scripted run shows what its frames computed, however long a step of
  // the CPU backend takes: the step started a frame ago is handed over now.
  // The picture of frame N is then the same on any machine, at any load.
  if (options_.frames > 0) visualizer.wait_for_simulation().value();
  if (!paused_ || step_once_) visualizer.record_simulation(cmd, paused_ ? session_.config.dt : dt).value();
  step_once_ = false;
  visualizer.record_totals(cmd, totals_[slot].get(), 0).value();
  stamp(1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);

  const VkImage color = swapchain_->image(image);
  const VkImage depth = swapchain_->depth_image(image);
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  // WAR: the image's last reader was presentation (ordered by the acquire
  // semaphore, waited at this stage); its contents are not kept.
  draw::image_barrier(cmd, color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  // WAR: the previous frame on this image sampled and tested its depth.
  draw::image_barrier(cmd, depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depth_stages | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      0, depth_stages,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  const VkExtent2D extent = swapchain_->extent();
  const draw::ViewCamera view = camera_.view_camera(extent.width, extent.height);
  stamp(2, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  begin_pass(cmd, swapchain_->views()[image], swapchain_->depth_view(image), extent, true);
  painting_.scene_pass->record(cmd, view, visualizer.scene().listener());
  vkCmdEndRendering(cmd);
  stamp(3, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  // RAW: the scene's depth lands before the indicators test and sample it
  // (their vertex stage samples each spot's centre).
  draw::image_barrier(cmd, depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, depth_stages,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      depth_stages | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  stamp(4, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  begin_pass(cmd, swapchain_->views()[image], swapchain_->depth_view(image), extent, false);
  DrawOptions draw_options;
  draw_options.viewport_width = extent.width;
  draw_options.viewport_height = extent.height;
  draw_options.scene_depth = static_cast<std::int32_t>(image);
  visualizer.record_draw(cmd, view.view, view.projection, draw_options).value();
  vkCmdEndRendering(cmd);
  stamp(5, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  panel_->record(cmd, image);

  const bool screenshot = last && options_.screenshot && swapchain_->readable();
  if (screenshot) {
    screenshot_.record(*context_, cmd, color, extent);
  } else {
    // Presentation waits on the semaphore the submit signals after this.
    draw::image_barrier(cmd, color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0);
  }
  SP_VK_CHECK(vkEndCommandBuffer(cmd));

  VkSemaphoreSubmitInfo wait{};
  wait.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  wait.semaphore = acquired_[slot].get();
  // The simulation's transfers and dispatches do not touch the image: only
  // its first write waits for presentation to let go of it.
  wait.stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSemaphoreSubmitInfo signal{};
  signal.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  signal.semaphore = swapchain_->rendered(image);
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo command{};
  command.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  command.commandBuffer = cmd;
  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &command;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  SP_VK_CHECK(vkQueueSubmit2(context_->queue(), 1, &submit, fence));
  submitted_[slot] = true;

  const VkSemaphore rendered = swapchain_->rendered(image);
  const VkSwapchainKHR swapchain = swapchain_->handle();
  VkPresentInfoKHR present{};
  present.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain;
  present.pImageIndices = &image;
  const VkResult presented = vkQueuePresentKHR(context_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR) {
    swapchain_stale_ = true;
  } else {
    SP_VK_CHECK(presented);
  }
  if (screenshot) {
    SP_VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    screenshot_.write(*options_.screenshot, swapchain_->format());
  }
  return true;
}

}  // namespace sp::view
