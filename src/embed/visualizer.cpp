// Visualizer::create: checks the host's objects and formats, wraps the
// host's device, and picks the backend by the library's shared policy.
#include <string>
#include <vector>

#include "core/invalid_argument.h"
#include "embed/visualizers.h"
#include "sim/memory_estimate.h"
#include "sim/world_geometry.h"

namespace sp {
namespace {

bool family_has(VkPhysicalDevice device, std::uint32_t family, VkQueueFlags flags) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  return family < count && (families[family].queueFlags & flags) == flags;
}

bool format_has(VkPhysicalDevice device, VkFormat format, VkFormatFeatureFlags feature) {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(device, format, &properties);
  return (properties.optimalTilingFeatures & feature) != 0;
}

bool has_depth_aspect(VkFormat f) {
  return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D32_SFLOAT ||
         f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

bool has_stencil_aspect(VkFormat f) {
  return f == VK_FORMAT_S8_UINT || f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT ||
         f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

Result<bool> check_target(VkPhysicalDevice device, const DrawTarget& target) {
  if (target.color_format == VK_FORMAT_UNDEFINED) return invalid_argument_error("DrawTarget: color_format must be set");
  if (!format_has(device, target.color_format, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT))
    return invalid_argument_error("DrawTarget: color format " + std::to_string(target.color_format) +
                                  " cannot be a blended colour attachment on this device");
  if (target.depth_format != VK_FORMAT_UNDEFINED &&
      (!has_depth_aspect(target.depth_format) ||
       !format_has(device, target.depth_format, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)))
    return invalid_argument_error("DrawTarget: depth format " + std::to_string(target.depth_format) +
                                  " is not a depth attachment format on this device");
  if (target.stencil_format != VK_FORMAT_UNDEFINED &&
      (!has_stencil_aspect(target.stencil_format) ||
       !format_has(device, target.stencil_format, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)))
    return invalid_argument_error("DrawTarget: stencil format " + std::to_string(target.stencil_format) +
                                  " is not a stencil attachment format on this device");
  const VkSampleCountFlagBits s = target.samples;
  if (s == 0 || (s & (s - 1)) != 0 || s > VK_SAMPLE_COUNT_64_BIT)
    return invalid_argument_error("DrawTarget: samples must be one VkSampleCountFlagBits value");
  if (target.depth_compare > VK_COMPARE_OP_ALWAYS)
    return invalid_argument_error("DrawTarget: depth_compare is not a VkCompareOp");
  return true;
}

}  // namespace

Result<std::unique_ptr<Visualizer>> Visualizer::create(const HostVulkan& host, const DrawTarget& target, World world,
                                                       const VisualizerSettings& settings) {
  if (settings.max_steps_per_frame == 0) return invalid_argument_error("Visualizer: max_steps_per_frame must be >= 1");
  if (world.geometry->bvh.nodes.empty())
    return invalid_argument_error("Visualizer: the world has no BVH (make it with make_world)");
  // The host's handles, checked (null, queue families, features) and used as
  // they are: no copy of them is made.
  Result<std::unique_ptr<vk::Context>> context = vk::Context::borrow(host);
  if (!context) return context.error();
  if (auto valid = check_target(host.physical_device, target); !valid) return valid.error();
  if (!family_has(host.physical_device, host.queue_family, VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))
    return invalid_argument_error("Visualizer: queue family " + std::to_string(host.queue_family) +
                                  " must support graphics and compute (it runs the indicator draw)");
  const bool simulation_on_graphics_queue =
      (*context)->sharing_families().size() == 1 ||
      family_has(host.physical_device, host.compute_queue_family, VK_QUEUE_GRAPHICS_BIT);

  const bool cpu_device = (*context)->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  const bool use_gpu =
      settings.backend == BackendChoice::Gpu || (settings.backend == BackendChoice::Auto && !cpu_device);
  return capture_errors(
      [&]() -> std::unique_ptr<Visualizer> {
        // A player's config must not take the host down: refused at once when
        // its rays and indicators could need more than the host allows.
        check_memory_budget(world.config, use_gpu ? Backend::Gpu : Backend::Cpu, settings.cpu.memory_budget_bytes);
        if (use_gpu)
          return embed::make_gpu_visualizer(std::move(*context), target, std::move(world), settings,
                                            simulation_on_graphics_queue);
        return embed::make_cpu_visualizer(std::move(*context), target, std::move(world), settings,
                                          simulation_on_graphics_queue);
      },
      ErrorCode::Vulkan);
}

}  // namespace sp
