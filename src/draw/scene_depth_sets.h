// Descriptor sets (set 1 of the clipping indicator pipeline) that let the
// indicator pass sample the scene's depth: one per depth image view the
// frames draw over, made once, kept until cleared.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "vk/context.h"
#include "vk/handle.h"

namespace sp::draw {

class SceneDepthSets {
 public:
  // Room for `capacity` views. Throws sp::Exception.
  SceneDepthSets(const vk::Context& context, std::uint32_t capacity);

  VkDescriptorSetLayout layout() const { return layout_.get(); }

  // A set sampling `view` (a depth aspect, single-sample image in
  // VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL when drawn with). Throws
  // sp::Exception(LimitExceeded) past the capacity.
  VkDescriptorSet add(VkImageView view);

  // Frees every set. Not while a command buffer using one is pending.
  void clear();


 private:
  const vk::Context* context_ = nullptr;
  std::uint32_t capacity_ = 0;
  vk::UniqueSampler sampler_;
  vk::UniqueDescriptorSetLayout layout_;
  vk::UniqueDescriptorPool pool_;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace sp::draw
