#include "sp_types.h"
#include "vk/device_selection.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <vector>

#include "soundpaint/result.h"
#include "vk/vk_check.h"

namespace sp::vk {

const char* const kNoDeviceMessage = "no Vulkan device found (install mesa-vulkan-drivers for the lavapipe CPU device)";

namespace {

struct Candidate {
  VkPhysicalDevice device = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  std::optional<std::uint32_t> queue_family;  // empty: no compute+graphics family

  bool suitable() const {
    return queue_family.has_value() && VK_API_VERSION_MAJOR(properties.apiVersion) == 1 &&
           VK_API_VERSION_MINOR(properties.apiVersion) >= 3;
  }
};

std::optional<std::uint32_t> compute_graphics_family(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  constexpr VkQueueFlags kNeeded = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
  for (std::uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & kNeeded) == kNeeded && families[i].queueCount > 0) return i;
  }
  return std::nullopt;
}

// Lower is better.
int type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// "llvmpipe (LLVM 15.0.6, 256 bits) [Vulkan 1.3]" for each device, with the
// reason a device cannot be used.
std::string list_devices(const std::vector<Candidate>& candidates) {
  std::string text;
  for (const Candidate& c : candidates) {
    if (!text.empty()) text += "; ";
    text += c.properties.deviceName;
    text += " [Vulkan " + std::to_string(VK_API_VERSION_MAJOR(c.properties.apiVersion)) + "." +
            std::to_string(VK_API_VERSION_MINOR(c.properties.apiVersion));
    if (!c.queue_family) text += ", no compute+graphics queue";
    text += "]";
  }
  return text;
}

}  // namespace

DeviceChoice select_device(VkInstance instance, const std::string& name) {
  std::uint32_t count = 0;
  VkResult result = vkEnumeratePhysicalDevices(instance, &count, nullptr);
  if (result == VK_ERROR_INITIALIZATION_FAILED || (result == VK_SUCCESS && count == 0)) {
    throw Exception(Error{ErrorCode::Vulkan, kNoDeviceMessage, static_cast<int>(result)});
  }
  SP_VK_CHECK(result);
  std::vector<VkPhysicalDevice> devices(count);
  SP_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  devices.resize(count);

  std::vector<Candidate> candidates;
  for (VkPhysicalDevice device : devices) {
    Candidate c;
    c.device = device;
    vkGetPhysicalDeviceProperties(device, &c.properties);
    c.queue_family = compute_graphics_family(device);
    candidates.push_back(c);
  }

  const Candidate* best = nullptr;
  if (!name.empty()) {
    const std::string wanted = lower(name);
    for (const Candidate& c : candidates) {
      if (c.suitable() && lower(c.properties.deviceName).find(wanted) != std::string::npos) {
        best = &c;
        break;
      }
    }
    if (best == nullptr) {
      throw Exception(ErrorCode::Vulkan, "no suitable Vulkan device matches \"" + name +
                                             "\" (needs Vulkan 1.3 and a compute+graphics queue; available: " +
                                             list_devices(candidates) + ")");
    }
  } else {
    for (const Candidate& c : candidates) {
      if (c.suitable() &&
          (best == nullptr || type_rank(c.properties.deviceType) < type_rank(best->properties.deviceType)))
        best = &c;
    }
    if (best == nullptr) {
      throw Exception(ErrorCode::Vulkan, "no Vulkan device supports Vulkan 1.3 with a compute+graphics queue (found: " +
                                             list_devices(candidates) + ")");
    }
  }
  return DeviceChoice{best->device, *best->queue_family};
}

}  // namespace sp::vk
