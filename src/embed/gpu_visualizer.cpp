// The GPU backend in a host's command buffers: record_simulation records
// the StepEngine's transfers and dispatches; nothing is submitted or waited
// on here.
#include <array>
#include <iterator>
#include <cstddef>
#include <vector>

#include "embed/visualizers.h"
#include "gpu/step_engine.h"
#include "sp_gpu_types.h"
#include "vk/barriers.h"
#include "vk/handle.h"
#include "vk/objects.h"
#include "vk/vk_check.h"

namespace sp::embed {
namespace {

// Frames whose stage timestamps are kept: the host may have this many in
// flight before the oldest one's queries are reused (then its timings are
// simply not reported).
constexpr std::uint32_t kTimedFrames = 8;

class GpuVisualizer final : public VisualizerBase {
 public:
  GpuVisualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target, World world,
                const VisualizerSettings& settings, bool simulation_on_graphics_queue)
      : VisualizerBase(std::move(context), target, std::move(world), settings, simulation_on_graphics_queue),
        engine_(*context_, scene_) {
    // Timestamps are optional; this limit promises them on every graphics
    // and compute queue.
    if (!context_->properties().limits.timestampComputeAndGraphics) return;
    queries_per_frame_ = settings.max_steps_per_frame * gpu::stage_queries_per_step(engine_.iterations());
    stage_pool_ = vk::create_timestamp_pool(*context_, queries_per_frame_ * kTimedFrames, "stage timestamps");
    tick_ms_ = double(context_->properties().limits.timestampPeriod) * 1e-6;
  }

  Backend backend() const override { return Backend::Gpu; }
  std::uint64_t steps_run() const override { return steps_run_; }
  Result<bool> wait_for_simulation() override { return true; }

  Result<std::uint32_t> record_simulation(VkCommandBuffer cmd, double dt) override {
    if (auto valid = check_simulation_args(cmd, dt); !valid) return valid.error();
    return capture_errors(
        [&] {
          const std::uint32_t steps = clock_.advance(dt);
          gpu::RecordOptions options;
          options.graphics_queue = simulation_on_graphics_queue_;
          gpu::StageQueries* stages = nullptr;
          if (stage_pool_ && steps > 0) {
            TimedFrame& timed = timed_[frames_ % kTimedFrames];
            const std::uint32_t first = (frames_ % kTimedFrames) * queries_per_frame_;
            vkCmdResetQueryPool(cmd, stage_pool_.get(), first, queries_per_frame_);
            timed.queries = gpu::StageQueries{stage_pool_.get(), first, first + queries_per_frame_, {}};
            timed.steps = steps;
            timed.frame = frames_;
            stages = &timed.queries;
            ++frames_;
          }
          options.stages = stages;
          // Even without a step due: the first frame's uploads and moved
          // geometry go in now, and the draw's barrier is recorded.
          engine_.record(cmd, scene_, steps_run_, steps, options);
          steps_run_ += steps;
          recorded_ = true;
          record_display(cmd);
          return steps;
        },
        ErrorCode::Vulkan);
  }

  StageTimings stage_timings() const override {
    StageTimings timings;
    // Newest first; a frame whose queries are not all written yet is skipped.
    for (std::uint32_t back = 1; back <= kTimedFrames && back <= frames_; ++back) {
      const TimedFrame& timed = timed_[(frames_ - back) % kTimedFrames];
      const std::uint32_t count = static_cast<std::uint32_t>(timed.queries.kinds.size());
      if (count == 0) continue;
      std::vector<std::uint64_t> values(2 * std::size_t{count});
      const std::uint32_t first = timed.queries.end - queries_per_frame_;
      const VkResult result = vkGetQueryPoolResults(
          context_->device(), stage_pool_.get(), first, count, values.size() * sizeof(std::uint64_t), values.data(),
          2 * sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
      if (result != VK_SUCCESS && result != VK_NOT_READY) continue;
      // All written, and in order: a slot whose reset has not run yet still
      // holds an older frame's values, which need not fit this one's labels.
      bool ready = values[1] != 0;
      for (std::uint32_t k = 1; k < count; ++k)
        ready = ready && values[2 * k + 1] != 0 && values[2 * k] >= values[2 * k - 2];
      if (!ready) continue;
      timings.measured = true;
      timings.steps = timed.steps;
      for (std::uint32_t k = 1; k < count; ++k) {
        const double ms = double(values[2 * k] - values[2 * (k - 1)]) * tick_ms_;
        switch (timed.queries.kinds[k]) {
          case gpu::StageKernel::Emit:
            timings.emit_ms += ms;
            break;
          case gpu::StageKernel::Trace:
            timings.trace_ms += ms;
            break;
          case gpu::StageKernel::Resolve:
            timings.resolve_ms += ms;
            break;
          case gpu::StageKernel::Prepare:
            timings.prepare_ms += ms;
            break;
          case gpu::StageKernel::Connect:
            timings.connect_ms += ms;
            break;
          case gpu::StageKernel::Admit:
            timings.admit_ms += ms;
            break;
          case gpu::StageKernel::Start:
            break;  // between steps: the uploads, not a kernel
        }
      }
      return timings;
    }
    return timings;
  }

  Result<bool> record_totals(VkCommandBuffer cmd, VkBuffer destination, VkDeviceSize offset) override {
    if (cmd == VK_NULL_HANDLE || destination == VK_NULL_HANDLE)
      return Error{ErrorCode::InvalidArgument, "record_totals: the command buffer and the destination must be set"};
    const VkBuffer control = engine_.view().draw_args;  // the control block, the draw's arguments first
    // RAW: the step's last prepare wrote the counts.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    vkCmdFillBuffer(cmd, destination, offset, sizeof(SimulationTotals), 0u);
    // WAW: the zeros land before the 32-bit counts fill the low halves. A
    // fill is a transfer command of no one sub-stage (the validation layer
    // books it under copy, not clear): all transfer stages.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
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
        region(offsetof(Control, ring_filled), offsetof(SimulationTotals, ring_filled), 4),
        region(offsetof(Control, total_cut_short_lo), offsetof(SimulationTotals, casts_cut_short), 8)};
    vkCmdCopyBuffer(cmd, control, destination, static_cast<std::uint32_t>(std::size(regions)), regions);
    // Device -> host: the copy is visible to host reads after the fence.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    return true;
  }

 protected:
  gpu::IndicatorView indicator_view() override { return engine_.view(); }
  bool ready_to_draw() const override { return recorded_; }

 private:
  struct TimedFrame {
    gpu::StageQueries queries;
    std::uint32_t steps = 0;
    std::uint64_t frame = 0;
  };

  gpu::StepEngine engine_;
  vk::UniqueQueryPool stage_pool_;
  std::uint32_t queries_per_frame_ = 0;
  double tick_ms_ = 0.0;
  std::array<TimedFrame, kTimedFrames> timed_{};
  std::uint64_t frames_ = 0;  // frames with steps recorded
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
