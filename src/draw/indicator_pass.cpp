#include "draw/indicator_pass.h"

#include "draw/draw_layout_checks.h"
#include "indicator.frag.spv.h"
#include "indicator.vert.spv.h"
#include "soundpaint/result.h"

namespace sp::draw {

IndicatorPass::IndicatorPass(const vk::Context& context, VkFormat color_format, VkFormat depth_format)
    : IndicatorPass(context, DrawTarget{color_format, depth_format}) {}

IndicatorPass::IndicatorPass(const vk::Context& context, const DrawTarget& target)
    : device_(context.device()), bindings_(context, 1, "indicator pass bindings") {
  GraphicsPipelineDesc desc;
  desc.vertex_spirv = sp_spirv_indicator_vert;
  desc.fragment_spirv = sp_spirv_indicator_frag;
  desc.set_layout = bindings_.layout();
  desc.push_constant_bytes = sizeof(shader::IndicatorPush);
  desc.color_format = target.color_format;
  desc.depth_format = target.depth_format;
  desc.stencil_format = target.stencil_format;
  desc.samples = target.samples;
  desc.depth_compare = target.depth_compare;
  // Tested against the scene's depth but not written: overlapping spots
  // blend instead of hiding one another.
  desc.blend = Blend::Alpha;
  desc.depth_write = false;
  desc.name = "indicator pass";
  pipeline_ = GraphicsPipeline(context, desc);
}

void IndicatorPass::bind(const gpu::IndicatorView& indicators) {
  if (indicators.ring == VK_NULL_HANDLE || indicators.draw_args == VK_NULL_HANDLE)
    throw Exception(ErrorCode::InvalidArgument, "indicator pass: the indicator view has no ring or draw arguments");
  // The view holds a raw VkBuffer (the simulator owns it), which
  // StorageBindings::bind does not take; the write is the same.
  const VkDescriptorBufferInfo info{indicators.ring, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = bindings_.set();
  write.dstBinding = 0;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &info;
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
}

void IndicatorPass::record(VkCommandBuffer cmd, const ViewCamera& camera, const gpu::IndicatorView& indicators,
                           const IndicatorClock& clock) const {
  record(cmd, camera.view_projection(), camera.eye, indicators, clock);
}

void IndicatorPass::record(VkCommandBuffer cmd, const glm::mat4& view_projection, glm::vec3 eye,
                           const gpu::IndicatorView& indicators, const IndicatorClock& clock) const {
  shader::IndicatorPush push{};
  push.view_proj = view_projection;
  push.eye = eye;
  push.current_step = clock.current_step;
  push.dt = clock.dt;
  push.lifetime = clock.lifetime;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const VkDescriptorSet set = bindings_.set();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout(), 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                     &push);
  vkCmdDrawIndirect(cmd, indicators.draw_args, indicators.draw_args_offset, 1, sizeof(VkDrawIndirectCommand));
}

}  // namespace sp::draw
