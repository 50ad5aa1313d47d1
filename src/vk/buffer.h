// A VkBuffer with its own VkDeviceMemory (soundpaint makes a handful of large
// allocations, so no sub-allocator).
#pragma once

#include <cstddef>
#include <string>
#include <utility>

#include <vulkan/vulkan.h>

#include "vk/context.h"
#include "vk/handle.h"

namespace sp::vk {

enum class MemoryUsage {
  DeviceLocal,  // GPU only; fill with upload() or GPU writes
  HostVisible,  // persistently mapped, host-coherent (device-local if possible): small per-step data
  Readback,     // persistently mapped, host-cached if possible: GPU -> CPU copies
};

class Buffer {
 public:
  Buffer() = default;
  // size > 0. Throws sp::Exception (Vulkan, or LimitExceeded when larger than
  // the device allows). `name` becomes the debug name.
  Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory, const char* name);

  Buffer(Buffer&& other) noexcept
      : memory_(std::move(other.memory_)),
        buffer_(std::move(other.buffer_)),
        size_(std::exchange(other.size_, 0)),
        mapped_(std::exchange(other.mapped_, nullptr)) {}
  Buffer& operator=(Buffer&& other) noexcept {
    if (this != &other) {
      buffer_ = std::move(other.buffer_);  // the buffer goes before its memory
      memory_ = std::move(other.memory_);
      size_ = std::exchange(other.size_, 0);
      mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
  }

  VkBuffer get() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }  // null for DeviceLocal
  explicit operator bool() const { return static_cast<bool>(buffer_); }

 private:
  // Declared memory first so that the buffer is destroyed before the memory
  // bound to it.
  UniqueMemory memory_;
  UniqueBuffer buffer_;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

// Allocates device memory meeting `requirements`, with all `required` and
// preferably the `preferred` property flags, debug-named "<name> memory".
// Out of memory is sp::Exception(LimitExceeded) naming `name` and the size;
// other failures are ErrorCode::Vulkan. Shared by buffers and images.
UniqueMemory allocate_memory(const Context& context, const VkMemoryRequirements& requirements,
                             VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred, const std::string& name);

// Copies `bytes` into `destination` at `offset` through a staging buffer
// (or directly if it is mapped) and waits. Not for the hot path. An unmapped
// (DeviceLocal) destination needs VK_BUFFER_USAGE_TRANSFER_DST_BIT; a mapped
// one must not be in use by pending GPU work. Throws sp::Exception
// (InvalidArgument when the range exceeds the buffer, Vulkan on failure).
void upload(Context& context, const Buffer& destination, const void* bytes, VkDeviceSize size, VkDeviceSize offset = 0);

// Copies `size` bytes at `offset` from `source` into `out` and waits, after
// all work submitted earlier on the context's queue. An unmapped (DeviceLocal)
// source needs VK_BUFFER_USAGE_TRANSFER_SRC_BIT. Throws like upload().
void download(Context& context, const Buffer& source, void* out, VkDeviceSize size, VkDeviceSize offset = 0);

// Records vkCmdUpdateBuffer calls writing `size` bytes at `offset`: the
// bytes are copied into the command buffer now, so the caller may reuse
// them at once and command buffers of several frames in flight never share
// a staging area. For small or occasional data (a step's inputs, a moved
// door's BVH entries). Outside a render pass; offset and size multiples of
// 4; the caller orders it against other accesses with barriers.
void record_update(VkCommandBuffer cmd, const Buffer& destination, VkDeviceSize offset, const void* bytes,
                   VkDeviceSize size);

}  // namespace sp::vk
