#include "vk/compute_pipeline.h"

#include <string>
#include <vector>

#include "soundpaint/result.h"
#include "vk/vk_check.h"

namespace sp::vk {

StorageBindings::StorageBindings(const Context& context, std::uint32_t binding_count, const char* name) {
  const std::string label = name != nullptr ? name : "storage bindings";
  if (binding_count == 0) throw Exception(ErrorCode::InvalidArgument, label + ": needs at least one binding");
  const VkDevice device = context.device();

  std::vector<VkDescriptorSetLayoutBinding> bindings(binding_count);
  for (std::uint32_t i = 0; i < binding_count; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    // Vertex and fragment too: the indicator drawing pass reads its buffer
    // through a set of the same layout.
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  VkDescriptorSetLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  layout_info.bindingCount = binding_count;
  layout_info.pBindings = bindings.data();
  VkDescriptorSetLayout raw_layout = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateDescriptorSetLayout(device, &layout_info, context.allocator(), &raw_layout));
  layout_ = UniqueDescriptorSetLayout(device, raw_layout, context.allocator());
  context.set_name(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, raw_layout, (label + " layout").c_str());

  const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, binding_count};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VkDescriptorPool raw_pool = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateDescriptorPool(device, &pool_info, context.allocator(), &raw_pool));
  pool_ = UniqueDescriptorPool(device, raw_pool, context.allocator());
  context.set_name(VK_OBJECT_TYPE_DESCRIPTOR_POOL, raw_pool, (label + " pool").c_str());

  VkDescriptorSetAllocateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  set_info.descriptorPool = raw_pool;
  set_info.descriptorSetCount = 1;
  set_info.pSetLayouts = &raw_layout;
  SP_VK_CHECK(vkAllocateDescriptorSets(device, &set_info, &set_));  // freed with the pool
  context.set_name(VK_OBJECT_TYPE_DESCRIPTOR_SET, set_, label.c_str());
}

void StorageBindings::bind(const Context& context, std::uint32_t binding, const Buffer& buffer) {
  bind(context, binding, buffer.get());
}

void StorageBindings::bind(const Context& context, std::uint32_t binding, VkBuffer buffer, VkDeviceSize offset,
                           VkDeviceSize range) {
  const VkDescriptorBufferInfo info{buffer, offset, range};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = set_;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &info;
  vkUpdateDescriptorSets(context.device(), 1, &write, 0, nullptr);
}

ComputePipeline::ComputePipeline(const Context& context, std::span<const std::uint32_t> spirv,
                                 VkDescriptorSetLayout set_layout, std::uint32_t push_constant_bytes,
                                 const char* name) {
  const std::string label = name != nullptr ? name : "compute pipeline";
  if (spirv.empty()) throw Exception(ErrorCode::InvalidArgument, label + ": no SPIR-V code");
  const VkDevice device = context.device();

  const VkPushConstantRange push_range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  layout_info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &push_range;
  VkPipelineLayout raw_layout = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreatePipelineLayout(device, &layout_info, context.allocator(), &raw_layout));
  layout_ = UniquePipelineLayout(device, raw_layout, context.allocator());
  context.set_name(VK_OBJECT_TYPE_PIPELINE_LAYOUT, raw_layout, (label + " layout").c_str());

  VkShaderModuleCreateInfo module_info{};
  module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  module_info.codeSize = spirv.size_bytes();
  module_info.pCode = spirv.data();
  VkShaderModule raw_module = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateShaderModule(device, &module_info, context.allocator(), &raw_module));
  const UniqueShaderModule shader(device, raw_module, context.allocator());  // not needed once the pipeline exists
  context.set_name(VK_OBJECT_TYPE_SHADER_MODULE, raw_module, label.c_str());

  VkComputePipelineCreateInfo pipeline_info{};
  pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = raw_module;
  pipeline_info.stage.pName = "main";
  pipeline_info.layout = raw_layout;
  VkPipeline raw_pipeline = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateComputePipelines(device, context.pipeline_cache(), 1, &pipeline_info, context.allocator(), &raw_pipeline));
  pipeline_ = UniquePipeline(device, raw_pipeline, context.allocator());
  context.set_name(VK_OBJECT_TYPE_PIPELINE, raw_pipeline, label.c_str());
}

}  // namespace sp::vk
