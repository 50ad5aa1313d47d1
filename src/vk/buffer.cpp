#include "sp_types.h"
#include "vk/buffer.h"

#include <algorithm>
#include <stdexcept>
#include <cstring>
#include <string>
#include <vector>

#include "soundpaint/result.h"
#include "vk/barriers.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::vk {
namespace {

struct MemoryFlags {
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
};

MemoryFlags memory_flags(MemoryUsage usage) {
  switch (usage) {
    case MemoryUsage::DeviceLocal:
      return {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0};
    case MemoryUsage::HostVisible:
      // Coherent: host writes need no flush before the next submission.
      return {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT};
    case MemoryUsage::Readback:
      // Coherent too (no invalidate before reads); cached makes those reads fast.
      return {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
              VK_MEMORY_PROPERTY_HOST_CACHED_BIT};
  }
  return {};
}

void check_range(const Buffer& buffer, VkDeviceSize size, VkDeviceSize offset, const char* what) {
  if (!buffer || offset > buffer.size() || size > buffer.size() - offset) {
    throw Exception(ErrorCode::InvalidArgument, std::string(what) + ": " + std::to_string(size) + " bytes at offset " +
                                                    std::to_string(offset) + " exceed the buffer's " +
                                                    std::to_string(buffer.size()) + " bytes");
  }
}

}  // namespace

Buffer::Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
               const char* name)
    : size_(size) {
  const std::string label = name != nullptr ? name : "buffer";
  if (size == 0) throw Exception(ErrorCode::InvalidArgument, label + ": a buffer needs at least one byte");
  const VkDeviceSize max_range = context.properties().limits.maxStorageBufferRange;
  if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) != 0 && size > max_range) {
    throw Exception(ErrorCode::LimitExceeded, label + ": " + std::to_string(size) +
                                                  " bytes exceeds the device's maxStorageBufferRange of " +
                                                  std::to_string(max_range) + " bytes");
  }
  const VkDevice device = context.device();

  VkBufferCreateInfo buffer_info{};
  buffer_info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  buffer_info.size = size;
  buffer_info.usage = usage;
  // A host running the simulation on an async compute queue draws from the
  // same buffers on its graphics queue: shared, no ownership transfers.
  const std::vector<std::uint32_t>& families = context.sharing_families();
  if (families.size() > 1) {
    buffer_info.sharingMode = VK_SHARING_MODE_CONCURRENT;
    buffer_info.queueFamilyIndexCount = static_cast<std::uint32_t>(families.size());
    buffer_info.pQueueFamilyIndices = families.data();
  } else {
    buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  }
  buffer_ = create_object<UniqueBuffer>(context, vkCreateBuffer, buffer_info, VK_OBJECT_TYPE_BUFFER, label.c_str());
  const VkBuffer raw_buffer = buffer_.get();

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device, raw_buffer, &requirements);
  const MemoryFlags flags = memory_flags(memory);
  memory_ = allocate_memory(context, requirements, flags.required, flags.preferred, label);
  const VkDeviceMemory raw_memory = memory_.get();

  SP_VK_CHECK(vkBindBufferMemory(device, raw_buffer, raw_memory, 0));
  // Mapped for the buffer's lifetime; vkFreeMemory unmaps.
  if (memory != MemoryUsage::DeviceLocal) SP_VK_CHECK(vkMapMemory(device, raw_memory, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

UniqueMemory allocate_memory(const Context& context, const VkMemoryRequirements& requirements,
                             VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred, const std::string& name) {
  VkMemoryAllocateInfo allocate{};
  allocate.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = context.memory_type(requirements.memoryTypeBits, required, preferred);
  VkDeviceMemory raw_memory = VK_NULL_HANDLE;
  const VkResult result = vkAllocateMemory(context.device(), &allocate, context.allocator(), &raw_memory);
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) {
    throw Exception(
        Error{ErrorCode::LimitExceeded,
              name + ": cannot allocate " + std::to_string(requirements.size) + " bytes (" + result_name(result) + ")",
              static_cast<int>(result)});
  }
  SP_VK_CHECK(result);
  context.set_name(VK_OBJECT_TYPE_DEVICE_MEMORY, raw_memory, (name + " memory").c_str());
  return UniqueMemory(context.device(), raw_memory, context.allocator());
}

// The host <-> device copies below, with the hazards each barrier resolves.
// All memory here is host-coherent, so no flush or invalidate is needed; the
// barriers only order device work and make device writes visible.

void upload(Context& context, const Buffer& destination, const void* bytes, VkDeviceSize size, VkDeviceSize offset) {
  check_range(destination, size, offset, "upload");
  if (size == 0) return;
  if (destination.mapped() != nullptr) {
    // Host writes before a vkQueueSubmit are visible to the work it submits.
    std::memcpy(static_cast<std::byte*>(destination.mapped()) + offset, bytes, size);
    return;
  }
  Buffer staging(context, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::HostVisible, "upload staging");
  std::memcpy(staging.mapped(), bytes, size);
  context.submit_and_wait([&](VkCommandBuffer cmd) {
    // WAR/WAW: work submitted earlier that still reads or writes the
    // destination finishes before the copy overwrites it.
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkBufferCopy region{0, offset, size};
    vkCmdCopyBuffer(cmd, staging.get(), destination.get(), 1, &region);
    // RAW: later work of any kind (shader reads, indirect arguments, copies)
    // sees the copied bytes.
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  });
}

void download(Context& context, const Buffer& source, void* out, VkDeviceSize size, VkDeviceSize offset) {
  check_range(source, size, offset, "download");
  if (size == 0) return;
  if (source.mapped() != nullptr) {
    context.submit_and_wait([&](VkCommandBuffer cmd) {
      // RAW (device -> host): writes by earlier submissions become visible to
      // host reads; waiting for their fence alone does not do that.
      memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    std::memcpy(out, static_cast<const std::byte*>(source.mapped()) + offset, size);
    return;
  }
  Buffer staging(context, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "download staging");
  context.submit_and_wait([&](VkCommandBuffer cmd) {
    // RAW: shader or transfer writes by earlier work land before the copy reads them.
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    const VkBufferCopy region{offset, 0, size};
    vkCmdCopyBuffer(cmd, source.get(), staging.get(), 1, &region);
    // RAW (device -> host): the copy's writes become visible to the memcpy below.
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                   VK_ACCESS_2_HOST_READ_BIT);
  });
  std::memcpy(out, staging.mapped(), size);
}

void record_update(VkCommandBuffer cmd, const Buffer& destination, VkDeviceSize offset, const void* bytes,
                   VkDeviceSize size) {
  check_range(destination, size, offset, "record_update");
  if (offset % 4 != 0 || size % 4 != 0) throw std::logic_error("record_update: offset and size must be multiples of 4");
  // vkCmdUpdateBuffer takes at most 65536 bytes per call.
  constexpr VkDeviceSize kMaxUpdate = 65536;
  const auto* data = static_cast<const std::byte*>(bytes);
  for (VkDeviceSize done = 0; done < size; done += kMaxUpdate) {
    const VkDeviceSize chunk = std::min(kMaxUpdate, size - done);
    vkCmdUpdateBuffer(cmd, destination.get(), offset + done, chunk, data + done);
  }
}

}  // namespace sp::vk
