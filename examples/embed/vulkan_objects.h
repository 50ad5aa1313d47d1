// Owning wrappers for the example's Vulkan objects, so that an early return
// or a thrown HostError releases whatever was created so far.
#pragma once

#include <memory>
#include <utility>

#include <vulkan/vulkan.h>

// A device-level object destroyed with Destroy(device, handle, nullptr).
template <class Handle, auto Destroy>
class DeviceObject {
 public:
  DeviceObject() = default;
  DeviceObject(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  DeviceObject(DeviceObject&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  DeviceObject& operator=(DeviceObject&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  DeviceObject(const DeviceObject&) = delete;
  DeviceObject& operator=(const DeviceObject&) = delete;
  ~DeviceObject() { reset(); }

  Handle get() const { return handle_; }

 private:
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

using Buffer = DeviceObject<VkBuffer, vkDestroyBuffer>;
using Memory = DeviceObject<VkDeviceMemory, vkFreeMemory>;
using Image = DeviceObject<VkImage, vkDestroyImage>;
using ImageView = DeviceObject<VkImageView, vkDestroyImageView>;
using ShaderModule = DeviceObject<VkShaderModule, vkDestroyShaderModule>;
using PipelineLayout = DeviceObject<VkPipelineLayout, vkDestroyPipelineLayout>;
using Pipeline = DeviceObject<VkPipeline, vkDestroyPipeline>;
using CommandPool = DeviceObject<VkCommandPool, vkDestroyCommandPool>;  // frees its command buffers too
using Fence = DeviceObject<VkFence, vkDestroyFence>;

// Dispatchable handles are pointers, so unique_ptr owns them directly.
struct InstanceDeleter {
  void operator()(VkInstance instance) const noexcept { vkDestroyInstance(instance, nullptr); }
};
using UniqueInstance = std::unique_ptr<VkInstance_T, InstanceDeleter>;

struct DeviceDeleter {
  void operator()(VkDevice device) const noexcept { vkDestroyDevice(device, nullptr); }
};
using UniqueDevice = std::unique_ptr<VkDevice_T, DeviceDeleter>;

// The messenger's functions come from VK_EXT_debug_utils, so they are looked
// up at run time rather than linked.
class DebugMessenger {
 public:
  DebugMessenger() = default;
  DebugMessenger(VkInstance instance, const VkDebugUtilsMessengerCreateInfoEXT& info);
  DebugMessenger(const DebugMessenger&) = delete;
  DebugMessenger& operator=(const DebugMessenger&) = delete;
  ~DebugMessenger();

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};
