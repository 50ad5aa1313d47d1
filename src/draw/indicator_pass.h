// The indicator pass: every ring slot as a soft round quad on its surface,
// drawn with vkCmdDrawIndirect from a VkDrawIndirectCommand whose instance
// count the simulation wrote -- no vertex buffers, no read-back. Expired
// slots collapse in the vertex shader.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include "draw/graphics_pipeline.h"
#include "draw/view_camera.h"
#include "gpu/gpu_simulator.h"
#include "soundpaint/visualizer.h"
#include "vk/compute_pipeline.h"
#include "vk/context.h"

namespace sp::draw {

// The step a picture shows and how indicators age (SPEC 1.4).
struct IndicatorClock {
  std::uint32_t current_step = 0;  // the last step run; age = (current_step - birth step) * dt
  float dt = 1.0f / 60.0f;         // seconds per step
  float lifetime = 1.0f;           // indicator_lifetime, seconds (> 0)
};

class IndicatorPass {
 public:
  // Throws sp::Exception.
  IndicatorPass(const vk::Context& context, VkFormat color_format, VkFormat depth_format);
  // Into a host's rendering with the attachments `target` describes.
  IndicatorPass(const vk::Context& context, const DrawTarget& target);

  // Points the pass at `indicators`' ring. Call before recording each frame
  // that draws them, and never while a frame using the pass is pending (a
  // ring may have been replaced since, even under the same handle value).
  void bind(const gpu::IndicatorView& indicators);

  // Records the indirect draw inside an active rendering scope. The caller
  // has made the ring and draw arguments visible to the vertex-shader and
  // draw-indirect stages.
  void record(VkCommandBuffer cmd, const ViewCamera& camera, const gpu::IndicatorView& indicators,
              const IndicatorClock& clock) const;
  // The same with the host's matrices; `eye` is the camera position.
  void record(VkCommandBuffer cmd, const glm::mat4& view_projection, glm::vec3 eye,
              const gpu::IndicatorView& indicators, const IndicatorClock& clock) const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  vk::StorageBindings bindings_;
  GraphicsPipeline pipeline_;
};

}  // namespace sp::draw
