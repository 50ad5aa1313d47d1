// The GPU backend in a host's command buffers: record_simulation records
// the StepEngine's transfers and dispatches; nothing is submitted or waited
// on here.
#include "embed/visualizers.h"
#include "gpu/step_engine.h"

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
