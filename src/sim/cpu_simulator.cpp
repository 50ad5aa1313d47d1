// The CPU backend: the reference the GPU is tested against. One
// parallel_for per step over the step's rays; results are independent of the
// thread count because every random number is keyed by (seed, step, ray,
// interaction) and indicators are merged in canonical order.
#include <algorithm>
#include <cmath>

#include "sim/cpu_tracer.h"
#include "sim/indicator_ring.h"
#include "sim/host_inputs.h"
#include "sim/step_plan.h"
#include "sim/thread_pool.h"
#include "sp_ray_model.h"

namespace sp {
namespace {

// Rays per work chunk: big enough to amortise the atomic claim, small
// enough to balance 2-16 workers at a budget of a few hundred rays.
constexpr std::size_t kChunkRays = 32;

class CpuSimulator final : public Simulator {
 public:
  CpuSimulator(World world, const CpuSettings& settings)
      : world_(std::move(world)),
        pool_(settings.threads),
        ring_(world_.config.max_indicators),
        layer_table_(make_layer_table(world_)),
        host_(world_.listener, world_.sources.size()),
        worker_counters_(pool_.size()) {
    totals_.layers.resize(world_.layer_names.size());
    for (auto& counters : worker_counters_) counters.layers.resize(world_.layer_names.size());
  }

  Backend backend() const override { return Backend::Cpu; }
  std::string device_description() const override {
    return "CPU, " + std::to_string(pool_.size()) + " thread" + (pool_.size() == 1 ? "" : "s");
  }
  const World& world() const override { return world_; }
  std::uint64_t steps_run() const override { return steps_run_; }
  std::uint64_t last_step_casts() const override { return last_casts_; }

  Result<bool> set_listener(glm::vec3 position) override { return host_.set_listener(position); }

  Result<bool> play(std::uint32_t source_id, double duration) override {
    return host_.play(source_id, duration, static_cast<double>(steps_run_) * world_.config.dt);
  }

  Result<bool> step() override {
    const std::uint64_t step = steps_run_;
    StepPlan plan = host_.plan(world_, step);
    TraceContext context{&world_.bvh, layer_table_, plan.sources, make_sim_params(world_.config, step)};

    const std::size_t chunks = (plan.total_rays + kChunkRays - 1) / kChunkRays;
    if (chunk_indicators_.size() < chunks) chunk_indicators_.resize(chunks);
    for (std::size_t c = 0; c < chunks; ++c) chunk_indicators_[c].clear();
    for (auto& counters : worker_counters_) {
      counters.casts = 0;
      std::fill(counters.layers.begin(), counters.layers.end(), LayerCounters{});
    }

    pool_.parallel_for(plan.total_rays, kChunkRays, [&](std::size_t first, std::size_t last, unsigned worker) {
      std::vector<Indicator>& out = chunk_indicators_[first / kChunkRays];
      std::size_t slot = 0;  // rays are grouped by source in ascending ray index
      for (std::size_t i = first; i < last; ++i) {
        while (i >= plan.sources[slot].first_ray + plan.sources[slot].ray_count) ++slot;
        shader::RayState ray = shader::sp_emit_ray(plan.sources[slot], static_cast<std::uint32_t>(slot),
                                                   static_cast<std::uint32_t>(i), context.params.seed,
                                                   context.params.step);
        trace_ray(context, ray, out, worker_counters_[worker]);
      }
    });

    merge_in_canonical_order(chunks);
    ring_.push(last_indicators_);

    last_casts_ = 0;
    for (const auto& counters : worker_counters_) {
      last_casts_ += counters.casts;
      for (std::size_t l = 0; l < counters.layers.size(); ++l) {
        totals_.layers[l].hits += counters.layers[l].hits;
        totals_.layers[l].reflections += counters.layers[l].reflections;
        totals_.layers[l].penetrations += counters.layers[l].penetrations;
        totals_.layers[l].backcast_misses += counters.layers[l].backcast_misses;
      }
    }
    totals_.steps += 1;
    totals_.casts += last_casts_;
    totals_.max_casts_per_step = std::max(totals_.max_casts_per_step, last_casts_);
    totals_.rays_emitted += plan.total_rays;
    totals_.indicators += last_indicators_.size();
    steps_run_ += 1;
    return true;
  }

  Result<std::vector<Indicator>> last_step_indicators() override { return last_indicators_; }

  Result<std::vector<Indicator>> live_indicators() override {
    if (steps_run_ == 0) return std::vector<Indicator>{};
    return ring_.live(steps_run_ - 1, world_.config.dt, world_.config.indicator_lifetime);
  }

  Result<SimulationStats> stats() override { return totals_; }

 private:
  // Chunks hold rays in ascending order and each ray's indicators in
  // ascending iteration; a stable counting sort by iteration then yields
  // (iteration, ray) order, whatever thread ran which chunk.
  void merge_in_canonical_order(std::size_t chunks) {
    std::size_t total = 0;
    std::uint32_t max_iteration = 0;
    for (std::size_t c = 0; c < chunks; ++c) {
      total += chunk_indicators_[c].size();
      for (const Indicator& ind : chunk_indicators_[c]) max_iteration = std::max(max_iteration, ind.iteration);
    }
    std::vector<std::size_t> offsets(max_iteration + 2, 0);
    for (std::size_t c = 0; c < chunks; ++c)
      for (const Indicator& ind : chunk_indicators_[c]) offsets[ind.iteration + 1] += 1;
    for (std::size_t k = 1; k < offsets.size(); ++k) offsets[k] += offsets[k - 1];
    last_indicators_.resize(total);
    for (std::size_t c = 0; c < chunks; ++c)
      for (const Indicator& ind : chunk_indicators_[c]) last_indicators_[offsets[ind.iteration]++] = ind;
  }

  World world_;
  ThreadPool pool_;
  IndicatorRing ring_;
  std::vector<shader::LayerAcoustics> layer_table_;
  HostInputs host_;
  std::vector<TraceCounters> worker_counters_;
  std::vector<std::vector<Indicator>> chunk_indicators_;
  std::vector<Indicator> last_indicators_;
  SimulationStats totals_;
  std::uint64_t steps_run_ = 0;
  std::uint64_t last_casts_ = 0;
};

}  // namespace

Result<std::unique_ptr<Simulator>> create_cpu_simulator(World world, const CpuSettings& settings) {
  return capture_errors([&]() -> std::unique_ptr<Simulator> {
    if (world.bvh.nodes.empty()) throw Exception(ErrorCode::InvalidArgument, "create_cpu_simulator: the world has no BVH");
    return std::make_unique<CpuSimulator>(std::move(world), settings);
  });
}

}  // namespace sp
