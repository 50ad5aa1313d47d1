// The host's side of a Visualizer test: a command pool on the shared
// context's queue family, command buffers begun for recording, and
// submissions waited on with the host's own fences, as a renderer would.
#pragma once

#include <initializer_list>

#include <gtest/gtest.h>

#include "soundpaint/visualizer.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace sp::test {

// The shared context's handles, lent as a host lends its own.
inline HostVulkan host_vulkan_of(const vk::Context& context) {
  HostVulkan host;
  host.instance = context.instance();
  host.physical_device = context.physical_device();
  host.device = context.device();
  host.queue_family = context.queue_family();
  return host;
}

class HostCommands {
 public:
  explicit HostCommands(const vk::Context& context) : context_(context) {
    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateCommandPool(context.device(), &pool_info, nullptr, &pool), VK_SUCCESS);
    pool_ = vk::UniqueCommandPool(context.device(), pool);
  }

  // A new primary command buffer in the recording state (freed with the pool).
  VkCommandBuffer begin() {
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool_.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateCommandBuffers(context_.device(), &alloc, &cmd), VK_SUCCESS);
    VkCommandBufferBeginInfo info{};
    info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    EXPECT_EQ(vkBeginCommandBuffer(cmd, &info), VK_SUCCESS);
    return cmd;
  }

  // Submits ended command buffers in order, each waited for before the next.
  void submit_and_wait(std::initializer_list<VkCommandBuffer> cmds) {
    for (VkCommandBuffer cmd : cmds) {
      VkFenceCreateInfo fence_info{};
      fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
      VkFence fence = VK_NULL_HANDLE;
      EXPECT_EQ(vkCreateFence(context_.device(), &fence_info, nullptr, &fence), VK_SUCCESS);
      const vk::UniqueFence owned(context_.device(), fence);
      VkSubmitInfo submit{};
      submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
      submit.commandBufferCount = 1;
      submit.pCommandBuffers = &cmd;
      EXPECT_EQ(vkQueueSubmit(context_.queue(), 1, &submit, fence), VK_SUCCESS);
      EXPECT_EQ(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
    }
  }

 private:
  const vk::Context& context_;
  vk::UniqueCommandPool pool_;
};

}  // namespace sp::test
