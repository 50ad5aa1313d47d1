// One step of the CPU backend on a thread pool, given its plan: the part of
// the CPU simulator that can run on a worker thread while the host goes on
// (the visualizer runs it one step ahead of the frame it draws).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "sim/cpu_tracer.h"
#include "sim/step_plan.h"
#include "sim/thread_pool.h"
#include "soundpaint/simulation.h"

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
// (bench/RESULTS.md sections 14 and 16).
class CpuStepOutput {
 public:
  TraceCounters counters;  // summed over the workers

  std::size_t indicator_count() const;
  // Every indicator, in canonical order.
  std::vector<shader::Indicator> canonical() const;
  // admit(canonical(), quota, inverse_indicator_size), without merging the
  // indicators the ring does not admit.
  std::vector<shader::Indicator> admitted(std::uint32_t quota, float inverse_indicator_size) const;

 private:
  friend class CpuStepRunner;
  struct alignas(kCacheLine) Chunk {
    DefaultInitVector<shader::Indicator> list;
  };

  // Calls visit(indicator) for each indicator, chunk by chunk.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (std::size_t c = 0; c < chunk_count_; ++c)
      for (const shader::Indicator& ind : chunks_[c].list) visit(ind);
  }
  // The indicators that `keep` selects, in canonical order.
  template <class Keep>
  std::vector<shader::Indicator> canonical_where(Keep&& keep) const;

  std::vector<Chunk> chunks_;  // the first chunk_count_ hold this step's
  std::size_t chunk_count_ = 0;
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
  void run(const Bvh& bvh, std::span<const shader::LayerAcoustics> layers, const StepPlan& plan,
           const shader::SimParams& params, CpuStepOutput& out, const EmbreeTraversal* embree = nullptr);

 private:
  struct alignas(kCacheLine) WorkerCounters {
    TraceCounters counters;
  };

  ThreadPool pool_;
  std::size_t layer_count_;
  std::vector<WorkerCounters> worker_counters_;
};

}  // namespace sp
