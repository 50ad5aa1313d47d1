#include "sp_types.h"
#include "vk/context.h"

#include <cstdlib>
#include <stdexcept>
#include <algorithm>
#include <cstring>
#include <string_view>

#include "soundpaint/visualizer.h"
#include "vk/debug_messenger.h"
#include "vk/device_selection.h"
#include "vk/handle.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::vk {

// The messenger's sink; see debug_messenger.h.
struct Context::Messages : MessageLog {};

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool env_is(const char* variable, std::string_view value) {
  const char* text = std::getenv(variable);
  return text != nullptr && value == text;
}

bool has_instance_layer(const char* name) {
  std::uint32_t count = 0;
  SP_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  SP_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  for (std::uint32_t i = 0; i < count; ++i) {
    if (std::strcmp(layers[i].layerName, name) == 0) return true;
  }
  return false;
}

// Instance extensions from the loader and drivers, or from `layer` if given.
bool has_instance_extension(const char* layer, const char* name) {
  std::uint32_t count = 0;
  SP_VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr));
  std::vector<VkExtensionProperties> extensions(count);
  SP_VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()));
  for (std::uint32_t i = 0; i < count; ++i) {
    if (std::strcmp(extensions[i].extensionName, name) == 0) return true;
  }
  return false;
}

// `messages` non-null: validation on, with a messenger chained into the
// create info so that vkCreateInstance/vkDestroyInstance are watched too.
VkInstance create_instance(MessageLog* messages, const std::vector<std::string>& wanted) {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  VkInstanceCreateFlags flags = 0;
  // Validation checks synchronization too, where the layer offers the switch
  // (every Khronos layer of the last years does): hazards between commands,
  // such as a shader stage reading what no barrier made visible to it.
  bool sync_validation = false;
  for (const std::string& name : wanted) {
    if (!has_instance_extension(nullptr, name.c_str()))
      throw Exception(ErrorCode::Vulkan, "the Vulkan instance extension " + name + " is not available");
    extensions.push_back(name.c_str());
  }

  if (messages != nullptr) {
    if (!has_instance_layer(kValidationLayer)) {
      throw Exception(ErrorCode::Vulkan, std::string("validation requested but the Vulkan layer ") + kValidationLayer +
                                             " is not installed (Debian/Ubuntu package vulkan-validationlayers)");
    }
    if (!has_instance_extension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
        !has_instance_extension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
      throw Exception(ErrorCode::Vulkan, std::string("validation requested but the instance extension ") +
                                             VK_EXT_DEBUG_UTILS_EXTENSION_NAME + " is not available");
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    sync_validation = has_instance_extension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    if (sync_validation) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }
  // Lists devices layered over another API (MoltenVK) too; harmless elsewhere.
  if (has_instance_extension(nullptr, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
    extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
    flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
  }

  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "soundpaint";
  app.pEngineName = "soundpaint";
  app.apiVersion = VK_API_VERSION_1_3;

  const VkDebugUtilsMessengerCreateInfoEXT messenger_info = debug_messenger_info(messages);
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.pNext = &messenger_info;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  if (messages != nullptr) info.pNext = sync_validation ? static_cast<const void*>(&features) : &messenger_info;
  info.flags = flags;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  // The loader's answer when it finds no driver at all.
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
    throw Exception(Error{ErrorCode::Vulkan, kNoDeviceMessage, static_cast<int>(result)});
  }
  SP_VK_CHECK(result);
  return instance;
}

// Features every Vulkan 1.3 device has, requested explicitly: the later
// graphics pass uses dynamic rendering and synchronization2 barriers;
// timestamp queries are reset from the host; glslang's vulkan1.3 target
// (SPIR-V 1.6) declares workgroup sizes with LocalSizeId, which needs
// maintenance4.
struct DeviceFeatures {
  VkPhysicalDeviceFeatures2 features{};
  VkPhysicalDeviceVulkan12Features vulkan12{};
  VkPhysicalDeviceVulkan13Features vulkan13{};

  DeviceFeatures() {
    features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    vulkan12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    vulkan13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
    features.pNext = &vulkan12;
    vulkan12.pNext = &vulkan13;
  }
  DeviceFeatures(const DeviceFeatures&) = delete;  // self-referential pNext chain
  DeviceFeatures& operator=(const DeviceFeatures&) = delete;
};

// The Vulkan 1.3 features every shader and barrier of soundpaint relies on.
std::string missing_core_features(const VkPhysicalDeviceVulkan13Features& features) {
  std::string missing;
  if (!features.synchronization2) missing += " synchronization2";
  if (!features.dynamicRendering) missing += " dynamicRendering";
  if (!features.maintenance4) missing += " maintenance4";
  return missing;
}

// What the host enabled, read from the pNext chain it gave vkCreateDevice:
// VkPhysicalDeviceVulkan13Features or the per-feature structs it replaces.
// Returns the missing ones; a chain naming none of them misses all three.
std::string missing_enabled_features(const void* chain) {
  VkPhysicalDeviceVulkan13Features enabled{};
  for (auto* node = static_cast<const VkBaseInStructure*>(chain); node != nullptr; node = node->pNext) {
    switch (node->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
        const auto* v13 = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(node);
        enabled.synchronization2 |= v13->synchronization2;
        enabled.dynamicRendering |= v13->dynamicRendering;
        enabled.maintenance4 |= v13->maintenance4;
        break;
      }
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
        enabled.synchronization2 |=
            reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(node)->synchronization2;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
        enabled.dynamicRendering |=
            reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(node)->dynamicRendering;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
        enabled.maintenance4 |= reinterpret_cast<const VkPhysicalDeviceMaintenance4Features*>(node)->maintenance4;
        break;
      default:
        break;
    }
  }
  return missing_core_features(enabled);
}

void require_features(VkPhysicalDevice device, const char* device_name, bool host_query_reset = true) {
  DeviceFeatures supported;
  vkGetPhysicalDeviceFeatures2(device, &supported.features);
  std::string missing = missing_core_features(supported.vulkan13);
  if (host_query_reset && !supported.vulkan12.hostQueryReset) missing += " hostQueryReset";
  if (!missing.empty()) {
    throw Exception(ErrorCode::Vulkan, std::string(device_name) + " lacks required Vulkan features:" + missing);
  }
}

}  // namespace

std::string missing_subgroup_support(const VkPhysicalDeviceSubgroupProperties& subgroup) {
  std::string missing;
  if ((subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0) missing += " compute-stage subgroups";
  const struct {
    VkSubgroupFeatureFlagBits bit;
    const char* name;
  } operations[] = {{VK_SUBGROUP_FEATURE_BASIC_BIT, " basic"},
                    {VK_SUBGROUP_FEATURE_BALLOT_BIT, " ballot"},
                    {VK_SUBGROUP_FEATURE_ARITHMETIC_BIT, " arithmetic"}};
  for (const auto& operation : operations)
    if ((subgroup.supportedOperations & operation.bit) == 0)
      missing += std::string(operation.name) + " subgroup operations";
  return missing;
}

Result<std::unique_ptr<Context>> Context::create(const ContextSettings& settings) {
  return capture_errors(
      [&]() -> std::unique_ptr<Context> {
        // Built step by step; if a step throws, the destructor releases the
        // steps already done (it skips null handles).
        std::unique_ptr<Context> context(new Context());
        context->requested_kernels_ = settings.kernels;
        const bool validation = settings.validation || env_is("SOUNDPAINT_VALIDATION", "1");
        if (validation) context->messages_ = std::make_unique<Messages>();

        context->instance_ = create_instance(context->messages_.get(), settings.instance_extensions);
        const VkInstance instance = context->instance_;
        if (validation) {
          const auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
              vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
          context->set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
              vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
          if (create_messenger == nullptr) {
            throw Exception(ErrorCode::Vulkan,
                            "vkCreateDebugUtilsMessengerEXT is missing although VK_EXT_debug_utils is on");
          }
          const VkDebugUtilsMessengerCreateInfoEXT info = debug_messenger_info(context->messages_.get());
          SP_VK_CHECK(create_messenger(instance, &info, nullptr, &context->messenger_));
        }

        std::string device_name = settings.device_name;
        if (device_name.empty()) {
          const char* from_env = std::getenv("SOUNDPAINT_DEVICE");
          if (from_env != nullptr) device_name = from_env;
        }
        const DeviceChoice choice = select_device(instance, device_name);
        context->physical_device_ = choice.device;
        context->queue_family_ = choice.queue_family;

        context->sharing_families_ = {choice.queue_family};
        context->query_device_properties();
        require_features(choice.device, context->properties_.deviceName);
        DeviceFeatures enabled;
        enabled.vulkan13.synchronization2 = VK_TRUE;
        enabled.vulkan13.dynamicRendering = VK_TRUE;
        enabled.vulkan13.maintenance4 = VK_TRUE;
        enabled.vulkan12.hostQueryReset = VK_TRUE;

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{};
        queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
        queue_info.queueFamilyIndex = choice.queue_family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        std::vector<const char*> device_extensions;
        if (!settings.device_extensions.empty()) {
          std::uint32_t count = 0;
          SP_VK_CHECK(vkEnumerateDeviceExtensionProperties(choice.device, nullptr, &count, nullptr));
          std::vector<VkExtensionProperties> available(count);
          SP_VK_CHECK(vkEnumerateDeviceExtensionProperties(choice.device, nullptr, &count, available.data()));
          for (const std::string& name : settings.device_extensions) {
            const bool found = std::any_of(available.begin(), available.end(),
                                           [&](const VkExtensionProperties& e) { return name == e.extensionName; });
            if (!found)
              throw Exception(ErrorCode::Vulkan,
                              std::string(context->properties_.deviceName) + " lacks the device extension " + name);
            device_extensions.push_back(name.c_str());
          }
        }
        VkDeviceCreateInfo device_info{};
        device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
        device_info.pNext = &enabled.features;
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        device_info.enabledExtensionCount = static_cast<std::uint32_t>(device_extensions.size());
        device_info.ppEnabledExtensionNames = device_extensions.data();
        SP_VK_CHECK(vkCreateDevice(choice.device, &device_info, nullptr, &context->device_));
        vkGetDeviceQueue(context->device_, choice.queue_family, 0, &context->queue_);
        context->set_name(VK_OBJECT_TYPE_DEVICE, context->device_, "soundpaint device");
        context->set_name(VK_OBJECT_TYPE_QUEUE, context->queue_, "soundpaint queue");

        context->one_time_pool_ =
            create_command_pool(*context, choice.queue_family, VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                "soundpaint one-time commands");
        return context;
      },
      ErrorCode::Vulkan);
}

void Context::query_device_properties() {
  VkPhysicalDeviceDriverProperties driver{};
  driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
  VkPhysicalDeviceSubgroupProperties subgroup{};
  subgroup.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES;
  subgroup.pNext = &driver;
  VkPhysicalDeviceProperties2 properties{};
  properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
  properties.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(physical_device_, &properties);
  properties_ = properties.properties;
  subgroup_size_ = subgroup.subgroupSize;
  driver_info_ = std::string(driver.driverName) + " " + driver.driverInfo;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);
  if (const std::string missing = missing_subgroup_support(subgroup); !missing.empty())
    throw Exception(ErrorCode::Vulkan, std::string(properties_.deviceName) +
                                           " lacks what soundpaint's compute kernels need of subgroups:" + missing);
}

Result<std::unique_ptr<Context>> Context::borrow(const HostVulkan& host) {
  return capture_errors(
      [&]() -> std::unique_ptr<Context> {
        if (host.instance == VK_NULL_HANDLE || host.physical_device == VK_NULL_HANDLE || host.device == VK_NULL_HANDLE)
          throw Exception(ErrorCode::InvalidArgument,
                          "the host's VkInstance, VkPhysicalDevice and VkDevice must all be set");
        if (host.queue_family == VK_QUEUE_FAMILY_IGNORED)
          throw Exception(ErrorCode::InvalidArgument, "HostVulkan::queue_family must be set");
        std::unique_ptr<Context> context(new Context());
        context->borrowed_ = true;
        context->instance_ = host.instance;
        context->physical_device_ = host.physical_device;
        context->device_ = host.device;
        context->allocator_ = host.allocator;
        context->pipeline_cache_ = host.pipeline_cache;
        context->query_device_properties();
        const std::string name = context->properties_.deviceName;
        if (context->properties_.apiVersion < VK_API_VERSION_1_3)
          throw Exception(
              ErrorCode::Vulkan,
              name + " supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(context->properties_.apiVersion)) + "." +
                  std::to_string(VK_API_VERSION_MINOR(context->properties_.apiVersion)) + "; soundpaint needs 1.3");
        require_features(host.physical_device, name.c_str(), false);
        if (host.enabled_features != nullptr) {
          const std::string missing = missing_enabled_features(host.enabled_features);
          if (!missing.empty())
            throw Exception(ErrorCode::Vulkan,
                            "the host's VkDevice was created without Vulkan 1.3 features soundpaint "
                            "needs (enable them in VkDeviceCreateInfo::pNext):" +
                                missing);
        }

        std::uint32_t family_count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &family_count, nullptr);
        std::vector<VkQueueFamilyProperties> families(family_count);
        vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &family_count, families.data());
        for (std::uint32_t family : {host.queue_family, host.compute_queue_family}) {
          if (family == VK_QUEUE_FAMILY_IGNORED) continue;  // no async compute queue
          if (family >= family_count)
            throw Exception(ErrorCode::InvalidArgument, "queue family " + std::to_string(family) +
                                                            " does not exist on " + name + " (it has " +
                                                            std::to_string(family_count) + ")");
          if ((families[family].queueFlags & VK_QUEUE_COMPUTE_BIT) == 0)
            throw Exception(ErrorCode::InvalidArgument,
                            "queue family " + std::to_string(family) + " of " + name + " cannot run compute work");
          if (std::find(context->sharing_families_.begin(), context->sharing_families_.end(), family) ==
              context->sharing_families_.end())
            context->sharing_families_.push_back(family);
        }
        context->queue_family_ = host.queue_family;
        return context;
      },
      ErrorCode::Vulkan);
}

Context::~Context() {
  if (borrowed_) return;  // the host destroys its own device and instance
  if (device_ != VK_NULL_HANDLE) {
    // A lost device cannot be helped while tearing down; destroy regardless.
    (void)vkDeviceWaitIdle(device_);
    one_time_pool_.reset();
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_ != VK_NULL_HANDLE) {
    const auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger != nullptr) destroy_messenger(instance_, messenger_, nullptr);
  }
  // Messages from here on reach messages_ through the create-info messenger.
  if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

std::string Context::description() const { return std::string(properties_.deviceName) + ", driver " + driver_info_; }

std::uint32_t Context::validation_message_count() const {
  if (!messages_) return 0;
  const std::lock_guard lock(messages_->mutex);
  return messages_->count;
}

std::uint32_t Context::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                   VkMemoryPropertyFlags preferred) const {
  for (const VkMemoryPropertyFlags wanted : {required | preferred, required}) {
    for (std::uint32_t i = 0; i < memory_properties_.memoryTypeCount; ++i) {
      const VkMemoryPropertyFlags flags = memory_properties_.memoryTypes[i].propertyFlags;
      if ((type_bits & (1u << i)) != 0 && (flags & wanted) == wanted) return i;
    }
  }
  throw Exception(ErrorCode::Vulkan, "no memory type among bits " + std::to_string(type_bits) +
                                         " has the required property flags " + std::to_string(required));
}

void Context::set_name(VkObjectType type, std::uint64_t handle, const char* name) const {
  if (set_object_name_ == nullptr || name == nullptr) return;
  VkDebugUtilsObjectNameInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT;
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  (void)set_object_name_(device_, &info);  // naming is best effort
}

VkCommandBuffer Context::begin_one_time() {
  if (borrowed_) throw std::logic_error("soundpaint never submits to a host's queues");
  VkCommandBuffer cmd = allocate_command_buffer(*this, one_time_pool_.get(), "soundpaint one-time command buffer");

  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  const VkResult result = vkBeginCommandBuffer(cmd, &begin);
  if (result != VK_SUCCESS) vkFreeCommandBuffers(device_, one_time_pool_.get(), 1, &cmd);
  SP_VK_CHECK(result);
  return cmd;
}

void Context::end_one_time_and_wait(VkCommandBuffer cmd) {
  // Frees `cmd` however this function ends.
  struct FreeOnExit {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } free_on_exit{device_, one_time_pool_.get(), cmd};

  SP_VK_CHECK(vkEndCommandBuffer(cmd));
  const UniqueFence fence = create_fence(*this, "soundpaint one-time fence");
  const VkFence raw_fence = fence.get();

  submit(cmd, raw_fence);
  SP_VK_CHECK(vkWaitForFences(device_, 1, &raw_fence, VK_TRUE, UINT64_MAX));
}

void Context::submit(VkCommandBuffer cmd, VkFence fence) const {
  if (borrowed_) throw std::logic_error("soundpaint never submits to a host's queues");
  VkCommandBufferSubmitInfo cmd_info{};
  cmd_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  cmd_info.commandBuffer = cmd;
  VkSubmitInfo2 submit_info{};
  submit_info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit_info.commandBufferInfoCount = 1;
  submit_info.pCommandBufferInfos = &cmd_info;
  SP_VK_CHECK(vkQueueSubmit2(queue_, 1, &submit_info, fence));
}

}  // namespace sp::vk
