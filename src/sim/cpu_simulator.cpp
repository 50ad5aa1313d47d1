// The CPU backend: the reference the GPU is tested against. Each step plans
// on the calling thread, then casts its rays on the thread pool
// (cpu_step_runner.h) and keeps the indicators in a ring as the GPU does.
#include <algorithm>
#include <optional>
#include <string>

#include "bvh/bvh.h"
#include "sim/config_change.h"
#include "sim/cpu_ring.h"
#include "sim/cpu_step_runner.h"
#include "sim/embree_traversal.h"
#include "sim/indicator_convert.h"
#include "sim/memory_estimate.h"
#include "sim/sound_scene_backend.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"

namespace sp {
namespace {

class CpuSimulator final : public Simulator {
 public:
  CpuSimulator(World world, const CpuSettings& settings)
      : memory_budget_bytes_(settings.memory_budget_bytes),
        traversal_threads_(settings.threads),
        scene_(std::move(world)),
        runner_(settings.threads, scene_.world().layer_names.size()),
        ring_(scene_.world().config),
        layer_table_(make_layer_table(scene_.world())),
        embree_(make_cpu_traversal(scene_.world().config, scene_.world().geometry->bvh, settings.threads)) {
    totals_.layers.resize(scene_.world().layer_names.size());
  }

  Backend backend() const override { return Backend::Cpu; }
  std::string device_description() const override {
    return "CPU, " + std::to_string(runner_.threads()) + " thread" + (runner_.threads() == 1 ? "" : "s");
  }
  std::uint32_t thread_count() const override { return runner_.threads(); }
  SoundScene& scene() override { return scene_; }
  const SoundScene& scene() const override { return scene_; }
  std::uint64_t steps_run() const override { return steps_run_; }
  std::uint64_t last_step_casts() const override { return last_.counters.casts; }

  // A step that fails (out of memory, say) has planned its sources and
  // half-traced its rays; rather than run on from that state, the simulator
  // stops: this and every later step() (and last_step_indicators()) return
  // the error, while live_indicators() and stats() keep reporting the steps
  // before it. A host recovers by creating a new simulator.
  Result<bool> step() override {
    if (failure_) return *failure_;
    Result<bool> done = run_step();
    if (!done) {
      failure_ = done.error();
      failure_->message =
          "step " + std::to_string(steps_run_) + " failed, the simulator has stopped: " + failure_->message;
      return *failure_;
    }
    return done;
  }

  // Everything that can fail is made aside first (the checked config, the
  // resized ring, the layer table, another traversal); then moves alone
  // commit it, so that a refused config leaves the simulator as it was.
  Result<bool> set_config(const Config& config) override {
    if (failure_) return *failure_;
    return capture_errors([&] {
      ConfigChange change = prepare_config_change(scene_.world(), config, steps_run_);
      check_memory_budget(change.config, Backend::Cpu, memory_budget_bytes_);
      const World& world = scene_.world();
      if (change.config.diffraction.enabled) world.geometry->ensure_exposed_edges();
      CpuRing ring = ring_.resized(change.config);
      std::vector<shader::LayerAcoustics> layer_table = make_layer_table(change.layer_properties);
      const bool new_traversal = change.config.cpu_traversal != world.config.cpu_traversal;
      std::unique_ptr<EmbreeTraversal> embree =
          new_traversal ? make_cpu_traversal(change.config, world.geometry->bvh, traversal_threads_) : nullptr;

      const std::uint32_t ray_budget = change.config.ray_budget;
      detail::SoundSceneBackend::apply_config(scene_, std::move(change.config), std::move(change.layer_properties));
      last_.release_beyond(ray_budget);
      ring_ = std::move(ring);
      layer_table_ = std::move(layer_table);
      if (new_traversal) embree_ = std::move(embree);
      return true;
    });
  }

  Result<std::vector<Indicator>> last_step_indicators() override {
    if (failure_) return *failure_;  // the failed step's list may be partial
    return to_public(last_.canonical());
  }

  Result<std::vector<Indicator>> live_indicators() override {
    return to_public(ring_.live(steps_run_, scene_.world().config));
  }

  Result<SimulationStats> stats() override { return totals_; }

 private:
  Result<bool> run_step() {
    return capture_errors([&] {
      const std::uint64_t step = steps_run_;
      const BvhChanges changes = detail::SoundSceneBackend::update_geometry(scene_);
      const Bvh& bvh = scene_.world().geometry->bvh;
      if (embree_) embree_->update(changes);
      detail::SoundSceneBackend::plan(scene_, step, plan_);
      runner_.run(bvh, layer_table_, plan_, make_sim_params(scene_.world().config, step, plan_.listener),
                  ring_.writer().inverse_indicator_size(), last_, embree_.get());
      ring_.write(last_, static_cast<std::uint32_t>(step));

      for (std::size_t l = 0; l < totals_.layers.size(); ++l) accumulate(totals_.layers[l], last_.counters.layers[l]);
      totals_.steps += 1;
      totals_.casts += last_.counters.casts;
      totals_.casts_cut_short += last_.counters.cut_short;
      totals_.connections += last_.counters.connections;
      totals_.max_casts_per_step = std::max(totals_.max_casts_per_step, last_.counters.casts);
      totals_.rays_emitted += plan_.total_rays;
      totals_.indicators += last_.indicator_count();
      steps_run_ += 1;
      return true;
    });
  }

  std::uint64_t memory_budget_bytes_;  // CpuSettings', checked again by set_config
  unsigned traversal_threads_;         // CpuSettings::threads, for an Embree scene set_config asks for
  SoundScene scene_;
  CpuStepRunner runner_;
  CpuRing ring_;
  std::vector<shader::LayerAcoustics> layer_table_;
  std::unique_ptr<EmbreeTraversal> embree_;  // null: soundpaint's own traversal
  StepPlan plan_;
  CpuStepOutput last_;
  SimulationStats totals_;
  std::uint64_t steps_run_ = 0;
  std::optional<Error> failure_;  // set by the first failed step
};

}  // namespace

Result<std::unique_ptr<Simulator>> create_cpu_simulator(World world, const CpuSettings& settings) {
  return capture_errors([&]() -> std::unique_ptr<Simulator> {
    if (world.geometry->bvh.nodes.empty())
      throw Exception(ErrorCode::InvalidArgument, "create_cpu_simulator: the world has no BVH");
    check_memory_budget(world.config, Backend::Cpu, settings.memory_budget_bytes);
    return std::make_unique<CpuSimulator>(std::move(world), settings);
  });
}

}  // namespace sp
