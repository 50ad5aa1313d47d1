// The GPU backend: the ray model as Vulkan compute, one submit per step.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "gpu/stage_queries.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"
#include "vk/context.h"

namespace sp::gpu {

// Creates a GPU simulator on `context`, which must outlive it (tests share
// one context per binary this way). Its memory budget is only checked by
// set_config: the caller checked the world's config itself.
Result<std::unique_ptr<Simulator>> create_simulator(World world, vk::Context& context,
                                                    std::uint64_t memory_budget_bytes = kDefaultMemoryBudgetBytes);

// sp::create_simulator's policy on an existing context (the renderer's):
// Auto takes the CPU backend when `context` is a CPU-type device.
Result<std::unique_ptr<Simulator>> create_simulator_on(vk::Context& context, World world, BackendChoice backend,
                                                       const CpuSettings& cpu, std::string* fallback_reason);

// Where a GPU simulator keeps its indicators, for a draw pass on the same
// device: the ring of shader::Indicator and the VkDrawIndirectCommand whose
// instanceCount the compute pass keeps equal to the ring's filled slots
// (SP_INDICATOR_QUAD_VERTICES, a triangle strip, per instance). Both are
// written by each step's compute work; a draw recorded after
// Simulator::step() returned sees that step's state.
struct IndicatorView {
  vk::Context* context = nullptr;
  VkBuffer ring = VK_NULL_HANDLE;  // STORAGE_BUFFER, ring_capacity entries
  std::uint32_t ring_capacity = 0;
  VkBuffer draw_args = VK_NULL_HANDLE;  // INDIRECT_BUFFER
  VkDeviceSize draw_args_offset = 0;
};

// The view of `simulator` if it is this GPU backend, else nothing. Take it
// again after Simulator::set_config, which may replace the ring.
std::optional<IndicatorView> indicator_view(Simulator& simulator);

// Where a GPU step's time goes (bench_step): what the step recorded, and
// the GPU time of each kind of kernel from timestamps around its
// dispatches (indexed by StageKernel; Start stays 0).
struct StepProfile {
  bool measured = false;  // false without timestamp support
  RecordCounts counts;
  std::array<double, kStageKernelCount> kernel_ms{};
};

// Turns the per-kernel timestamps on for later steps of `simulator`; false
// when it is not this GPU backend. They cost a little: benchmarks time
// steps without them.
bool enable_step_profile(Simulator& simulator);
// The last step's profile, once enabled and a step has run.
std::optional<StepProfile> last_step_profile(const Simulator& simulator);

}  // namespace sp::gpu
