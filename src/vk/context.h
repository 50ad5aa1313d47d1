// The Vulkan instance, device and queue soundpaint runs on when it owns them
// (CLI, tests, benchmarks). Picks a discrete or integrated GPU when present,
// else any other device (lavapipe in CI).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "soundpaint/result.h"
#include "vk/handle.h"

namespace sp {
struct HostVulkan;
}

namespace sp::vk {

// How the simulation's kernels are set up on a context, where a caller asks
// for something other than the device's choice (a 0 field).
struct KernelSettings {
  // Threads per workgroup (gpu::kernel_workgroup_size).
  std::uint32_t workgroup_size = 0;
  // The most spots a step may have for the connect pass to admit them
  // itself (gpu::inline_admission_max).
  std::uint32_t inline_admission_max = 0;
  // The most workgroups the connect pass runs (gpu::connect_groups_max).
  std::uint32_t connect_groups_max = 0;
  // The most texels the walks' tree may take in one uniform texel buffer,
  // below the device's maxTexelBufferElements; a tree needing more is read
  // from its storage buffers (gpu::bvh_texels_usable).
  std::uint32_t max_texel_buffer_elements = 0;
};

struct ContextSettings {
  // Enables VK_LAYER_KHRONOS_validation and a debug messenger that counts
  // every warning and error it reports. Also on when SOUNDPAINT_VALIDATION=1.
  bool validation = false;
  // Case-insensitive substring of the device name to pick; empty: the
  // SOUNDPAINT_DEVICE environment variable, else the best device by type
  // (discrete > integrated > virtual > CPU).
  std::string device_name;
  // Further extensions to enable (the viewer's surface and swapchain);
  // missing ones are errors naming them.
  std::vector<std::string> instance_extensions;
  std::vector<std::string> device_extensions;
  KernelSettings kernels;
};

// What the compute kernels need of the device's subgroups
// (shaders/gpu_bindings.glsl: GL_KHR_shader_subgroup_basic, _ballot and
// _arithmetic in compute shaders): the missing parts, each preceded by a
// space, or "" when all are there.
std::string missing_subgroup_support(const VkPhysicalDeviceSubgroupProperties& subgroup);

class Context {
 public:
  // Errors (ErrorCode::Vulkan): no Vulkan loader/driver, no device with
  // Vulkan 1.3 and a compute+graphics queue, a device without the subgroup
  // operations the kernels use, no device matching the name,
  // validation requested but the layer is not installed.
  static Result<std::unique_ptr<Context>> create(const ContextSettings& settings = {});
  // Wraps the host's device (sp::HostVulkan, include/soundpaint/visualizer.h,
  // read in place: its handles, allocator and pipeline cache are used as
  // they are). soundpaint creates its objects on it but never submits,
  // waits or destroys it. Errors: ErrorCode::InvalidArgument for a null
  // handle or a queue family that is unset, out of range or without
  // compute; ErrorCode::Vulkan for a device below Vulkan 1.3 or without a
  // required feature or subgroup operation (named).
  static Result<std::unique_ptr<Context>> borrow(const HostVulkan& host);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }  // VK_NULL_HANDLE when borrowed
  bool borrowed() const { return borrowed_; }
  const VkAllocationCallbacks* allocator() const { return allocator_; }
  VkPipelineCache pipeline_cache() const { return pipeline_cache_; }
  // Queue families whose queues run soundpaint's commands: the host's
  // queue_family and, when set and different, its compute_queue_family, whose
  // shared buffers are then VK_SHARING_MODE_CONCURRENT. One when owned.
  const std::vector<std::uint32_t>& sharing_families() const { return sharing_families_; }
  std::uint32_t queue_family() const { return queue_family_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::uint32_t subgroup_size() const { return subgroup_size_; }
  // ContextSettings::kernels (all 0 when borrowed).
  const KernelSettings& requested_kernels() const { return requested_kernels_; }

  // "llvmpipe (LLVM 15.0.6, 256 bits), driver Mesa 22.3.6" style text.
  std::string description() const;

  // Validation messages (warning or error severity) seen so far.
  std::uint32_t validation_message_count() const;
  bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }

  // Index of a memory type allowed by `type_bits` having all `required`
  // flags, preferring one that also has `preferred`. Throws if none.
  std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred = 0) const;

  // Debug name for an object (vkSetDebugUtilsObjectNameEXT); no-op without
  // validation.
  void set_name(VkObjectType type, std::uint64_t handle, const char* name) const;
  template <class T>
  void set_name(VkObjectType type, T handle, const char* name) const {
    set_name(type, reinterpret_cast<std::uint64_t>(handle), name);
  }

  // Submits one recorded command buffer to the queue, signalling `fence`.
  // Owned contexts only: a borrowed one throws (the host owns its queues).
  void submit(VkCommandBuffer cmd, VkFence fence) const;

  // Records with `record`, submits once, waits for completion. For uploads
  // and readbacks outside the hot path.
  template <class Fn>
  void submit_and_wait(Fn&& record) {
    VkCommandBuffer cmd = begin_one_time();
    record(cmd);
    end_one_time_and_wait(cmd);
  }

 private:
  Context() = default;
  // Reads the device's properties; throws (ErrorCode::Vulkan) when its
  // subgroups lack what the kernels use.
  void query_device_properties();
  VkCommandBuffer begin_one_time();
  void end_one_time_and_wait(VkCommandBuffer cmd);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  std::string driver_info_;
  std::uint32_t subgroup_size_ = 1;
  KernelSettings requested_kernels_;
  UniqueCommandPool one_time_pool_;  // owned contexts only
  PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
  bool borrowed_ = false;
  const VkAllocationCallbacks* allocator_ = nullptr;
  VkPipelineCache pipeline_cache_ = VK_NULL_HANDLE;
  std::vector<std::uint32_t> sharing_families_;

  struct Messages;
  std::unique_ptr<Messages> messages_;
};

}  // namespace sp::vk
