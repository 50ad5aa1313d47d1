#include "sp_types.h"
#include "vk/compute_pipeline.h"

#include <string>
#include <vector>

#include "soundpaint/result.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::vk {

StorageBindings::StorageBindings(const Context& context, std::uint32_t binding_count, const char* name,
                                 std::uint32_t texel_binding_count) {
  const std::string label = name != nullptr ? name : "storage bindings";
  if (binding_count == 0) throw Exception(ErrorCode::InvalidArgument, label + ": needs at least one binding");

  std::vector<VkDescriptorSetLayoutBinding> bindings(binding_count);
  for (std::uint32_t i = 0; i < binding_count; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    // Vertex and fragment too: the indicator drawing pass reads its buffer
    // through a set of the same layout.
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  for (std::uint32_t i = 0; i < texel_binding_count; ++i) {
    VkDescriptorSetLayoutBinding texels{};
    texels.binding = binding_count + i;
    texels.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    texels.descriptorCount = 1;
    texels.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    bindings.push_back(texels);
  }
  layout_ = create_descriptor_set_layout(context, bindings, (label + " layout").c_str());
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, binding_count},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, texel_binding_count}};
  pool_ = create_descriptor_pool(context, sizes, 1, (label + " pool").c_str());
  set_ = allocate_descriptor_set(context, pool_.get(), layout_.get(), label.c_str());
}

void StorageBindings::bind(const Context& context, std::uint32_t binding, const Buffer& buffer) {
  bind(context, binding, buffer.get());
}

void StorageBindings::bind(const Context& context, std::uint32_t binding, VkBuffer buffer, VkDeviceSize offset,
                           VkDeviceSize range) {
  write_descriptor(context, set_, binding, VkDescriptorBufferInfo{buffer, offset, range});
}

void StorageBindings::bind(const Context& context, std::uint32_t binding, VkBufferView view) {
  write_descriptor(context, set_, binding, view);
}

ComputePipeline::ComputePipeline(const Context& context, std::span<const std::uint32_t> spirv,
                                 VkDescriptorSetLayout set_layout, std::uint32_t push_constant_bytes, const char* name,
                                 std::span<const std::uint32_t> specialization) {
  const std::string label = name != nullptr ? name : "compute pipeline";
  // Only needed until the pipeline exists.
  const UniqueShaderModule shader = create_shader_module(context, spirv, label.c_str());
  layout_ = create_pipeline_layout(context, {&set_layout, 1}, VK_SHADER_STAGE_COMPUTE_BIT, push_constant_bytes,
                                   (label + " layout").c_str());

  VkComputePipelineCreateInfo pipeline_info{};
  pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = shader.get();
  pipeline_info.stage.pName = "main";
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (std::size_t i = 0; i < entries.size(); ++i)
    entries[i] = {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i * sizeof(std::uint32_t)),
                  sizeof(std::uint32_t)};
  const VkSpecializationInfo specialization_info{static_cast<std::uint32_t>(entries.size()), entries.data(),
                                                 specialization.size_bytes(), specialization.data()};
  if (!specialization.empty()) pipeline_info.stage.pSpecializationInfo = &specialization_info;
  pipeline_info.layout = layout_.get();
  VkPipeline raw_pipeline = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateComputePipelines(context.device(), context.pipeline_cache(), 1, &pipeline_info,
                                       context.allocator(), &raw_pipeline));
  pipeline_ = UniquePipeline(context.device(), raw_pipeline, context.allocator());
  context.set_name(VK_OBJECT_TYPE_PIPELINE, raw_pipeline, label.c_str());
}

}  // namespace sp::vk
