// Image layout transitions (synchronization2) as one small free function,
// built on vk/barriers.h's; each call site names its hazard.
#pragma once

#include <vulkan/vulkan.h>

#include "vk/barriers.h"

namespace sp::draw {

inline void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout old_layout,
                          VkImageLayout new_layout, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                          VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  auto barrier = vk::stage_barrier<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, src_stage,
                                                          src_access, dst_stage, dst_access);
  barrier.oldLayout = old_layout;
  barrier.newLayout = new_layout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, 0, 1};
  vk::pipeline_barrier(cmd, nullptr, &barrier);
}

}  // namespace sp::draw
