// Timestamps around the kernels of each step, for a host's per-stage timings
// (sp::Visualizer::stage_timings): one before the step's first dispatch and
// one after each group of dispatches of one kernel, each labelled with the
// kernel whose work ends at it.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace sp::gpu {

enum class StageKernel : std::uint8_t { Start, Emit, Trace, Resolve, Prepare, Admit };

// Queries [next, end) of `pool` are reset and free; record_step_dispatches
// writes one per entry it appends to `kinds`, and stops writing (for the
// rest of the frame) when a step would not fit.
struct StageQueries {
  VkQueryPool pool = VK_NULL_HANDLE;
  std::uint32_t next = 0;
  std::uint32_t end = 0;
  std::vector<StageKernel> kinds;
};

// Timestamps one step writes: its start, emit, then trace, resolve and
// prepare per wavefront iteration, and the admission.
inline std::uint32_t stage_queries_per_step(std::uint32_t iterations) { return 3 + 3 * iterations; }

}  // namespace sp::gpu
