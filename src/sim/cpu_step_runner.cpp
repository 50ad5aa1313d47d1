#include "sim/cpu_step_runner.h"

#include <algorithm>
#include <bit>

#include "sim/indicator_ring.h"
#include "sp_guide.h"
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
                        const shader::SimParams& params, float inverse_indicator_size, CpuStepOutput& out,
                        const EmbreeTraversal* embree) {
  TraceContext context{&bvh, layers, plan.sources, params, embree};
  const std::size_t chunks = (plan.total_rays + kChunkRays - 1) / kChunkRays;
  if (out.chunks_.size() < chunks) out.chunks_.resize(chunks);
  out.chunk_count_ = chunks;
  for (std::size_t c = 0; c < chunks; ++c) out.chunks_[c].list.clear();
  out.worker_bins_.resize(pool_.size());
  for (CpuStepOutput::WorkerBins& worker : out.worker_bins_) worker.count.fill(0u);
  out.binned_ = false;  // until every chunk is binned: a throwing step leaves lists and bins unmatched
  for (WorkerCounters& worker : worker_counters_) {
    worker.counters.casts = 0;
    worker.counters.cut_short = 0;
    worker.counters.connections = 0;
    std::fill(worker.counters.layers.begin(), worker.counters.layers.end(), LayerCounters{});
    worker.guide_pending.assign(plan.sources.size() * SP_GUIDE_CELLS, 0u);
  }
  fold_guides(plan);
  const std::uint32_t* guide = guides_.data();

  pool_.parallel_for(plan.total_rays, kChunkRays, [&](std::size_t first, std::size_t last, unsigned worker) {
    const std::size_t chunk = first / kChunkRays;
    DefaultInitVector<shader::Indicator>& indicators = out.chunks_[chunk].list;
    WorkerCounters& mine = worker_counters_[worker];
    std::size_t slot = 0;  // rays are grouped by source in ascending ray index
    for (std::size_t i = first; i < last; ++i) {
      while (i >= plan.sources[slot].first_ray + plan.sources[slot].ray_count) ++slot;
      const auto ray_index = static_cast<std::uint32_t>(i);
      std::uint32_t cell = 0;
      const glm::vec3 dir = shader::sp_source_emission(guide, plan.sources[slot], ray_index, params, cell);
      const shader::RayState ray =
          shader::sp_emit_ray(plan.sources[slot], static_cast<std::uint32_t>(slot), ray_index, dir, cell);
      trace_ray(context, ray, indicators, mine.counters);
    }
    connect_indicators(context, indicators, mine.counters);
    for (const shader::Indicator& ind : indicators) {
      if (ind.heard <= 0.0f) continue;
      mine.guide_pending[ind.source_slot * SP_GUIDE_CELLS + ind.emit_cell] +=
          shader::sp_guide_spot_weight(shader::sp_heard_relative(ind, inverse_indicator_size), ind.toward);
    }
    out.count_bins(chunk, inverse_indicator_size, out.worker_bins_[worker].count);
  });

  out.bins_.fill(0u);
  for (const CpuStepOutput::WorkerBins& worker : out.worker_bins_)
    for (std::size_t b = 0; b < SP_ADMISSION_BINS; ++b) out.bins_[b] += worker.count[b];
  out.binned_ = true;
  out.binned_inverse_size_ = inverse_indicator_size;

  out.counters.casts = 0;
  out.counters.cut_short = 0;
  out.counters.connections = 0;
  out.counters.layers.assign(layer_count_, LayerCounters{});
  for (const WorkerCounters& worker : worker_counters_) {
    out.counters.casts += worker.counters.casts;
    out.counters.cut_short += worker.counters.cut_short;
    out.counters.connections += worker.counters.connections;
    for (std::size_t l = 0; l < layer_count_; ++l) accumulate(out.counters.layers[l], worker.counters.layers[l]);
    // Integer sums: the pending weights do not depend on which worker
    // traced what.
    for (std::size_t slot = 0; slot < plan.sources.size(); ++slot) {
      const std::uint32_t base = shader::sp_guide_base(plan.sources[slot].source_id) + SP_GUIDE_PENDING;
      for (std::uint32_t c = 0; c < SP_GUIDE_CELLS; ++c)
        guides_[base + c] += worker.guide_pending[slot * SP_GUIDE_CELLS + c];
    }
  }
}

void CpuStepRunner::fold_guides(const StepPlan& plan) {
  std::uint32_t sources = 0;
  for (const shader::StepSource& source : plan.sources) sources = std::max(sources, source.source_id + 1u);
  if (guides_.size() < std::size_t{sources} * SP_GUIDE_STRIDE)
    guides_.resize(std::size_t{sources} * SP_GUIDE_STRIDE, 0u);
  for (const shader::StepSource& source : plan.sources)
    shader::sp_guide_fold(guides_.data(), shader::sp_guide_base(source.source_id));
}

void CpuStepOutput::release_beyond(std::uint32_t rays) {
  const std::size_t needed = std::max(chunk_count_, (std::size_t{rays} + kChunkRays - 1) / kChunkRays);
  // Shrinking destroys the spare chunks' lists and frees their indicators.
  if (chunks_.size() > needed) chunks_.resize(needed);
}

std::size_t CpuStepOutput::indicator_count() const {
  std::size_t count = 0;
  for (std::size_t c = 0; c < chunk_count_; ++c) count += chunks_[c].list.size();
  return count;
}

void CpuStepOutput::count_bins(std::size_t c, float inverse_indicator_size, BinCounts& counts) {
  Chunk& chunk = chunks_[c];
  chunk.bins.resize(chunk.list.size());
  for (std::size_t i = 0; i < chunk.list.size(); ++i) {
    const std::uint32_t bin = shader::sp_admission_bin(chunk.list[i], inverse_indicator_size);
    chunk.bins[i] = static_cast<std::uint16_t>(bin);
    counts[bin] += 1u;
  }
}

// Chunks hold rays in ascending order and each ray's indicators in ascending
// iteration; a stable counting sort by iteration of indicators listed in
// chunk order then yields (iteration, ray) order, whatever thread ran which
// chunk.
std::vector<shader::Indicator> CpuStepOutput::canonical_order(std::span<const shader::Indicator* const> kept) {
  std::vector<std::size_t> offsets;  // per iteration + 1: how many kept, then where the next goes
  for (const shader::Indicator* ind : kept) {
    if (offsets.size() < ind->iteration + 2u) offsets.resize(ind->iteration + 2u, 0u);
    offsets[ind->iteration + 1u] += 1u;
  }
  for (std::size_t k = 1; k < offsets.size(); ++k) offsets[k] += offsets[k - 1u];
  std::vector<shader::Indicator> out(kept.size());
  for (const shader::Indicator* ind : kept) out[offsets[ind->iteration]++] = *ind;
  return out;
}

template <class Keep>
std::vector<shader::Indicator> CpuStepOutput::canonical_where(Keep&& keep) const {
  std::vector<const shader::Indicator*> kept;
  for_each([&](const shader::Indicator& ind) {
    if (keep(ind)) kept.push_back(&ind);
  });
  return canonical_order(kept);
}

std::vector<shader::Indicator> CpuStepOutput::canonical() const {
  return canonical_where([](const shader::Indicator&) { return true; });
}

std::vector<shader::Indicator> CpuStepOutput::admitted(std::uint32_t quota, float inverse_indicator_size) const {
  if (!binned_ ||
      std::bit_cast<std::uint32_t>(inverse_indicator_size) != std::bit_cast<std::uint32_t>(binned_inverse_size_)) {
    // Not binned, or not with this size: every indicator's bin anew.
    const AdmissionPlan plan([&](auto&& visit) { for_each(visit); }, indicator_count(), quota, inverse_indicator_size);
    return canonical_where([&](const shader::Indicator& ind) { return plan.admits(ind); });
  }
  AdmissionPlan plan(indicator_count(), quota, inverse_indicator_size);
  if (plan.admits_all()) return canonical();
  std::copy(bins_.begin(), bins_.end(), plan.bins());
  plan.plan_bins();
  // One pass over the bins finds the few that may be admitted (in chunk
  // order); their tie-breaks are counted and decided among them alone.
  struct Candidate {
    const shader::Indicator* indicator;
    std::uint32_t bin;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(std::min(std::size_t{2} * quota, indicator_count()));
  for (std::size_t c = 0; c < chunk_count_; ++c) {
    const Chunk& chunk = chunks_[c];
    for (std::size_t i = 0; i < chunk.list.size(); ++i)
      if (plan.may_admit(chunk.bins[i])) candidates.push_back(Candidate{&chunk.list[i], chunk.bins[i]});
  }
  for (const Candidate& candidate : candidates)
    if (plan.in_tiebreak_bin(candidate.bin)) plan.count_tiebreak(*candidate.indicator);
  plan.plan_tiebreaks();
  std::vector<const shader::Indicator*> kept;
  for (const Candidate& candidate : candidates)
    if (plan.admits(candidate.bin, *candidate.indicator)) kept.push_back(candidate.indicator);
  return canonical_order(kept);
}

}  // namespace sp
