// Records the command buffer of one step: emit, then per wavefront iteration
// trace -> resolve -> prepare, with indirect dispatches sized on the GPU.
// Nothing in it changes between steps (per-step data lives in the host-written
// step input), so it is recorded once and submitted every step.
#pragma once

#include <vulkan/vulkan.h>

#include "gpu/gpu_resources.h"

namespace sp::gpu {

// `timestamps` holds 2 queries (start, end) or is VK_NULL_HANDLE.
void record_step(VkCommandBuffer cmd, const GpuResources& resources, VkQueryPool timestamps);

}  // namespace sp::gpu
