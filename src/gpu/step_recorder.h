// Records the dispatches of one step: emit, then per wavefront iteration
// trace -> resolve (whose last workgroup prepares the next iteration), with
// indirect dispatches sized on the GPU.
// Nothing in it depends on the step (per-step data lives in the step input
// buffer), so the same sequence serves every step.
#pragma once

#include <vulkan/vulkan.h>

#include "gpu/gpu_resources.h"
#include "gpu/stage_queries.h"

namespace sp::gpu {

// The caller has made the step input visible to compute reads and ordered
// earlier accesses to the ray, queue and control buffers before this.
// `source_count`: entries of the step's source table (its guides are folded
// after its spots are heard). With `stages`, timestamps go around its
// kernels when the step fits.
void record_step_dispatches(VkCommandBuffer cmd, const GpuResources& resources, std::uint32_t source_count,
                            StageQueries* stages = nullptr, RecordCounts* counts = nullptr);

}  // namespace sp::gpu
