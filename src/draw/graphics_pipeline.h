// A graphics pipeline for dynamic rendering (no render pass, no framebuffer)
// whose vertices are pulled from storage buffers: no vertex input state.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "vk/context.h"
#include "vk/handle.h"

namespace sp::draw {

enum class Blend {
  Opaque,  // colour replaces the target
  Alpha,   // straight alpha: src * a + dst * (1 - a)
};

struct GraphicsPipelineDesc {
  std::span<const std::uint32_t> vertex_spirv;  // embedded SPIR-V, entry point "main"
  std::span<const std::uint32_t> fragment_spirv;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;    // set 0
  VkDescriptorSetLayout set_layout_1 = VK_NULL_HANDLE;  // set 1, optional
  std::uint32_t push_constant_bytes = 0;                // one range, vertex + fragment stages
  VkFormat color_format = VK_FORMAT_UNDEFINED;
  VkFormat depth_format = VK_FORMAT_UNDEFINED;    // UNDEFINED: no depth attachment, no depth test
  VkFormat stencil_format = VK_FORMAT_UNDEFINED;  // the rendering's stencil attachment, if any
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  Blend blend = Blend::Opaque;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;  // the indicator pass draws strips
  bool depth_write = true;
  bool depth_test = true;                                   // false: drawn over everything (screen-space overlays)
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;  // GREATER_OR_EQUAL for reversed depth
  const char* name = "graphics pipeline";                   // debug name
};

// The description's topology (triangle lists unless told), no culling (the
// level's surfaces are seen from both sides), dynamic viewport and scissor.
// Throws sp::Exception on failure.
class GraphicsPipeline {
 public:
  GraphicsPipeline() = default;
  GraphicsPipeline(const vk::Context& context, const GraphicsPipelineDesc& desc);

  VkPipeline get() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }

 private:
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline pipeline_;
};

}  // namespace sp::draw
