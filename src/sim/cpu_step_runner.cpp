#include "sim/cpu_step_runner.h"

#include <algorithm>

#include "sp_ray_model.h"

namespace sp {
namespace {

// Rays per work chunk: big enough to amortise the atomic claim, small
// enough to balance 2-16 workers at a budget of a few hundred rays.
constexpr std::size_t kChunkRays = 32;

}  // namespace

CpuStepRunner::CpuStepRunner(unsigned threads, std::size_t layer_count)
    : pool_(threads), layer_count_(layer_count), worker_counters_(pool_.size()) {
  for (WorkerCounters& worker : worker_counters_) {
    // A cache line of spare capacity after the counters keeps the next
    // heap block, perhaps another worker's, off their last line.
    worker.counters.layers.reserve(layer_count_ + (kCacheLine + sizeof(LayerCounters) - 1u) / sizeof(LayerCounters));
    worker.counters.layers.resize(layer_count_);
  }
}

void CpuStepRunner::run(const Bvh& bvh, std::span<const shader::LayerAcoustics> layers, const StepPlan& plan,
                        const shader::SimParams& params, CpuStepOutput& out, const EmbreeTraversal* embree) {
  TraceContext context{&bvh, layers, plan.sources, params, embree};
  const std::size_t chunks = (plan.total_rays + kChunkRays - 1) / kChunkRays;
  if (chunk_indicators_.size() < chunks) chunk_indicators_.resize(chunks);
  for (std::size_t c = 0; c < chunks; ++c) chunk_indicators_[c].list.clear();
  for (WorkerCounters& worker : worker_counters_) {
    worker.counters.casts = 0;
    std::fill(worker.counters.layers.begin(), worker.counters.layers.end(), LayerCounters{});
  }

  pool_.parallel_for(plan.total_rays, kChunkRays, [&](std::size_t first, std::size_t last, unsigned worker) {
    DefaultInitVector<shader::Indicator>& indicators = chunk_indicators_[first / kChunkRays].list;
    std::size_t slot = 0;  // rays are grouped by source in ascending ray index
    for (std::size_t i = first; i < last; ++i) {
      while (i >= plan.sources[slot].first_ray + plan.sources[slot].ray_count) ++slot;
      shader::RayState ray = shader::sp_emit_ray(plan.sources[slot], static_cast<std::uint32_t>(slot),
                                                 static_cast<std::uint32_t>(i), params.seed, params.step);
      trace_ray(context, ray, indicators, worker_counters_[worker].counters);
    }
  });

  merge_in_canonical_order(chunks, out.indicators);
  out.counters.casts = 0;
  out.counters.layers.assign(layer_count_, LayerCounters{});
  for (const WorkerCounters& worker : worker_counters_) {
    out.counters.casts += worker.counters.casts;
    for (std::size_t l = 0; l < layer_count_; ++l) accumulate(out.counters.layers[l], worker.counters.layers[l]);
  }
}

// Chunks hold rays in ascending order and each ray's indicators in ascending
// iteration; a stable counting sort by iteration then yields (iteration, ray)
// order, whatever thread ran which chunk.
void CpuStepRunner::merge_in_canonical_order(std::size_t chunks, std::vector<shader::Indicator>& out) const {
  std::size_t total = 0;
  std::uint32_t max_iteration = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    total += chunk_indicators_[c].list.size();
    for (const shader::Indicator& ind : chunk_indicators_[c].list)
      max_iteration = std::max(max_iteration, ind.iteration);
  }
  std::vector<std::size_t> offsets(max_iteration + 2, 0);
  for (std::size_t c = 0; c < chunks; ++c)
    for (const shader::Indicator& ind : chunk_indicators_[c].list) offsets[ind.iteration + 1] += 1;
  for (std::size_t k = 1; k < offsets.size(); ++k) offsets[k] += offsets[k - 1];
  out.resize(total);
  for (std::size_t c = 0; c < chunks; ++c)
    for (const shader::Indicator& ind : chunk_indicators_[c].list) out[offsets[ind.iteration]++] = ind;
}

}  // namespace sp
