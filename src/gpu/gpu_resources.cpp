#include "gpu/gpu_resources.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "admit.comp.spv.h"
#include "connect.comp.spv.h"
#include "emit.comp.spv.h"
#include "gpu/gpu_layout_checks.h"
#include "vk/objects.h"
#include "sim/world_geometry.h"
#include "sp_admission.h"
#include "sp_draw_types.h"
#include "sp_guide.h"
#include "resolve.comp.spv.h"
#include "sim/step_plan.h"
#include "sp_ring.h"
#include "trace.comp.spv.h"
#include "trace_matter.comp.spv.h"

namespace sp::gpu {
namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
constexpr VkBufferUsageFlags kTransfer = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr VkBufferUsageFlags kTexels = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;

template <class T>
VkDeviceSize bytes(std::uint64_t count) {
  return static_cast<VkDeviceSize>(std::max<std::uint64_t>(count, 1) * sizeof(T));
}

// Lays out the initial contents of several buffers in one staging buffer.
class StagingPlan {
 public:
  // `data` (a std::vector or LargeArray) is read by fill(), later: it must
  // outlive the plan.
  template <class Array>
  void add(const vk::Buffer& destination, const Array& data) {
    const std::size_t bytes = data.size() * sizeof(typename Array::value_type);
    parts_.push_back({&destination, size_, bytes});
    sources_.push_back(data.data());
    size_ += (bytes + 15) / 16 * 16;
  }
  template <class Array>
  void add(const vk::Buffer&, const Array&&) = delete;  // a temporary would dangle

  void fill(vk::Context& context, GpuResources& r) {
    r.initial_staging = vk::Buffer(context, std::max<VkDeviceSize>(size_, 16), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                   vk::MemoryUsage::HostVisible, "initial contents staging");
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      if (parts_[i].size == 0) continue;
      std::memcpy(static_cast<std::byte*>(r.initial_staging.mapped()) + parts_[i].staging_offset, sources_[i],
                  parts_[i].size);
      r.initial_copies.push_back(parts_[i]);
    }
  }

 private:
  std::vector<GpuResources::InitialCopy> parts_;
  std::vector<const void*> sources_;
  VkDeviceSize size_ = 0;
};

// The admission's buffer: histograms and plan, the order bitmap and its
// running counts, and the list of tied indicators (sp_ring.h).
std::uint64_t admission_words(const ConfigSizes& sizes) {
  const std::uint64_t order_words = SP_ORDER_WORDS(std::uint64_t{sizes.max_rays}, std::uint64_t{sizes.iterations});
  return SP_ADMISSION_BUFFER_SIZE + 2 * order_words + sizes.capture_capacity;
}

struct SizedSpec {
  VkDeviceSize bytes;
  VkBufferUsageFlags usage;
  const char* name;
};

SizedSpec sized_spec(const SizedBuffer& buffer, const ConfigSizes& s) {
  switch (buffer.binding) {
    case SP_BINDING_RAYS:
      return {bytes<shader::RayState>(s.max_rays), kStorage, "rays"};
    case SP_BINDING_HITS:
      return {bytes<shader::CastResult>(s.max_rays), kStorage, "hits"};
    case SP_BINDING_QUEUES:
      return {bytes<std::uint32_t>(2ull * s.max_rays), kStorage, "ray queues"};
    case SP_BINDING_RING:
      return {bytes<shader::Indicator>(s.ring_capacity), kStorage | kTransfer | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
              "indicator ring"};
    case SP_BINDING_CAPTURE:
      return {bytes<shader::Indicator>(s.capture_capacity), kStorage | kTransfer, "indicator capture"};
    case SP_BINDING_ADMISSION:
      return {bytes<std::uint32_t>(admission_words(s)), kStorage | kTransfer, "ring admission histogram"};
    case SP_BINDING_CONNECT:
      return {bytes<std::uint32_t>(s.capture_capacity), kStorage, "connect queue"};
    default:
      throw std::logic_error("binding " + std::to_string(buffer.binding) + " is not sized by the config");
  }
}

}  // namespace

const SizedBuffer kSizedBuffers[kSizedBufferCount] = {
    {&GpuResources::rays, SP_BINDING_RAYS},
    {&GpuResources::hits, SP_BINDING_HITS},
    {&GpuResources::queues, SP_BINDING_QUEUES},
    {&GpuResources::ring, SP_BINDING_RING},
    {&GpuResources::capture, SP_BINDING_CAPTURE},
    {&GpuResources::admission, SP_BINDING_ADMISSION},
    {&GpuResources::connect_queue, SP_BINDING_CONNECT},
};

std::uint32_t kernel_workgroup_size(const vk::Context& context, std::uint32_t max_rays) {
  const std::uint32_t subgroup = std::max<std::uint32_t>(1, context.subgroup_size());
  const std::uint32_t requested = context.requested_kernels().workgroup_size;
  const VkPhysicalDeviceLimits& limits = context.properties().limits;
  if (requested != 0) {
    const std::uint32_t most = std::min(limits.maxComputeWorkGroupSize[0], limits.maxComputeWorkGroupInvocations);
    if (requested % subgroup != 0 || requested > most)
      throw Exception(ErrorCode::InvalidArgument, "workgroup_size " + std::to_string(requested) +
                                                      " must be a multiple of the device's subgroup width " +
                                                      std::to_string(subgroup) + " and at most " +
                                                      std::to_string(most));
    return requested;
  }
  if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU || subgroup >= SP_WORKGROUP_SIZE)
    return SP_WORKGROUP_SIZE;
  // Wider only when the budget's rays would need more workgroups than the
  // device dispatches.
  std::uint32_t width = subgroup;
  while (width < SP_WORKGROUP_SIZE && workgroups_for(max_rays, width) > limits.maxComputeWorkGroupCount[0]) width *= 2;
  return width;
}

std::uint32_t inline_admission_max(const vk::Context& context) {
  const std::uint32_t requested = context.requested_kernels().inline_admission_max;
  if (requested != 0) return requested;
  return context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? std::numeric_limits<std::uint32_t>::max()
                                                                        : SP_WORKGROUP_SIZE;
}

std::uint32_t connect_groups_max(const vk::Context& context) {
  const std::uint32_t requested = context.requested_kernels().connect_groups_max;
  if (requested != 0) return requested;
  if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return std::numeric_limits<std::uint32_t>::max();
  return 2 * std::max(1u, std::thread::hardware_concurrency());
}

namespace {

// RGBA32UI texels of a node and of a triangle (BvhNode, BvhTriangle).
constexpr std::size_t kTexelBytes = 16;
constexpr std::size_t kNodeTexels = sizeof(shader::BvhNode) / kTexelBytes;
constexpr std::size_t kTriangleTexels = sizeof(shader::BvhTriangle) / kTexelBytes;
static_assert(sizeof(shader::BvhNode) % kTexelBytes == 0 && sizeof(shader::BvhTriangle) % kTexelBytes == 0);

std::size_t texel_limit(const vk::Context& context) {
  std::size_t limit = context.properties().limits.maxTexelBufferElements;
  const std::uint32_t requested = context.requested_kernels().max_texel_buffer_elements;
  if (requested != 0) limit = std::min<std::size_t>(limit, requested);
  // texelFetch takes an int.
  return std::min<std::size_t>(limit, std::numeric_limits<std::int32_t>::max());
}

// A view of `buffer` as texels: all of it when `whole`, else as many texels
// as the limit allows (a view the kernels never read, for the binding).
vk::UniqueBufferView texel_view(const vk::Context& context, const vk::Buffer& buffer, bool whole, const char* name) {
  const VkDeviceSize range =
      whole ? VK_WHOLE_SIZE : std::min<VkDeviceSize>(buffer.size(), texel_limit(context) * kTexelBytes);
  return vk::create_buffer_view(context, buffer.get(), VK_FORMAT_R32G32B32A32_UINT, 0, range, name);
}

}  // namespace

bool bvh_texels_usable(const vk::Context& context, std::size_t nodes, std::size_t triangles) {
  const std::size_t limit = texel_limit(context);
  return nodes <= limit / kNodeTexels && triangles <= limit / kTriangleTexels;
}

ConfigSizes config_sizes(const vk::Context& context, const Config& config, std::uint32_t workgroup_size) {
  ConfigSizes sizes;
  sizes.max_rays = std::max<std::uint32_t>(1, config.ray_budget);
  // A ray casts at most twice per interaction (a closest-hit cast and, when
  // it penetrates, a matter query) plus a final closest-hit cast, and leaves at most one indicator per cast.
  sizes.iterations = 2 * config.max_bounces + 1;
  sizes.capture_capacity = sizes.max_rays * sizes.iterations;
  sizes.ring_capacity = config.max_indicators;
  const std::uint32_t max_groups = context.properties().limits.maxComputeWorkGroupCount[0];
  if (workgroups_for(sizes.max_rays, workgroup_size) > max_groups)
    throw Exception(ErrorCode::LimitExceeded, "ray_budget " + std::to_string(config.ray_budget) +
                                                  " needs more workgroups of " + std::to_string(workgroup_size) +
                                                  " threads than the device's limit of " + std::to_string(max_groups));
  return sizes;
}

VkDeviceSize sized_buffer_bytes(const SizedBuffer& buffer, const ConfigSizes& sizes) {
  return sized_spec(buffer, sizes).bytes;
}

vk::Buffer create_sized_buffer(const vk::Context& context, const SizedBuffer& buffer, const ConfigSizes& sizes) {
  const SizedSpec spec = sized_spec(buffer, sizes);
  return vk::Buffer(context, spec.bytes, spec.usage, vk::MemoryUsage::DeviceLocal, spec.name);
}

GpuResources::GpuResources(vk::Context& context, const World& world, std::uint32_t sources)
    : workgroup_size(kernel_workgroup_size(context, std::max<std::uint32_t>(1, world.config.ray_budget))) {
  const ConfigSizes sized = config_sizes(context, world.config, workgroup_size);
  max_rays = sized.max_rays;
  iterations = sized.iterations;
  capture_capacity = sized.capture_capacity;
  ring_capacity = sized.ring_capacity;
  layer_count = static_cast<std::uint32_t>(world.layer_names.size());

  // Moving parts may force a rebuild, whose node count can differ; a binary
  // tree over n triangles never has more than 2n - 1 nodes.
  const std::size_t triangle_count = world.geometry->bvh.triangles.size();
  node_capacity = static_cast<std::uint32_t>(world.instance_names.empty()
                                                 ? world.geometry->bvh.nodes.size()
                                                 : std::max(world.geometry->bvh.nodes.size(), 2 * triangle_count - 1));
  source_capacity = sources;
  const std::vector<shader::LayerAcoustics> layer_table = make_layer_table(world);
  nodes = vk::Buffer(context, bytes<shader::BvhNode>(node_capacity), kStorage | kTexels | kTransfer,
                     vk::MemoryUsage::DeviceLocal, "bvh nodes");
  triangles = vk::Buffer(context, bytes<shader::BvhTriangle>(triangle_count), kStorage | kTexels | kTransfer,
                         vk::MemoryUsage::DeviceLocal, "bvh triangles");
  const bool bvh_texels = bvh_texels_usable(context, node_capacity, triangle_count);
  node_texels = texel_view(context, nodes, bvh_texels, "bvh node texels");
  triangle_texels = texel_view(context, triangles, bvh_texels, "bvh triangle texels");
  // Diffraction off: one zero entry, which the kernels never read.
  const std::vector<shader::TriangleEdges> edge_table =
      world.geometry->bvh.edges.empty() ? std::vector<shader::TriangleEdges>(1) : world.geometry->bvh.edges;
  edges = vk::Buffer(context, bytes<shader::TriangleEdges>(edge_table.size()), kStorage | kTransfer,
                     vk::MemoryUsage::DeviceLocal, "exposed edges");
  edge_count = world.geometry->bvh.edges.size();
  layers = vk::Buffer(context, bytes<shader::LayerAcoustics>(layer_table.size()), kStorage | kTransfer,
                      vk::MemoryUsage::DeviceLocal, "layer acoustics");
  step_input = vk::Buffer(context, sizeof(shader::StepInput) + bytes<shader::StepSource>(source_capacity),
                          kStorage | kTransfer, vk::MemoryUsage::DeviceLocal, "step input");
  for (const SizedBuffer& buffer : kSizedBuffers) this->*buffer.member = create_sized_buffer(context, buffer, sized);
  control = vk::Buffer(context, sizeof(shader::Control), kStorage | kTransfer | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                       vk::MemoryUsage::DeviceLocal, "control");
  // per layer: SP_COUNTERS_PER_LAYER step counters, then as many (lo, hi) totals
  counters = vk::Buffer(context, bytes<std::uint32_t>(layer_count * SP_COUNTERS_PER_LAYER * 3), kStorage | kTransfer,
                        vk::MemoryUsage::DeviceLocal, "layer counters");
  guide = vk::Buffer(context, bytes<std::uint32_t>(std::uint64_t{source_capacity} * SP_GUIDE_STRIDE),
                     kStorage | kTransfer, vk::MemoryUsage::DeviceLocal, "source guides");
  control_readback =
      vk::Buffer(context, sizeof(shader::Control), kTransfer, vk::MemoryUsage::Readback, "control readback");

  std::vector<shader::Control> initial(1);
  initial[0].draw_vertex_count = SP_INDICATOR_QUAD_VERTICES;  // one quad per indicator instance
  std::vector<std::uint32_t> zeros(layer_count * SP_COUNTERS_PER_LAYER * 3, 0);
  const std::vector<std::uint32_t> empty_admission(admission_words(sized), 0u);
  const std::vector<std::uint32_t> empty_guides(
      std::max<std::size_t>(1, std::size_t{source_capacity} * SP_GUIDE_STRIDE), 0u);
  StagingPlan staging;
  staging.add(nodes, world.geometry->bvh.nodes);
  staging.add(triangles, world.geometry->bvh.triangles);
  staging.add(layers, layer_table);
  staging.add(edges, edge_table);
  staging.add(control, initial);
  staging.add(counters, zeros);
  staging.add(admission, empty_admission);
  staging.add(guide, empty_guides);
  staging.fill(context, *this);

  bindings = vk::StorageBindings(context, SP_BINDING_COUNT, "soundpaint set", SP_TEXEL_BINDING_COUNT);
  const vk::Buffer* bound[SP_BINDING_COUNT] = {&nodes,    &triangles, &layers,  &step_input, &rays,
                                               &hits,     &queues,    &control, &ring,       &capture,
                                               &counters, &admission, &edges,   &guide,      &connect_queue};
  for (std::uint32_t b = 0; b < SP_BINDING_COUNT; ++b) bindings.bind(context, b, *bound[b]);
  bindings.bind(context, SP_BINDING_NODE_TEXELS, node_texels.get());
  bindings.bind(context, SP_BINDING_TRIANGLE_TEXELS, triangle_texels.get());

  static_assert(SP_SPEC_WORKGROUP_SIZE == 0 && SP_SPEC_GROUP_WIDTH == 1 && SP_SPEC_ADMIT_INLINE_MAX == 2 &&
                    SP_SPEC_BVH_TEXELS == 3 && SP_SPEC_CONNECT_GROUPS_MAX == 4 && SP_SPEC_DIFFRACTION == 5,
                "the kernels' specialization constants, in order");
  kernel_specialization = {workgroup_size,
                           workgroup_size,
                           inline_admission_max(context),
                           bvh_texels ? VK_TRUE : VK_FALSE,
                           connect_groups_max(context),
                           world.config.diffraction.enabled ? VK_TRUE : VK_FALSE};
  auto kernel = [&](std::span<const std::uint32_t> spirv, const char* name) {
    return vk::ComputePipeline(context, spirv, bindings.layout(), sizeof(shader::WavefrontPush), name,
                               kernel_specialization);
  };
  kernels.emit = kernel(sp_spirv_emit_comp, "emit");
  kernels.trace = kernel(sp_spirv_trace_comp, "trace");
  kernels.trace_matter = kernel(sp_spirv_trace_matter_comp, "trace_matter");
  kernels.resolve = make_resolve_kernel(context, *this, resolve_diffracts());
  kernels.connect = kernel(sp_spirv_connect_comp, "connect");
  kernels.admit = kernel(sp_spirv_admit_comp, "admit");
}

vk::ComputePipeline make_resolve_kernel(const vk::Context& context, const GpuResources& resources, bool diffraction) {
  std::array<std::uint32_t, kKernelSpecializationCount> specialization = resources.kernel_specialization;
  specialization[SP_SPEC_DIFFRACTION] = diffraction ? VK_TRUE : VK_FALSE;
  return vk::ComputePipeline(context, sp_spirv_resolve_comp, resources.bindings.layout(), sizeof(shader::WavefrontPush),
                             diffraction ? "resolve (diffraction)" : "resolve", specialization);
}

}  // namespace sp::gpu
