// The GPU backend's device objects: scene buffers, per-budget ray buffers,
// the indicator ring and capture list, counters, the shared descriptor set
// and the four kernels. Creating them submits nothing (a host's device may
// be borrowed): initial contents wait in a staging buffer for the first
// recorded step (StepEngine) to copy them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "soundpaint/simulation.h"
#include "sp_gpu_types.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "vk/context.h"

namespace sp::gpu {

struct Kernels {
  vk::ComputePipeline emit;
  vk::ComputePipeline trace;
  vk::ComputePipeline trace_matter;
  vk::ComputePipeline resolve;
  vk::ComputePipeline connect;
  vk::ComputePipeline admit;
};

// What the config decides of the buffers' sizes: ray_budget, max_bounces
// and max_indicators.
struct ConfigSizes {
  std::uint32_t max_rays = 0;          // rays per step the buffers hold (== ray_budget, at least 1)
  std::uint32_t iterations = 0;        // wavefront iterations per step (2 * max_bounces + 1)
  std::uint32_t capture_capacity = 0;  // indicators one step can create, worst case
  std::uint32_t ring_capacity = 0;     // max_indicators
};

// Workgroups of `width` threads that `invocations` need: sp_group_count
// (sp_gpu_types.h) in 64 bits, for budgets whose count would overflow 32.
inline std::uint64_t workgroups_for(std::uint64_t invocations, std::uint32_t width) {
  return (invocations + width - 1u) / width;
}

// Threads per workgroup of the simulation's kernels on `context`'s device
// for a budget of `max_rays`: the one ContextSettings asked for; else, on a
// CPU device, its subgroup width (lavapipe runs a workgroup's invocations a
// subgroup at a time on one thread, every branch of them, so a partly
// empty workgroup costs in full, and more workgroups spread over its
// threads), doubled while the budget would need more workgroups than the
// device dispatches, up to SP_WORKGROUP_SIZE; else SP_WORKGROUP_SIZE.
// Throws sp::Exception(InvalidArgument) when the one asked for is not a
// multiple of the subgroup width within the device's limits, naming them.
std::uint32_t kernel_workgroup_size(const vk::Context& context, std::uint32_t max_rays);

// The most spots a step may have for the connect pass's last subgroup to
// admit them itself (shaders/admission_passes.glsl), the two admit
// dispatches then running no group: the one ContextSettings asked for;
// else, on a CPU device, every step (there each dispatch is a thread-pool
// hand-off that costs more than one subgroup's walk over even the 9,000
// spots of a 2,500-ray step: bench/RESULTS.md section 30); else one GPU
// workgroup's worth, SP_WORKGROUP_SIZE (on a GPU one subgroup's walk over
// many spots would cost more than the two dispatches).
std::uint32_t inline_admission_max(const vk::Context& context);

// The most workgroups the connect pass runs: the one ContextSettings asked
// for; else, on a CPU device, two for each of the host's hardware threads
// (lavapipe's pool has a thread for each); else no limit. Fewer groups, each
// of whose subgroups takes a spot a lane in turn, pay on a CPU device:
// there a branch is no jump, so every subgroup runs the code of the last
// one's bookkeeping with its lanes masked off (bench/RESULTS.md section 34).
// A GPU wants a lane for every spot.
std::uint32_t connect_groups_max(const vk::Context& context);

// Whether the walks can read a tree of `nodes` nodes over `triangles`
// triangles from uniform texel buffers (two RGBA32UI texels a node, four a
// triangle): when each fits the device's maxTexelBufferElements (or the
// lower ContextSettings::kernels.max_texel_buffer_elements) and a texel
// index fits GLSL's int. RGBA32UI uniform texel buffers are mandatory in
// Vulkan, so the format needs no check. Otherwise the kernels read the
// storage buffers.
bool bvh_texels_usable(const vk::Context& context, std::size_t nodes, std::size_t triangles);

// Throws sp::Exception(LimitExceeded) when ray_budget needs more
// workgroups of `workgroup_size` threads than the device dispatches.
ConfigSizes config_sizes(const vk::Context& context, const Config& config, std::uint32_t workgroup_size);

struct GpuResources;

// The buffers ConfigSizes sizes, one entry each: GpuResources creates them
// all, Simulator::set_config again those whose size changes (gpu_resize.h).
struct SizedBuffer {
  vk::Buffer GpuResources::*member;
  std::uint32_t binding;  // SP_BINDING_*
};
inline constexpr std::size_t kSizedBufferCount = 7;
extern const SizedBuffer kSizedBuffers[kSizedBufferCount];

// Creates `buffer` for `sizes`: its bytes, usage and name.
vk::Buffer create_sized_buffer(const vk::Context& context, const SizedBuffer& buffer, const ConfigSizes& sizes);
// The bytes `buffer` takes for `sizes`.
VkDeviceSize sized_buffer_bytes(const SizedBuffer& buffer, const ConfigSizes& sizes);

// Specialization constants of the simulation's kernels (SP_SPEC_*).
inline constexpr std::size_t kKernelSpecializationCount = 6;

struct GpuResources {
  // Sizes all buffers for `world`; throws sp::Exception (LimitExceeded when
  // a buffer would exceed the device's storage-buffer range).
  GpuResources(vk::Context& context, const World& world, std::uint32_t source_capacity);
  // initial_copies points into this object.
  GpuResources(const GpuResources&) = delete;
  GpuResources& operator=(const GpuResources&) = delete;

  // The kernels' width (kernel_workgroup_size for the first config): kept
  // by set_config, whose budget must then fit the device's workgroup count.
  std::uint32_t workgroup_size = 0;

  // As ConfigSizes, for the config the buffers were last sized for.
  std::uint32_t max_rays = 0;
  std::uint32_t capture_capacity = 0;
  std::uint32_t ring_capacity = 0;
  std::uint32_t iterations = 0;
  std::uint32_t layer_count = 0;
  // Exposed edges the edges buffer holds: 0 while it holds the one zero
  // entry of a world without diffraction.
  std::size_t edge_count = 0;
  std::uint32_t node_capacity = 0;    // BVH nodes the buffer holds (a rebuild may need more than the first build)
  std::uint32_t source_capacity = 0;  // entries of the step input's source table

  ConfigSizes sizes() const { return {max_rays, iterations, capture_capacity, ring_capacity}; }

  vk::Buffer nodes, triangles, layers;  // scene, read-only
  vk::Buffer edges;                     // exposed edges per triangle (one zero entry while diffraction is off)
  vk::Buffer step_input;                // host-written each step
  vk::Buffer rays, hits, queues;        // ray state and work queues
  vk::Buffer control;                   // queue args, draw args, totals
  vk::Buffer ring, capture;             // indicators
  vk::Buffer counters;                  // per-layer counters
  vk::Buffer admission;                 // the step's admission histogram (sp_ring.h)
  vk::Buffer guide;                     // each source id's guide (sp_guide.h)
  vk::Buffer connect_queue;             // capture slots of the step's spots worth a cast to the listener
  vk::Buffer control_readback;          // copy of control after each step
  // nodes and triangles as RGBA32UI texels: the whole buffers where the
  // walks read them (bvh_texels_usable), else their first texels only
  // (bound, never read).
  vk::UniqueBufferView node_texels, triangle_texels;

  // Initial contents, copied by the first recorded step: where each part
  // lies in `initial_staging`.
  vk::Buffer initial_staging;
  struct InitialCopy {
    const vk::Buffer* destination;
    VkDeviceSize staging_offset;
    VkDeviceSize size;
  };
  std::vector<InitialCopy> initial_copies;
  vk::StorageBindings bindings;
  Kernels kernels;
  // The kernels' specialization constants (SP_SPEC_*), as the device and
  // the config chose them. Only resolve reads SP_SPEC_DIFFRACTION, which
  // set_config changes with the resolve kernel (make_resolve_kernel).
  std::array<std::uint32_t, kKernelSpecializationCount> kernel_specialization{};

  // Whether kernels.resolve was built with diffraction's code: the config's
  // diffraction.enabled, which every step's params must match.
  bool resolve_diffracts() const { return kernel_specialization[SP_SPEC_DIFFRACTION] != VK_FALSE; }
};

// resources.kernels.resolve's like, with diffraction's code where
// `diffraction` and without it elsewhere (SP_SPEC_DIFFRACTION). Throws
// sp::Exception on failure.
vk::ComputePipeline make_resolve_kernel(const vk::Context& context, const GpuResources& resources, bool diffraction);

}  // namespace sp::gpu
