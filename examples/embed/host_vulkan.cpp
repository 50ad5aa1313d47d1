#include "host_vulkan.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "host_error.h"

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user_data) {
  const char* kind = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0 ? "error" : "warning";
  const char* text = data != nullptr && data->pMessage != nullptr ? data->pMessage : "(no text)";
  std::fprintf(stderr, "soundpaint_embed_example: validation %s: %s\n", kind, text);
  static_cast<ValidationLog*>(user_data)->count.fetch_add(1);
  return VK_FALSE;  // report, never abort the call
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = on_validation_message;
  info.pUserData = log;
  return info;
}

bool has_layer(const char* name) {
  std::uint32_t count = 0;
  check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
  std::vector<VkLayerProperties> layers(count);
  check(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
  for (const VkLayerProperties& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

UniqueInstance create_instance(ValidationLog* log) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "soundpaint_embed_example";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  if (log != nullptr) {
    if (!has_layer(kValidationLayer))
      fail(std::string("validation requested but ") + kValidationLayer +
           " is not installed (Debian package vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  // Chained into the create info, the messenger also watches vkCreateInstance
  // and vkDestroyInstance, which the long-lived messenger cannot.
  const VkDebugUtilsMessengerCreateInfoEXT watch_instance = messenger_info(log);
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pNext = log != nullptr ? &watch_instance : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER) fail("no Vulkan driver found (no Vulkan device to render with)");
  check(result, "vkCreateInstance");
  return UniqueInstance(instance);
}

std::optional<std::uint32_t> graphics_compute_family(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & wanted) == wanted) return i;
  return std::nullopt;
}

bool has_needed_features(VkPhysicalDevice device) {
  VkPhysicalDeviceVulkan13Features v13{};
  v13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  VkPhysicalDeviceFeatures2 features{};
  features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features.pNext = &v13;
  vkGetPhysicalDeviceFeatures2(device, &features);
  return v13.synchronization2 && v13.dynamicRendering && v13.maintenance4;
}

// Lower is better: a real GPU before a CPU implementation such as lavapipe.
int preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 2;
    default:
      return 3;
  }
}

}  // namespace

DebugMessenger::DebugMessenger(VkInstance instance, const VkDebugUtilsMessengerCreateInfoEXT& info)
    : instance_(instance) {
  const auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  if (create == nullptr) fail("vkCreateDebugUtilsMessengerEXT is missing although VK_EXT_debug_utils is enabled");
  check(create(instance, &info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
}

DebugMessenger::~DebugMessenger() {
  if (messenger_ == VK_NULL_HANDLE) return;
  const auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
  if (destroy != nullptr) destroy(instance_, messenger_, nullptr);
}

HostContext::HostContext(ValidationLog* log) : instance_(create_instance(log)) {
  if (log != nullptr) messenger_.emplace(instance_.get(), messenger_info(log));

  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance_.get(), &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance_.get(), &count, devices.data()), "vkEnumeratePhysicalDevices");
  int best = 4;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(device, &properties);
    const std::optional<std::uint32_t> family = graphics_compute_family(device);
    if (properties.apiVersion < VK_API_VERSION_1_3 || !family || !has_needed_features(device)) continue;
    if (preference(properties.deviceType) >= best) continue;  // ties keep the first listed
    best = preference(properties.deviceType);
    physical_device_ = device;
    queue_family_ = *family;
    properties_ = properties;
  }
  if (physical_device_ == VK_NULL_HANDLE)
    fail("no Vulkan 1.3 device with a graphics+compute queue and synchronization2, dynamicRendering and maintenance4");
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);

  // What soundpaint requires (and this renderer uses: dynamic rendering and
  // synchronization2 barriers).
  features13_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  features13_.synchronization2 = VK_TRUE;
  features13_.dynamicRendering = VK_TRUE;
  features13_.maintenance4 = VK_TRUE;
  features_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  features_.pNext = &features13_;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.pNext = &features_;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  VkDevice device = VK_NULL_HANDLE;
  check(vkCreateDevice(physical_device_, &info, nullptr, &device), "vkCreateDevice");
  device_.reset(device);
  vkGetDeviceQueue(device, queue_family_, 0, &queue_);
}

Memory HostContext::allocate(const VkMemoryRequirements& requirements, VkMemoryPropertyFlags flags) const {
  for (std::uint32_t i = 0; i < memory_properties_.memoryTypeCount; ++i) {
    if ((requirements.memoryTypeBits & (1u << i)) == 0) continue;
    if ((memory_properties_.memoryTypes[i].propertyFlags & flags) != flags) continue;
    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = i;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device_.get(), &info, nullptr, &memory), "vkAllocateMemory");
    return Memory(device_.get(), memory);
  }
  fail("no memory type with property flags " + std::to_string(flags) + " for this resource");
}
