// Pipeline barriers as small free functions (synchronization2). Each call
// site names the hazard it resolves.
#pragma once

#include <vulkan/vulkan.h>

namespace sp::vk {

// A VkMemoryBarrier2 or VkImageMemoryBarrier2 with its stages and accesses
// either side set; the caller fills the rest.
template <class Barrier2>
Barrier2 stage_barrier(VkStructureType type, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                       VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  Barrier2 barrier{};
  barrier.sType = type;
  barrier.srcStageMask = src_stage;
  barrier.srcAccessMask = src_access;
  barrier.dstStageMask = dst_stage;
  barrier.dstAccessMask = dst_access;
  return barrier;
}

// One vkCmdPipelineBarrier2 of at most one memory and one image barrier.
inline void pipeline_barrier(VkCommandBuffer cmd, const VkMemoryBarrier2* memory, const VkImageMemoryBarrier2* image) {
  VkDependencyInfo dependency{};
  dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dependency.memoryBarrierCount = memory != nullptr ? 1 : 0;
  dependency.pMemoryBarriers = memory;
  dependency.imageMemoryBarrierCount = image != nullptr ? 1 : 0;
  dependency.pImageMemoryBarriers = image;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

inline void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  const auto barrier =
      stage_barrier<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, src_stage, src_access, dst_stage, dst_access);
  pipeline_barrier(cmd, &barrier, nullptr);
}

// Compute writes made visible to the next compute dispatch, including its
// indirect arguments.
inline void compute_to_compute(VkCommandBuffer cmd) {
  memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                     VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

}  // namespace sp::vk
