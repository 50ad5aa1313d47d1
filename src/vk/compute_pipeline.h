// Compute pipelines over one shared descriptor set layout: every kernel of a
// backend sees the same storage-buffer bindings, so one descriptor set serves
// all dispatches of a step.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace sp::vk {

// A descriptor set layout of `binding_count` (> 0) storage buffers (bindings
// 0..n-1, visible to the compute, vertex and fragment stages so the indicator
// drawing pass can share the layout), then `texel_binding_count` uniform
// texel buffers (bindings n.., compute only), its pool and one set.
class StorageBindings {
 public:
  StorageBindings() = default;
  StorageBindings(const Context& context, std::uint32_t binding_count, const char* name,
                  std::uint32_t texel_binding_count = 0);

  // Points binding `binding` at the whole of `buffer`. Not while a command
  // buffer using the set is pending.
  void bind(const Context& context, std::uint32_t binding, const Buffer& buffer);
  // The same for a buffer owned elsewhere, or a part of one.
  void bind(const Context& context, std::uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
            VkDeviceSize range = VK_WHOLE_SIZE);
  // Points texel binding `binding` (counted from the first storage binding)
  // at `view`. Not while a command buffer using the set is pending.
  void bind(const Context& context, std::uint32_t binding, VkBufferView view);

  VkDescriptorSetLayout layout() const { return layout_.get(); }
  VkDescriptorSet set() const { return set_; }

 private:
  UniqueDescriptorSetLayout layout_;
  UniqueDescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

class ComputePipeline {
 public:
  ComputePipeline() = default;
  // `spirv` is the embedded SPIR-V; push constants (if any) are visible to
  // the compute stage; `specialization[i]` is the value of the shader's
  // 32-bit specialization constant i. Throws sp::Exception on failure.
  ComputePipeline(const Context& context, std::span<const std::uint32_t> spirv, VkDescriptorSetLayout set_layout,
                  std::uint32_t push_constant_bytes, const char* name,
                  std::span<const std::uint32_t> specialization = {});

  VkPipeline get() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }

 private:
  UniquePipelineLayout layout_;
  UniquePipeline pipeline_;
};

}  // namespace sp::vk
