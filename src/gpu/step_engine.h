// The GPU simulation as commands recorded into any command buffer: the
// backend's own (GpuSimulator, which submits and waits) or a host's
// (Visualizer, which never does). Everything that changes between steps
// travels inside the command buffer (vkCmdUpdateBuffer), so command buffers
// of several frames in flight share no host-written memory.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "gpu/gpu_resources.h"
#include "gpu/gpu_simulator.h"
#include "gpu/stage_queries.h"
#include "sim/step_plan.h"
#include "soundpaint/simulation.h"
#include "vk/context.h"

namespace sp::gpu {

struct RecordOptions {
  // Copy the control block to GpuResources::control_readback after the last
  // step and make it visible to the host (a caller that waits for the work).
  bool readback_control = false;
  // The command buffer's queue family has graphics: barriers also cover the
  // indicator draw's stages. False on a compute-only queue, where the host's
  // semaphores order the draw instead.
  bool graphics_queue = true;
  VkQueryPool timestamps = VK_NULL_HANDLE;  // 2 queries: before and after, or none
  StageQueries* stages = nullptr;           // timestamps around each step's kernels, or none
  RecordCounts* counts = nullptr;           // adds what the steps recorded, or none
};

class StepEngine {
 public:
  // Wavefront iterations every step records (2 * max_bounces + 1).
  std::uint32_t iterations() const { return resources_.iterations; }
  // Throws sp::Exception (LimitExceeded when a buffer exceeds a device limit).
  StepEngine(vk::Context& context, const SoundScene& scene);

  // Records, outside any render pass: the first call's initial uploads,
  // the BVH entries changed by moving parts since the last call, then
  // `count` steps from `first_step` on, each planned on `scene`. After it,
  // the ring and draw arguments are visible to the indicator draw's vertex
  // shader and indirect read on the same queue.
  void record(VkCommandBuffer cmd, SoundScene& scene, std::uint64_t first_step, std::uint32_t count,
              const RecordOptions& options);

  // Records the initial uploads if no step has recorded them yet, and a
  // barrier after them: for work recorded outside a step
  // (Simulator::set_config's) that writes the same buffers.
  void record_pending_uploads(VkCommandBuffer cmd);

  GpuResources& resources() { return resources_; }
  const GpuResources& resources() const { return resources_; }
  IndicatorView view();

 private:
  void record_initial_uploads(VkCommandBuffer cmd);
  void record_geometry_changes(VkCommandBuffer cmd, const World& world, const BvhChanges& changes);
  void record_step_input(VkCommandBuffer cmd, const World& world, std::uint64_t step);

  vk::Context& context_;
  GpuResources resources_;
  StepPlan plan_;
  std::vector<std::byte> step_input_bytes_;
  bool uploaded_ = false;
};

}  // namespace sp::gpu
