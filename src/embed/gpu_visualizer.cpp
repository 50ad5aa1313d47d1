// The GPU backend in a host's command buffers: record_simulation records
// the StepEngine's transfers and dispatches; nothing is submitted or waited
// on here.
#include <cstddef>

#include "embed/visualizers.h"
#include "gpu/step_engine.h"
#include "sp_gpu_types.h"
#include "vk/barriers.h"

namespace sp::embed {
namespace {

class GpuVisualizer final : public VisualizerBase {
 public:
  GpuVisualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target, World world,
                const VisualizerSettings& settings, bool simulation_on_graphics_queue)
      : VisualizerBase(std::move(context), target, std::move(world), settings, simulation_on_graphics_queue),
        engine_(*context_, scene_) {}

  Backend backend() const override { return Backend::Gpu; }
  std::uint64_t steps_run() const override { return steps_run_; }
  Result<bool> wait_for_simulation() override { return true; }

  Result<std::uint32_t> record_simulation(VkCommandBuffer cmd, double dt) override {
    if (auto valid = check_simulation_args(cmd, dt); !valid) return valid.error();
    return capture_errors([&] {
      const std::uint32_t steps = clock_.advance(dt);
      gpu::RecordOptions options;
      options.graphics_queue = simulation_on_graphics_queue_;
      // Even without a step due: the first frame's uploads and moved
      // geometry go in now, and the draw's barrier is recorded.
      engine_.record(cmd, scene_, steps_run_, steps, options);
      steps_run_ += steps;
      recorded_ = true;
      record_display(cmd);
      return steps;
    }, ErrorCode::Vulkan);
  }

  Result<bool> record_totals(VkCommandBuffer cmd, VkBuffer destination, VkDeviceSize offset) override {
    if (cmd == VK_NULL_HANDLE || destination == VK_NULL_HANDLE)
      return Error{ErrorCode::InvalidArgument, "record_totals: the command buffer and the destination must be set"};
    const VkBuffer control = engine_.view().draw_args;  // the control block, the draw's arguments first
    // RAW: the step's last prepare wrote the counts.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    vkCmdFillBuffer(cmd, destination, offset, sizeof(SimulationTotals), 0u);
    // WAW: the zeros land before the 32-bit counts fill the low halves.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
    using shader::Control;
    auto region = [&](std::size_t from, std::size_t to, VkDeviceSize bytes) {
      return VkBufferCopy{from, offset + to, bytes};
    };
    // (lo, hi) pairs are little-endian 64-bit counts as they lie.
    const VkBufferCopy regions[] = {
        region(offsetof(Control, steps), offsetof(SimulationTotals, steps), 4),
        region(offsetof(Control, total_casts_lo), offsetof(SimulationTotals, casts), 8),
        region(offsetof(Control, total_rays_lo), offsetof(SimulationTotals, rays_emitted), 8),
        region(offsetof(Control, total_indicators_lo), offsetof(SimulationTotals, indicators), 8),
        region(offsetof(Control, ring_filled), offsetof(SimulationTotals, ring_filled), 4)};
    vkCmdCopyBuffer(cmd, control, destination, 5, regions);
    // Device -> host: the copy is visible to host reads after the fence.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    return true;
  }

 protected:
  gpu::IndicatorView indicator_view() override { return engine_.view(); }
  bool ready_to_draw() const override { return recorded_; }

 private:
  gpu::StepEngine engine_;
  std::uint64_t steps_run_ = 0;
  bool recorded_ = false;
};

}  // namespace

std::unique_ptr<Visualizer> make_gpu_visualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target,
                                                World world, const VisualizerSettings& settings,
                                                bool simulation_on_graphics_queue) {
  return std::make_unique<GpuVisualizer>(std::move(context), target, std::move(world), settings,
                                         simulation_on_graphics_queue);
}

}  // namespace sp::embed
