// A move-only owner of one Vulkan object created from a VkDevice: copy
// deleted, move via std::exchange, destroyed with the device's destroy
// function when the owner dies. The device must outlive its objects.
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace sp::vk {

template <class T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class DeviceObject {
 public:
  DeviceObject() = default;
  DeviceObject(VkDevice device, T handle, const VkAllocationCallbacks* allocator = nullptr)
      : device_(device), handle_(handle), allocator_(allocator) {}
  ~DeviceObject() { reset(); }

  DeviceObject(const DeviceObject&) = delete;
  DeviceObject& operator=(const DeviceObject&) = delete;
  DeviceObject(DeviceObject&& other) noexcept
      : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
        handle_(std::exchange(other.handle_, VK_NULL_HANDLE)),
        allocator_(std::exchange(other.allocator_, nullptr)) {}
  DeviceObject& operator=(DeviceObject&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = std::exchange(other.device_, VK_NULL_HANDLE);
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
      allocator_ = std::exchange(other.allocator_, nullptr);
    }
    return *this;
  }

  T get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, allocator_);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  T handle_ = VK_NULL_HANDLE;
  const VkAllocationCallbacks* allocator_ = nullptr;
};

using UniqueBuffer = DeviceObject<VkBuffer, vkDestroyBuffer>;
using UniqueMemory = DeviceObject<VkDeviceMemory, vkFreeMemory>;
using UniqueShaderModule = DeviceObject<VkShaderModule, vkDestroyShaderModule>;
using UniquePipeline = DeviceObject<VkPipeline, vkDestroyPipeline>;
using UniquePipelineLayout = DeviceObject<VkPipelineLayout, vkDestroyPipelineLayout>;
using UniqueDescriptorSetLayout = DeviceObject<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = DeviceObject<VkDescriptorPool, vkDestroyDescriptorPool>;
using UniqueCommandPool = DeviceObject<VkCommandPool, vkDestroyCommandPool>;
using UniqueFence = DeviceObject<VkFence, vkDestroyFence>;
using UniqueQueryPool = DeviceObject<VkQueryPool, vkDestroyQueryPool>;
using UniqueImage = DeviceObject<VkImage, vkDestroyImage>;
using UniqueImageView = DeviceObject<VkImageView, vkDestroyImageView>;
using UniqueSampler = DeviceObject<VkSampler, vkDestroySampler>;
using UniqueBufferView = DeviceObject<VkBufferView, vkDestroyBufferView>;

}  // namespace sp::vk
