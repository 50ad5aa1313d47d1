// The GPU backend: the ray model as Vulkan compute, one submit per step.
#pragma once

#include <memory>
#include <optional>

#include "soundpaint/simulation.h"
#include "sp_types.h"
#include "vk/context.h"

namespace sp::gpu {

// Creates a GPU simulator on `context`, which must outlive it (tests share
// one context per binary this way).
Result<std::unique_ptr<Simulator>> create_simulator(World world, vk::Context& context);

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

// The view of `simulator` if it is this GPU backend, else nothing.
std::optional<IndicatorView> indicator_view(Simulator& simulator);

}  // namespace sp::gpu
