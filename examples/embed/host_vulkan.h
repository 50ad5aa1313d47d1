// The host's own Vulkan instance, device and queue, as any engine has them
// before soundpaint is added: soundpaint borrows these, it creates none.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

#include "vulkan_objects.h"

// Validation warnings and errors, counted until the instance is gone (its
// destruction reports leaks), so it must outlive the HostContext.
struct ValidationLog {
  std::atomic<std::uint32_t> count{0};
};

class HostContext {
 public:
  // `log` non-null: the Khronos validation layer and a messenger that prints
  // each warning or error to stderr and counts it in `log`.
  explicit HostContext(ValidationLog* log);
  // The features chain below is pointed at by enabled_features().
  HostContext(const HostContext&) = delete;
  HostContext& operator=(const HostContext&) = delete;

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  // The pNext chain given to vkCreateDevice (what was enabled, not merely supported).
  const void* enabled_features() const { return &features_; }

  // Memory for `requirements` with all of `flags`; throws HostError if none fits.
  Memory allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags) const;

 private:
  UniqueInstance instance_;
  std::optional<DebugMessenger> messenger_;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  VkPhysicalDeviceFeatures2 features_{};
  VkPhysicalDeviceVulkan13Features features13_{};
  UniqueDevice device_;
  VkQueue queue_ = VK_NULL_HANDLE;
};
