#include "gpu/gpu_resources.h"

#include <algorithm>
#include <string>

#include "emit.comp.spv.h"
#include "gpu/gpu_layout_checks.h"
#include "prepare.comp.spv.h"
#include "resolve.comp.spv.h"
#include "sim/step_plan.h"
#include "trace.comp.spv.h"

namespace sp::gpu {
namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
constexpr VkBufferUsageFlags kTransfer = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

template <class T>
VkDeviceSize bytes(std::uint64_t count) {
  return static_cast<VkDeviceSize>(std::max<std::uint64_t>(count, 1) * sizeof(T));
}

template <class T>
vk::Buffer upload_array(vk::Context& context, const std::vector<T>& data, const char* name) {
  vk::Buffer buffer(context, bytes<T>(data.size()), kStorage | kTransfer, vk::MemoryUsage::DeviceLocal, name);
  if (!data.empty()) vk::upload(context, buffer, data.data(), data.size() * sizeof(T));
  return buffer;
}

}  // namespace

GpuResources::GpuResources(vk::Context& context, const World& world) {
  const Config& config = world.config;
  max_rays = std::max<std::uint32_t>(1, config.ray_budget);
  // A ray casts at most twice per interaction (forward + backcast) plus a
  // final forward cast, and leaves at most one indicator per cast.
  iterations = 2 * config.max_bounces + 1;
  capture_capacity = max_rays * iterations;
  ring_capacity = config.max_indicators;
  layer_count = static_cast<std::uint32_t>(world.layer_names.size());
  const std::uint32_t max_groups = context.properties().limits.maxComputeWorkGroupCount[0];
  if ((std::uint64_t{max_rays} + SP_WORKGROUP_SIZE - 1) / SP_WORKGROUP_SIZE > max_groups)
    throw Exception(ErrorCode::LimitExceeded, "ray_budget " + std::to_string(config.ray_budget) +
                                                  " needs more workgroups than the device's limit of " +
                                                  std::to_string(max_groups));

  nodes = upload_array(context, world.bvh.nodes, "bvh nodes");
  triangles = upload_array(context, world.bvh.triangles, "bvh triangles");
  layers = upload_array(context, make_layer_table(world), "layer acoustics");

  step_input = vk::Buffer(context,
                          sizeof(shader::StepInput) + bytes<shader::StepSource>(world.sources.size()),
                          kStorage, vk::MemoryUsage::HostVisible, "step input");
  rays = vk::Buffer(context, bytes<shader::RayState>(max_rays), kStorage, vk::MemoryUsage::DeviceLocal, "rays");
  hits = vk::Buffer(context, bytes<shader::HitInfo>(max_rays), kStorage, vk::MemoryUsage::DeviceLocal, "hits");
  queues = vk::Buffer(context, bytes<std::uint32_t>(2ull * max_rays), kStorage, vk::MemoryUsage::DeviceLocal,
                      "ray queues");
  control = vk::Buffer(context, sizeof(shader::Control), kStorage | kTransfer | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                       vk::MemoryUsage::DeviceLocal, "control");
  ring = vk::Buffer(context, bytes<shader::Indicator>(ring_capacity), kStorage | kTransfer |
                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vk::MemoryUsage::DeviceLocal, "indicator ring");
  capture = vk::Buffer(context, bytes<shader::Indicator>(capture_capacity), kStorage | kTransfer,
                       vk::MemoryUsage::DeviceLocal, "indicator capture");
  // per layer: 4 step counters, then 4 (lo, hi) totals
  counters = vk::Buffer(context, bytes<std::uint32_t>(layer_count * SP_COUNTERS_PER_LAYER * 3), kStorage | kTransfer,
                        vk::MemoryUsage::DeviceLocal, "layer counters");
  control_readback = vk::Buffer(context, sizeof(shader::Control), kTransfer, vk::MemoryUsage::Readback,
                                "control readback");

  shader::Control initial{};
  initial.draw_vertex_count = 6;  // one quad per indicator instance, as two triangles
  vk::upload(context, control, &initial, sizeof initial);
  std::vector<std::uint32_t> zeros(layer_count * SP_COUNTERS_PER_LAYER * 3, 0);
  if (!zeros.empty()) vk::upload(context, counters, zeros.data(), zeros.size() * sizeof(std::uint32_t));

  bindings = vk::StorageBindings(context, SP_BINDING_COUNT, "soundpaint set");
  const vk::Buffer* bound[SP_BINDING_COUNT] = {&nodes, &triangles, &layers, &step_input, &rays,   &hits,
                                               &queues, &control,  &ring,   &capture,    &counters};
  for (std::uint32_t b = 0; b < SP_BINDING_COUNT; ++b) bindings.bind(context, b, *bound[b]);

  const auto push = static_cast<std::uint32_t>(sizeof(shader::WavefrontPush));
  kernels.emit = vk::ComputePipeline(context, sp_spirv_emit_comp, bindings.layout(), push, "emit");
  kernels.trace = vk::ComputePipeline(context, sp_spirv_trace_comp, bindings.layout(), push, "trace");
  kernels.resolve = vk::ComputePipeline(context, sp_spirv_resolve_comp, bindings.layout(), push, "resolve");
  kernels.prepare = vk::ComputePipeline(context, sp_spirv_prepare_comp, bindings.layout(), push, "prepare");
}

}  // namespace sp::gpu
