// Records one step on the GPU: the step's starting counts (written by the
// host, no kernel), then emit (which also casts its rays), then per
// wavefront iteration trace -> resolve (whose last subgroup prepares the
// next iteration), then the casts to the listener and the ring's
// admission, with indirect dispatches sized on the GPU.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "gpu/gpu_resources.h"
#include "gpu/stage_queries.h"
#include "sp_gpu_types.h"

namespace sp::gpu {

// The control block's per-step part (from `queues` up to `ring_head`) as it
// stands before a step of `total_rays` rays, with kernels `group_width`
// invocations wide: queue 0 holds the emitted rays, every count is 0, the
// connect pass runs one group (its last subgroup plans the admission) and
// the admission none until resolve says more.
shader::Control step_start_control(std::uint32_t total_rays, std::uint32_t group_width);

// Transfers that start a step: the control block's per-step part
// (step_start_control), the per-layer step counters and the admission's
// order bitmap, zeroed. The caller orders them after the previous step's
// kernels and before this step's (with the step input's upload).
void record_step_start(VkCommandBuffer cmd, const GpuResources& resources, std::uint32_t total_rays);

// The step's dispatches, `total_rays` emitted. The caller has made the
// step start and the step input visible to compute reads and ordered
// earlier accesses to the ray, queue and control buffers before this.
// With `stages`, timestamps go around its kernels when the step fits.
void record_step_dispatches(VkCommandBuffer cmd, const GpuResources& resources, std::uint32_t total_rays,
                            StageQueries* stages = nullptr, RecordCounts* counts = nullptr);

}  // namespace sp::gpu
