// The one way soundpaint creates device objects: on the context's device,
// with its allocator (the host's VkAllocationCallbacks when borrowed, for the
// object and its destruction alike) and a debug name. Shader modules,
// descriptor set layouts, pools and writes, pipeline layouts, command pools,
// fences and timestamp pools all come from here.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/handle.h"
#include "vk/vk_check.h"

namespace sp::vk {

// `create` is a vkCreate* taking (device, info, allocator, out handle).
template <class Object, class Info, class Handle>
Object create_object(const Context& context,
                     VkResult(VKAPI_PTR* create)(VkDevice, const Info*, const VkAllocationCallbacks*, Handle*),
                     const Info& info, VkObjectType type, const char* name) {
  Handle raw = VK_NULL_HANDLE;
  const VkResult result = create(context.device(), &info, context.allocator(), &raw);
  if (result != VK_SUCCESS)
    check_result(result, (std::string("creating ") + (name != nullptr ? name : "a device object")).c_str(), __FILE__,
                 __LINE__);
  Object object(context.device(), raw, context.allocator());
  context.set_name(type, raw, name);
  return object;
}

// Throws sp::Exception (InvalidArgument) when `spirv` is empty.
UniqueShaderModule create_shader_module(const Context& context, std::span<const std::uint32_t> spirv, const char* name);

UniqueDescriptorSetLayout create_descriptor_set_layout(const Context& context,
                                                       std::span<const VkDescriptorSetLayoutBinding> bindings,
                                                       const char* name);
// A pool of `max_sets` sets holding `descriptors` descriptors of one type.
UniqueDescriptorPool create_descriptor_pool(const Context& context, VkDescriptorType type, std::uint32_t descriptors,
                                            std::uint32_t max_sets, const char* name);
// The same for descriptors of several types (entries of count 0 are left out).
UniqueDescriptorPool create_descriptor_pool(const Context& context, std::span<const VkDescriptorPoolSize> sizes,
                                            std::uint32_t max_sets, const char* name);
// A view of `range` bytes of `buffer` from `offset` as texels of `format`,
// for a uniform texel buffer binding.
UniqueBufferView create_buffer_view(const Context& context, VkBuffer buffer, VkFormat format, VkDeviceSize offset,
                                    VkDeviceSize range, const char* name);
// One set of `layout` from `pool`; freed with the pool (or its reset).
VkDescriptorSet allocate_descriptor_set(const Context& context, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                                        const char* name);
// Points one binding of `set` at a buffer range or at an image.
void write_descriptor(const Context& context, VkDescriptorSet set, std::uint32_t binding,
                      const VkDescriptorBufferInfo& buffer);
void write_descriptor(const Context& context, VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                      const VkDescriptorImageInfo& image);
// Points a uniform texel buffer binding of `set` at `view`.
void write_descriptor(const Context& context, VkDescriptorSet set, std::uint32_t binding, VkBufferView view);

// Push constants (if `push_constant_bytes` > 0) are one range for `push_stages`.
UniquePipelineLayout create_pipeline_layout(const Context& context, std::span<const VkDescriptorSetLayout> set_layouts,
                                            VkShaderStageFlags push_stages, std::uint32_t push_constant_bytes,
                                            const char* name);

UniqueCommandPool create_command_pool(const Context& context, std::uint32_t queue_family,
                                      VkCommandPoolCreateFlags flags, const char* name);
// One primary command buffer from `pool` (freed with it, or explicitly).
VkCommandBuffer allocate_command_buffer(const Context& context, VkCommandPool pool, const char* name);
UniqueFence create_fence(const Context& context, const char* name);
UniqueQueryPool create_timestamp_pool(const Context& context, std::uint32_t queries, const char* name);

}  // namespace sp::vk
