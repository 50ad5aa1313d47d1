// The CPU backend in a host's frame loop: each step runs on worker threads
// while the host renders; the next record_simulation hands its indicators
// to a device-local ring through the command buffer (only the new ones),
// then starts the following step. The render thread never blocks on it.
#include <algorithm>

#include "embed/cpu_step_thread.h"
#include "embed/visualizers.h"
#include "sim/cpu_ring.h"
#include "sim/embree_traversal.h"
#include "sim/sound_scene_backend.h"
#include "sim/world_geometry.h"
#include "sp_draw_types.h"
#include "vk/barriers.h"
#include "vk/buffer.h"

namespace sp::embed {
namespace {

class CpuVisualizer final : public VisualizerBase {
 public:
  CpuVisualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target, World world,
                const VisualizerSettings& settings, bool simulation_on_graphics_queue)
      : VisualizerBase(std::move(context), target, std::move(world), settings, simulation_on_graphics_queue),
        max_steps_(settings.max_steps_per_frame),
        writer_(scene_.world().config),
        layer_table_(make_layer_table(scene_.world())),
        ring_(*context_, VkDeviceSize{writer_.capacity()} * sizeof(Indicator),
              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,  // usage: visualizer.h
              vk::MemoryUsage::DeviceLocal, "cpu indicator ring"),
        draw_args_(*context_, sizeof(VkDrawIndirectCommand),
                   VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                       VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,  // the display prepass reads the instance count
                   vk::MemoryUsage::DeviceLocal, "cpu indicator draw args"),
        embree_(make_cpu_traversal(scene_.world().config, scene_.world().geometry->bvh, settings.cpu.threads)),
        worker_(settings.cpu.threads, scene_.world().layer_names.size()) {}

  ~CpuVisualizer() override { worker_.wait(); }

  Backend backend() const override { return Backend::Cpu; }
  std::uint64_t steps_run() const override { return steps_run_; }

  Result<bool> wait_for_simulation() override {
    worker_.wait();
    return true;
  }

  Result<std::uint32_t> record_simulation(VkCommandBuffer cmd, double dt) override {
    if (auto valid = check_simulation_args(cmd, dt); !valid) return valid.error();
    return capture_errors([&]() -> std::uint32_t {
      due_ = std::min(due_ + clock_.advance(dt), max_steps_);
      // WAR: earlier frames' draws are done reading the ring and arguments
      // before this frame's uploads overwrite them.
      const VkPipelineStageFlags2 readers =
          VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
          (simulation_on_graphics_queue_ ? VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT : VK_PIPELINE_STAGE_2_NONE);
      vk::memory_barrier(cmd, readers | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      std::uint32_t handed = 0;
      if (!recorded_) upload_draw_args(cmd);
      const CpuStepOutput* finished = nullptr;
      try {
        finished = worker_.poll();
      } catch (...) {
        steps_run_ = running_step_ + 1;  // that step is lost; later numbering stays right
        throw;
      }
      if (finished != nullptr) {
        totals_.casts += finished->counters.casts;
        totals_.casts_cut_short += finished->counters.cut_short;
        totals_.indicators += finished->indicator_count();
        totals_.rays_emitted += running_rays_;
        upload_step(cmd, *finished, static_cast<std::uint32_t>(running_step_));
        worker_.release();
        steps_run_ = running_step_ + 1;
        handed = 1;
      }
      if (due_ > 0 && worker_.idle()) start_next_step();
      // RAW: the uploads reach the indicator draw. On a compute-only queue
      // only the indirect stage exists; the host's semaphore carries the rest.
      vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, readers,
                         VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT |
                             (simulation_on_graphics_queue_ ? VK_ACCESS_2_SHADER_STORAGE_READ_BIT : VK_ACCESS_2_NONE));
      recorded_ = true;
      record_display(cmd);
      return handed;
    });
  }

  StageTimings stage_timings() const override {
    StageTimings timings;
    timings.cpu_step_ms = worker_.last_step_ms();
    timings.measured = steps_run_ > 0;
    timings.steps = timings.measured ? 1u : 0u;
    return timings;
  }

  Result<bool> record_totals(VkCommandBuffer cmd, VkBuffer destination, VkDeviceSize offset) override {
    if (cmd == VK_NULL_HANDLE || destination == VK_NULL_HANDLE)
      return Error{ErrorCode::InvalidArgument, "record_totals: the command buffer and the destination must be set"};
    // The host knows them: the steps handed over so far.
    SimulationTotals totals = totals_;
    totals.steps = steps_run_;
    totals.ring_filled = writer_.filled();
    vkCmdUpdateBuffer(cmd, destination, offset, sizeof totals, &totals);
    // Device -> host: the update is visible to host reads after the fence.
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    return true;
  }

 protected:
  gpu::IndicatorView indicator_view() override {
    gpu::IndicatorView view;
    view.context = context_.get();
    view.ring = ring_.get();
    view.ring_capacity = writer_.capacity();
    view.draw_args = draw_args_.get();
    return view;
  }
  bool ready_to_draw() const override { return recorded_; }

 private:
  void start_next_step() {
    // The worker is idle, so nothing reads the BVH (or the Embree scene over
    // it) while it is refitted.
    const BvhChanges changes = detail::SoundSceneBackend::update_geometry(scene_);
    const Bvh& bvh = scene_.world().geometry->bvh;
    if (embree_) embree_->update(changes);
    StepPlan plan;
    detail::SoundSceneBackend::plan(scene_, next_step_, plan);
    running_rays_ = plan.total_rays;
    const shader::SimParams params = make_sim_params(scene_.world().config, next_step_, plan.listener);
    worker_.start(bvh, layer_table_, std::move(plan), params, writer_.inverse_indicator_size(), embree_.get());
    running_step_ = next_step_;
    next_step_ += 1;
    due_ -= 1;
  }

  // The ring's one writer admits and places the step's indicators; only
  // the slots it writes are uploaded.
  void upload_step(VkCommandBuffer cmd, const CpuStepOutput& step, std::uint32_t step_number) {
    writer_.write(step, step_number, [&](std::uint32_t slot, std::span<const shader::Indicator> run) {
      vk::record_update(cmd, ring_, VkDeviceSize{slot} * sizeof(shader::Indicator), run.data(), run.size_bytes());
    });
    upload_draw_args(cmd);
  }

  void upload_draw_args(VkCommandBuffer cmd) {
    VkDrawIndirectCommand command{};
    command.vertexCount = SP_INDICATOR_QUAD_VERTICES;
    command.instanceCount = writer_.filled();
    vk::record_update(cmd, draw_args_, 0, &command, sizeof command);
  }

  std::uint32_t max_steps_;
  RingWriter writer_;  // admits and places each step's indicators in ring_
  std::vector<shader::LayerAcoustics> layer_table_;
  vk::Buffer ring_;
  vk::Buffer draw_args_;
  std::unique_ptr<EmbreeTraversal> embree_;  // null: soundpaint's own traversal
  CpuStepThread worker_;                     // after what its running step reads
  SimulationTotals totals_;                  // casts, rays and indicators of the steps handed over
  std::uint32_t running_rays_ = 0;           // rays of the step the worker runs
  std::uint64_t steps_run_ = 0;              // steps handed over
  std::uint64_t next_step_ = 0;              // step the worker runs next
  std::uint64_t running_step_ = 0;           // step the worker runs or ran last
  std::uint32_t due_ = 0;                    // steps due but not started
  bool recorded_ = false;
};

}  // namespace

std::unique_ptr<Visualizer> make_cpu_visualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target,
                                                World world, const VisualizerSettings& settings,
                                                bool simulation_on_graphics_queue) {
  return std::make_unique<CpuVisualizer>(std::move(context), target, std::move(world), settings,
                                         simulation_on_graphics_queue);
}

}  // namespace sp::embed
