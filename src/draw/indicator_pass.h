// The indicator pass: every ring slot drawn as its category's shape on its
// surface, elongated along its sound's direction, with a halo, clipped to
// its surface when the scene's depth is given; arrows at their bearing for
// the sources heard but out of view or occluded. Drawn with
// vkCmdDrawIndirect from the VkDrawIndirectCommand the simulation wrote: no
// vertex buffers, no read-back. docs/accessibility.md says what each part
// is for.
//
// Per frame, outside any rendering: record_prepare() (the source table,
// the source cues, and the prepass that counts live spots per source and
// applies the caps);
// inside the rendering: record() and record_arrows().
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

#include "draw/display_frame.h"
#include "draw/graphics_pipeline.h"
#include "draw/scene_depth_sets.h"
#include "gpu/gpu_simulator.h"
#include "soundpaint/visualizer.h"
#include "sp_draw_types.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "vk/context.h"

namespace sp::draw {

class IndicatorPass {
 public:
  // Draws into renderings with the attachments `target` describes, for
  // worlds of up to `source_capacity` sources. Throws sp::Exception.
  IndicatorPass(const vk::Context& context, const DrawTarget& target, std::uint32_t source_capacity);

  // Points the pass at `indicators`' ring and draw arguments. Not while a
  // frame using the pass is pending.
  void bind(const gpu::IndicatorView& indicators);

  // Outside rendering: uploads `sources` (make_display_sources) and the
  // source cues if set_source_cues() changed them, runs the prepass over the
  // bound ring, then makes all of it visible to the draw (on a
  // compute-only queue, `graphics_queue` false, the host's semaphore does
  // that). Earlier writes of the ring are made visible here.
  void record_prepare(VkCommandBuffer cmd, std::span<const shader::DisplaySource> sources, const DisplayFrame& frame,
                      bool graphics_queue = true);

  // Inside an active rendering: the spots. `scene_depth` (from
  // scene_depths()) clips them to their surfaces; VK_NULL_HANDLE does not.
  void record(VkCommandBuffer cmd, const DrawView& view, const DisplayFrame& frame,
              VkDescriptorSet scene_depth = VK_NULL_HANDLE) const;
  // Inside an active rendering: an arrow on a ring inset from the screen's
  // edge, at its bearing, for each source heard but out of view, or in view
  // but occluded (set_source_cues).
  void record_arrows(VkCommandBuffer cmd, const DrawView& view, const DisplayFrame& frame) const;

  // What the simulation found per source id (SP_SOURCE_CUE_* bits,
  // sp_draw_types.h): entry i for source i, ids past the span's end 0, as
  // all are until the first call. Copied now, uploaded by the next
  // record_prepare(). Throws sp::Exception(LimitExceeded) for more entries
  // than the pass's source capacity.
  void set_source_cues(std::span<const std::uint32_t> cues);

  // Descriptor sets that sample depth images for record().
  SceneDepthSets& scene_depths() { return depth_sets_; }

 private:
  void ensure_visible_capacity(std::uint32_t slots);

  const vk::Context* context_ = nullptr;
  std::uint32_t source_capacity_ = 0;
  std::uint32_t category_capacity_ = 0;
  std::uint32_t ring_capacity_ = 0;
  VkBuffer bound_draw_args_ = VK_NULL_HANDLE;  // the bound ring's VkDrawIndirectCommand
  VkDeviceSize bound_draw_args_offset_ = 0;
  vk::StorageBindings bindings_;
  SceneDepthSets depth_sets_;
  vk::Buffer sources_;               // DisplaySource per source id
  vk::Buffer source_live_;           // per source id
  vk::Buffer source_cues_;           // per source id, SP_SOURCE_CUE_*
  std::vector<std::uint32_t> cues_;  // what source_cues_ is to hold, source_capacity_ entries
  bool cues_changed_ = true;         // cues_ not yet uploaded (the buffer starts undefined)
  vk::Buffer categories_;            // SP_CATEGORY_STRIDE per category
  vk::Buffer visible_;               // per ring slot
  GraphicsPipeline pipeline_;        // without clipping
  GraphicsPipeline clip_pipeline_;   // with the scene's depth, set 1
  GraphicsPipeline arrows_;
  vk::ComputePipeline prepass_;
};

}  // namespace sp::draw
