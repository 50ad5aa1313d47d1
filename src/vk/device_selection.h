// Picking the physical device and queue family a Context runs on.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace sp::vk {

struct DeviceChoice {
  VkPhysicalDevice device = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;  // has both COMPUTE and GRAPHICS
};

// Among the instance's devices with Vulkan >= 1.3 and a compute+graphics
// queue family: the first whose name contains `name` case-insensitively
// (when `name` is not empty), else the best by type (discrete > integrated >
// virtual > CPU > other). Throws sp::Exception(ErrorCode::Vulkan) when there
// is no device at all, no suitable one, or none matching `name`; the message
// lists the devices found.
DeviceChoice select_device(VkInstance instance, const std::string& name);

// The error text used when Vulkan has no device (no driver installed).
extern const char* const kNoDeviceMessage;

}  // namespace sp::vk
