#include "frame_slots.h"

#include <limits>

#include "host_error.h"

FrameSlots::FrameSlots(const HostContext& host) : host_(host) {
  const VkDevice device = host.device();
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;  // each slot is reset on its own
  pool_info.queueFamilyIndex = host.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  check(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
  pool_ = CommandPool(device, pool);

  VkCommandBufferAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  allocate.commandPool = pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = kFramesInFlight;
  check(vkAllocateCommandBuffers(device, &allocate, commands_.data()), "vkAllocateCommandBuffers");

  for (Fence& fence : fences_) {
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait on each slot returns at once
    VkFence raw = VK_NULL_HANDLE;
    check(vkCreateFence(device, &fence_info, nullptr, &raw), "vkCreateFence");
    fence = Fence(device, raw);
  }
}

FrameSlots::~FrameSlots() { (void)vkDeviceWaitIdle(host_.device()); }

VkCommandBuffer FrameSlots::begin(std::uint64_t frame) {
  const std::size_t slot = frame % kFramesInFlight;
  const VkFence fence = fences_[slot].get();
  check(vkWaitForFences(host_.device(), 1, &fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()),
        "vkWaitForFences");
  const VkCommandBuffer cmd = commands_[slot];
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &info), "vkBeginCommandBuffer");
  return cmd;
}

void FrameSlots::submit(std::uint64_t frame) {
  const std::size_t slot = frame % kFramesInFlight;
  const VkCommandBuffer cmd = commands_[slot];
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  // Reset only now: a frame that failed while recording leaves its fence
  // signalled, so nothing waits forever on it.
  const VkFence fence = fences_[slot].get();
  check(vkResetFences(host_.device(), 1, &fence), "vkResetFences");
  VkCommandBufferSubmitInfo command{};
  command.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  command.commandBuffer = cmd;
  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &command;
  check(vkQueueSubmit2(host_.queue(), 1, &submit, fence), "vkQueueSubmit2");
}

void FrameSlots::wait_idle() const { check(vkDeviceWaitIdle(host_.device()), "vkDeviceWaitIdle"); }
