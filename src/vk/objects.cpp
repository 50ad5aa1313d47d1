#include "sp_types.h"
#include "vk/objects.h"

#include <string>
#include <vector>

#include "soundpaint/result.h"

namespace sp::vk {

UniqueShaderModule create_shader_module(const Context& context, std::span<const std::uint32_t> spirv,
                                        const char* name) {
  if (spirv.empty())
    throw Exception(ErrorCode::InvalidArgument, std::string(name != nullptr ? name : "shader") + ": no SPIR-V code");
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  return create_object<UniqueShaderModule>(context, vkCreateShaderModule, info, VK_OBJECT_TYPE_SHADER_MODULE, name);
}

UniqueDescriptorSetLayout create_descriptor_set_layout(const Context& context,
                                                       std::span<const VkDescriptorSetLayoutBinding> bindings,
                                                       const char* name) {
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = static_cast<std::uint32_t>(bindings.size());
  info.pBindings = bindings.data();
  return create_object<UniqueDescriptorSetLayout>(context, vkCreateDescriptorSetLayout, info,
                                                  VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name);
}

UniqueDescriptorPool create_descriptor_pool(const Context& context, VkDescriptorType type, std::uint32_t descriptors,
                                            std::uint32_t max_sets, const char* name) {
  const VkDescriptorPoolSize size{type, descriptors};
  return create_descriptor_pool(context, {&size, 1}, max_sets, name);
}

UniqueDescriptorPool create_descriptor_pool(const Context& context, std::span<const VkDescriptorPoolSize> sizes,
                                            std::uint32_t max_sets, const char* name) {
  // A pool size of count 0 is invalid (VUID-VkDescriptorPoolSize-descriptorCount-00302).
  std::vector<VkDescriptorPoolSize> used;
  for (const VkDescriptorPoolSize& size : sizes)
    if (size.descriptorCount > 0) used.push_back(size);
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.maxSets = max_sets;
  info.poolSizeCount = static_cast<std::uint32_t>(used.size());
  info.pPoolSizes = used.data();
  return create_object<UniqueDescriptorPool>(context, vkCreateDescriptorPool, info, VK_OBJECT_TYPE_DESCRIPTOR_POOL,
                                             name);
}

UniqueBufferView create_buffer_view(const Context& context, VkBuffer buffer, VkFormat format, VkDeviceSize offset,
                                    VkDeviceSize range, const char* name) {
  VkBufferViewCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO;
  info.buffer = buffer;
  info.format = format;
  info.offset = offset;
  info.range = range;
  return create_object<UniqueBufferView>(context, vkCreateBufferView, info, VK_OBJECT_TYPE_BUFFER_VIEW, name);
}

VkDescriptorSet allocate_descriptor_set(const Context& context, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                                        const char* name) {
  VkDescriptorSetAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  info.descriptorPool = pool;
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  SP_VK_CHECK(vkAllocateDescriptorSets(context.device(), &info, &set));
  context.set_name(VK_OBJECT_TYPE_DESCRIPTOR_SET, set, name);
  return set;
}

namespace {

void write(const Context& context, VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
           const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image,
           const VkBufferView* texel_view = nullptr) {
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pBufferInfo = buffer;
  write.pImageInfo = image;
  write.pTexelBufferView = texel_view;
  vkUpdateDescriptorSets(context.device(), 1, &write, 0, nullptr);
}

}  // namespace

void write_descriptor(const Context& context, VkDescriptorSet set, std::uint32_t binding,
                      const VkDescriptorBufferInfo& buffer) {
  write(context, set, binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &buffer, nullptr);
}

void write_descriptor(const Context& context, VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                      const VkDescriptorImageInfo& image) {
  write(context, set, binding, type, nullptr, &image);
}

void write_descriptor(const Context& context, VkDescriptorSet set, std::uint32_t binding, VkBufferView view) {
  write(context, set, binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, nullptr, nullptr, &view);
}

UniquePipelineLayout create_pipeline_layout(const Context& context, std::span<const VkDescriptorSetLayout> set_layouts,
                                            VkShaderStageFlags push_stages, std::uint32_t push_constant_bytes,
                                            const char* name) {
  const VkPushConstantRange push_range{push_stages, 0, push_constant_bytes};
  VkPipelineLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  info.setLayoutCount = static_cast<std::uint32_t>(set_layouts.size());
  info.pSetLayouts = set_layouts.data();
  info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;
  info.pPushConstantRanges = &push_range;
  return create_object<UniquePipelineLayout>(context, vkCreatePipelineLayout, info, VK_OBJECT_TYPE_PIPELINE_LAYOUT,
                                             name);
}

UniqueCommandPool create_command_pool(const Context& context, std::uint32_t queue_family,
                                      VkCommandPoolCreateFlags flags, const char* name) {
  VkCommandPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  info.flags = flags;
  info.queueFamilyIndex = queue_family;
  return create_object<UniqueCommandPool>(context, vkCreateCommandPool, info, VK_OBJECT_TYPE_COMMAND_POOL, name);
}

VkCommandBuffer allocate_command_buffer(const Context& context, VkCommandPool pool, const char* name) {
  VkCommandBufferAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  info.commandPool = pool;
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  SP_VK_CHECK(vkAllocateCommandBuffers(context.device(), &info, &cmd));
  context.set_name(VK_OBJECT_TYPE_COMMAND_BUFFER, cmd, name);
  return cmd;
}

UniqueFence create_fence(const Context& context, const char* name) {
  VkFenceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  return create_object<UniqueFence>(context, vkCreateFence, info, VK_OBJECT_TYPE_FENCE, name);
}

UniqueQueryPool create_timestamp_pool(const Context& context, std::uint32_t queries, const char* name) {
  VkQueryPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = queries;
  return create_object<UniqueQueryPool>(context, vkCreateQueryPool, info, VK_OBJECT_TYPE_QUERY_POOL, name);
}

}  // namespace sp::vk
