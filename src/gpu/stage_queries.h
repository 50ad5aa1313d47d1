// Timestamps around the kernels of each step, for a host's per-stage timings
// (sp::Visualizer::stage_timings): one before the step's first dispatch and
// one after each group of dispatches of one kernel, each labelled with the
// kernel whose work ends at it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace sp::gpu {

enum class StageKernel : std::uint8_t { Start, Emit, Trace, Resolve, Prepare, Connect, Admit };
inline constexpr std::size_t kStageKernelCount = 7;

// Queries [next, end) of `pool` are reset and free; record_step_dispatches
// writes one per entry it appends to `kinds`, and stops writing (for the
// rest of the frame) when a step would not fit.
struct StageQueries {
  VkQueryPool pool = VK_NULL_HANDLE;
  std::uint32_t next = 0;
  std::uint32_t end = 0;
  std::vector<StageKernel> kinds;
};

// Timestamps one step writes: its start, emit (which casts the first
// iteration's rays), then trace per wavefront iteration after the first and
// resolve per iteration (resolve's last subgroup does what the prepare
// dispatch did: Prepare stays unused), the casts to the listener and the
// admission.
inline std::uint32_t stage_queries_per_step(std::uint32_t iterations) { return 3 + 2 * iterations; }

// What a step recorded: dispatches (direct and indirect, empty ones too)
// and the pipeline barriers between them.
struct RecordCounts {
  std::uint32_t dispatches = 0;
  std::uint32_t barriers = 0;
};

}  // namespace sp::gpu
