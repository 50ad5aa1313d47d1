#include "draw/scene_depth_sets.h"

#include <string>

#include "soundpaint/result.h"
#include "vk/vk_check.h"

namespace sp::draw {

SceneDepthSets::SceneDepthSets(const vk::Context& context, std::uint32_t capacity)
    : context_(&context), capacity_(capacity) {
  const VkDevice device = context.device();
  // Depth is read texel by texel (texelFetch): no filtering, no mips.
  VkSamplerCreateInfo sampler_info{};
  sampler_info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  sampler_info.magFilter = VK_FILTER_NEAREST;
  sampler_info.minFilter = VK_FILTER_NEAREST;
  sampler_info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sampler_info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler raw_sampler = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateSampler(device, &sampler_info, context.allocator(), &raw_sampler));
  sampler_ = vk::UniqueSampler(device, raw_sampler, context.allocator());
  context.set_name(VK_OBJECT_TYPE_SAMPLER, raw_sampler, "scene depth sampler");

  VkDescriptorSetLayoutBinding binding{};
  binding.binding = 0;
  binding.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  binding.descriptorCount = 1;
  binding.stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
  VkDescriptorSetLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  layout_info.bindingCount = 1;
  layout_info.pBindings = &binding;
  VkDescriptorSetLayout raw_layout = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateDescriptorSetLayout(device, &layout_info, context.allocator(), &raw_layout));
  layout_ = vk::UniqueDescriptorSetLayout(device, raw_layout, context.allocator());
  context.set_name(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, raw_layout, "scene depth layout");

  const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, capacity};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = capacity;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VkDescriptorPool raw_pool = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateDescriptorPool(device, &pool_info, context.allocator(), &raw_pool));
  pool_ = vk::UniqueDescriptorPool(device, raw_pool, context.allocator());
  context.set_name(VK_OBJECT_TYPE_DESCRIPTOR_POOL, raw_pool, "scene depth pool");
}

VkDescriptorSet SceneDepthSets::add(VkImageView view) {
  if (view == VK_NULL_HANDLE) throw Exception(ErrorCode::InvalidArgument, "scene depth: the image view is VK_NULL_HANDLE");
  if (sets_.size() >= capacity_)
    throw Exception(ErrorCode::LimitExceeded,
                    "scene depth: at most " + std::to_string(capacity_) + " depth views can be registered at once");
  const VkDescriptorSetLayout layout = layout_.get();
  VkDescriptorSetAllocateInfo set_info{};
  set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  set_info.descriptorPool = pool_.get();
  set_info.descriptorSetCount = 1;
  set_info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  SP_VK_CHECK(vkAllocateDescriptorSets(context_->device(), &set_info, &set));
  const VkDescriptorImageInfo image{sampler_.get(), view, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet write{};
  write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  write.dstSet = set;
  write.dstBinding = 0;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = &image;
  vkUpdateDescriptorSets(context_->device(), 1, &write, 0, nullptr);
  sets_.push_back(set);
  return set;
}

void SceneDepthSets::clear() {
  if (sets_.empty()) return;
  SP_VK_CHECK(vkResetDescriptorPool(context_->device(), pool_.get(), 0));
  sets_.clear();
}

}  // namespace sp::draw
