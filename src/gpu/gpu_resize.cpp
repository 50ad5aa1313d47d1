#include "gpu/gpu_resize.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "vk/barriers.h"
#include "vk/buffer.h"

namespace sp::gpu {
namespace {

static_assert(offsetof(shader::Control, ring_filled) == offsetof(shader::Control, ring_head) + sizeof(std::uint32_t),
              "the ring's head and fill are written as one pair");

std::size_t index_of(std::uint32_t binding) {
  for (std::size_t i = 0; i < kSizedBufferCount; ++i)
    if (kSizedBuffers[i].binding == binding) return i;
  throw std::logic_error("binding " + std::to_string(binding) + " is not sized by the config");
}

}  // namespace

std::size_t GpuResize::capture_index() { return index_of(SP_BINDING_CAPTURE); }
std::size_t GpuResize::ring_index() { return index_of(SP_BINDING_RING); }

GpuResize::GpuResize(vk::Context& context, const GpuResources& resources, const Config& config, const Bvh& bvh)
    : sizes_(config_sizes(context, config, resources.workgroup_size)) {
  const ConfigSizes now = resources.sizes();
  for (std::size_t i = 0; i < kSizedBufferCount; ++i) {
    const SizedBuffer& buffer = kSizedBuffers[i];
    if (sized_buffer_bytes(buffer, sizes_) == sized_buffer_bytes(buffer, now)) continue;
    buffers_[i] = create_sized_buffer(context, buffer, sizes_);
    replaced_[i] = true;
  }
  // Diffraction switched on where the buffer holds the one zero entry of a
  // world without it: the edges the geometry found, uploaded now into a
  // buffer nothing else uses yet.
  if (config.diffraction.enabled && !bvh.edges.empty() && resources.edge_count != bvh.edges.size()) {
    const VkDeviceSize bytes = bvh.edges.size() * sizeof(shader::TriangleEdges);
    edges_ = vk::Buffer(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        vk::MemoryUsage::DeviceLocal, "exposed edges");
    vk::upload(context, edges_, bvh.edges.data(), bytes);
    edge_count_ = bvh.edges.size();
  }
  diffraction_ = config.diffraction.enabled;
  if (diffraction_ != resources.resolve_diffracts()) resolve_ = make_resolve_kernel(context, resources, diffraction_);
}

std::uint32_t GpuResize::kept_spots(std::uint32_t filled) const { return std::min(filled, sizes_.ring_capacity); }

void GpuResize::record(VkCommandBuffer cmd, const GpuResources& resources, const shader::Control& control,
                       std::span<const shader::LayerAcoustics> layer_table) const {
  // WAR/WAW: the last step's kernels and copies are done with the layers,
  // the ring and the control block before these transfers touch them.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
  // The layer count never changes: the same buffer takes the new acoustics.
  if (!layer_table.empty()) vk::record_update(cmd, resources.layers, 0, layer_table.data(), layer_table.size_bytes());
  // The admission kernel clears only what a step counted: it starts from zeros.
  const std::size_t admission = index_of(SP_BINDING_ADMISSION);
  if (replaced_[admission]) vkCmdFillBuffer(cmd, buffers_[admission].get(), 0, VK_WHOLE_SIZE, 0u);
  if (!replaced_[ring_index()]) return;

  // The ring's slots hold its spots oldest first from head - filled (mod
  // its capacity); the newest `kept` end at the head. They go to slots
  // 0 .. kept - 1 of the new ring, in order, in one or two runs.
  const std::uint32_t capacity = resources.ring_capacity;
  const std::uint32_t kept = kept_spots(std::min(control.ring_filled, capacity));
  constexpr VkDeviceSize kSpot = sizeof(shader::Indicator);
  if (kept > 0) {
    const std::uint32_t first = (control.ring_head % capacity + capacity - kept) % capacity;
    const std::uint32_t before_wrap = std::min(kept, capacity - first);
    const VkBufferCopy runs[2] = {{first * kSpot, 0, before_wrap * kSpot},
                                  {0, before_wrap * kSpot, (kept - before_wrap) * kSpot}};
    vkCmdCopyBuffer(cmd, resources.ring.get(), buffers_[ring_index()].get(), kept > before_wrap ? 2u : 1u, runs);
  }
  const std::uint32_t head_and_fill[2] = {kept % sizes_.ring_capacity, kept};
  vk::record_update(cmd, resources.control, offsetof(shader::Control, ring_head), head_and_fill, sizeof head_and_fill);
  vk::record_update(cmd, resources.control, offsetof(shader::Control, draw_instance_count), &kept, sizeof kept);
}

void GpuResize::commit(vk::Context& context, GpuResources& resources, shader::Control& control) {
  if (replaced_[ring_index()]) {
    const std::uint32_t kept = kept_spots(std::min(control.ring_filled, resources.ring_capacity));
    control.ring_head = kept % sizes_.ring_capacity;
    control.ring_filled = kept;
    control.draw_instance_count = kept;
  }
  for (std::size_t i = 0; i < kSizedBufferCount; ++i) {
    if (!replaced_[i]) continue;
    vk::Buffer& member = resources.*kSizedBuffers[i].member;
    member = std::move(buffers_[i]);  // the old buffer goes: the device is done with it
    resources.bindings.bind(context, kSizedBuffers[i].binding, member);
  }
  if (edges_) {
    resources.edges = std::move(edges_);
    resources.edge_count = edge_count_;
    resources.bindings.bind(context, SP_BINDING_EDGES, resources.edges);
  }
  if (diffraction_ != resources.resolve_diffracts()) {
    resources.kernels.resolve = std::move(resolve_);  // the device is done with the old one
    resources.kernel_specialization[SP_SPEC_DIFFRACTION] = diffraction_ ? VK_TRUE : VK_FALSE;
  }
  resources.max_rays = sizes_.max_rays;
  resources.iterations = sizes_.iterations;
  resources.capture_capacity = sizes_.capture_capacity;
  resources.ring_capacity = sizes_.ring_capacity;
}

}  // namespace sp::gpu
