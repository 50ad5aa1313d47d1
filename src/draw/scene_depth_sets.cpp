#include "draw/scene_depth_sets.h"

#include <string>

#include "soundpaint/result.h"
#include "sp_types.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::draw {

SceneDepthSets::SceneDepthSets(const vk::Context& context, std::uint32_t capacity)
    : context_(&context), capacity_(capacity) {
  // Depth is read texel by texel (texelFetch): no filtering, no mips.
  VkSamplerCreateInfo sampler_info{};
  sampler_info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  sampler_info.magFilter = VK_FILTER_NEAREST;
  sampler_info.minFilter = VK_FILTER_NEAREST;
  sampler_info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sampler_info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sampler_ = vk::create_object<vk::UniqueSampler>(context, vkCreateSampler, sampler_info, VK_OBJECT_TYPE_SAMPLER,
                                                  "scene depth sampler");

  VkDescriptorSetLayoutBinding binding{};
  binding.binding = 0;
  binding.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  binding.descriptorCount = 1;
  binding.stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  layout_ = vk::create_descriptor_set_layout(context, {&binding, 1}, "scene depth layout");
  pool_ = vk::create_descriptor_pool(context, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, capacity, capacity,
                                     "scene depth pool");
}

VkDescriptorSet SceneDepthSets::add(VkImageView view) {
  if (view == VK_NULL_HANDLE)
    throw Exception(ErrorCode::InvalidArgument, "scene depth: the image view is VK_NULL_HANDLE");
  if (sets_.size() >= capacity_)
    throw Exception(ErrorCode::LimitExceeded,
                    "scene depth: at most " + std::to_string(capacity_) + " depth views can be registered at once");
  const VkDescriptorSet set = vk::allocate_descriptor_set(*context_, pool_.get(), layout_.get(), "scene depth");
  vk::write_descriptor(*context_, set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                       VkDescriptorImageInfo{sampler_.get(), view, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL});
  sets_.push_back(set);
  return set;
}

void SceneDepthSets::clear() {
  if (sets_.empty()) return;
  SP_VK_CHECK(vkResetDescriptorPool(context_->device(), pool_.get(), 0));
  sets_.clear();
}

}  // namespace sp::draw
