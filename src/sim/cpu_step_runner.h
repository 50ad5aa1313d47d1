// One step of the CPU backend on a thread pool, given its plan: the part of
// the CPU simulator that can run on a worker thread while the host goes on
// (the visualizer runs it one step ahead of the frame it draws).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "sim/cpu_tracer.h"
#include "sim/step_plan.h"
#include "sim/thread_pool.h"
#include "soundpaint/simulation.h"
#include "sp_ring.h"

namespace sp {

// What workers write on every cast sits on cache lines of its own: with
// two workers' counters, or two chunks' list headers, side by side, each
// write stalled on the line the other core had just taken (on 2 threads,
// perf put 30 % of the step in trace_ray, half of it on the `casts`
// increment; bench/RESULTS.md section 14).
inline constexpr std::size_t kCacheLine = 64;

// A step's indicators as the workers left them: in chunks of consecutive
// rays, each chunk's rays in ascending order and each ray's indicators in
// ascending iteration. They are put in canonical order (iteration, then ray
// index) only for whoever asks: the ring admits tens or hundreds of a
// step's thousands (67 of 8,800 on the paper's workload), and merging all
// of them on every step was ~0.09 ms of serial work in a 1.6 ms step
// (bench/RESULTS.md sections 14 and 16). The workers also count each
// indicator's admission bin as they go, so that admitting the step is
// a pass over 2-byte bins on the calling thread rather than three over
// the 96-byte indicators (another 0.09 ms, section 19).
class CpuStepOutput {
 public:
  TraceCounters counters;  // summed over the workers

  std::size_t indicator_count() const;
  // Every indicator, in canonical order.
  std::vector<shader::Indicator> canonical() const;
  // admit(canonical(), quota, inverse_indicator_size), without merging the
  // indicators the ring does not admit; from the workers' bins when
  // `inverse_indicator_size` is the one the step ran with.
  std::vector<shader::Indicator> admitted(std::uint32_t quota, float inverse_indicator_size) const;

  // Frees the chunks that steps of at most `rays` rays never fill, once
  // set_config lowered the ray budget; the last step's are kept.
  void release_beyond(std::uint32_t rays);

 private:
  friend class CpuStepRunner;
  struct alignas(kCacheLine) Chunk {
    DefaultInitVector<shader::Indicator> list;
    DefaultInitVector<std::uint16_t> bins;  // list[i]'s admission bin
  };
  static_assert(SP_ADMISSION_BINS <= 65536u, "a bin fits in Chunk::bins");
  using BinCounts = std::array<std::uint32_t, SP_ADMISSION_BINS>;
  // One worker's count of the admission bins of the chunks it traced.
  struct alignas(kCacheLine) WorkerBins {
    BinCounts count;
  };

  // Calls visit(indicator) for each indicator, chunk by chunk.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (std::size_t c = 0; c < chunk_count_; ++c)
      for (const shader::Indicator& ind : chunks_[c].list) visit(ind);
  }
  // Fills chunk c's bins and counts them into `counts`.
  void count_bins(std::size_t c, float inverse_indicator_size, BinCounts& counts);
  // The indicators that `keep(indicator)` selects, in canonical order.
  template <class Keep>
  std::vector<shader::Indicator> canonical_where(Keep&& keep) const;
  // Copies of `kept`, indicators listed in chunk order, in canonical order.
  static std::vector<shader::Indicator> canonical_order(std::span<const shader::Indicator* const> kept);

  std::vector<Chunk> chunks_;  // the first chunk_count_ hold this step's
  std::size_t chunk_count_ = 0;
  std::vector<WorkerBins> worker_bins_;  // per worker, summed into bins_ after the step
  BinCounts bins_{};
  // Whether the chunks' bins and bins_ hold this step's, binned with
  // binned_inverse_size_ (not after a step that threw); otherwise, or asked
  // with another size, admitted() bins anew.
  bool binned_ = false;
  float binned_inverse_size_ = 0.0f;
};

class CpuStepRunner {
 public:
  // `threads` as CpuSettings::threads.
  CpuStepRunner(unsigned threads, std::size_t layer_count);

  unsigned threads() const { return pool_.size(); }

  // Casts every ray of `plan` through `bvh`. Results are independent of the
  // thread count: every random number is keyed by (seed, step, ray,
  // interaction) and chunks hold fixed ranges of rays. `bvh`,
  // `layers` and `plan` must not change during the call. With `embree`
  // (built over `bvh`), rays cast to the nearest surface through it.
  // Indicators are binned for the ring's admission with
  // `inverse_indicator_size` (the ring's; indicator_ring.h), which
  // CpuStepOutput::admitted then takes as given.
  void run(const Bvh& bvh, std::span<const shader::LayerAcoustics> layers, const StepPlan& plan,
           const shader::SimParams& params, float inverse_indicator_size, CpuStepOutput& out,
           const EmbreeTraversal* embree = nullptr);

 private:
  struct alignas(kCacheLine) WorkerCounters {
    TraceCounters counters;
    // Per step-source slot and guide cell: what this worker's heard spots
    // add to their sources' guides.
    std::vector<std::uint32_t> guide_pending;
  };

  // Grows the guides to the plan's source ids, and folds each planned
  // source's pending weights into its guide (sp_guide_fold).
  void fold_guides(const StepPlan& plan);

  ThreadPool pool_;
  std::size_t layer_count_;
  std::vector<WorkerCounters> worker_counters_;
  // Every source's guide (sp_guide.h), by source id: what the rays of its
  // earlier steps found the player hears.
  std::vector<std::uint32_t> guides_;
};

}  // namespace sp
