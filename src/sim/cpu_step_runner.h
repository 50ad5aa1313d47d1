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

struct CpuStepOutput {
  std::vector<shader::Indicator> indicators;  // canonical order: iteration, then ray index
  TraceCounters counters;                     // summed over the workers
};

class CpuStepRunner {
 public:
  // `threads` as CpuSettings::threads.
  CpuStepRunner(unsigned threads, std::size_t layer_count);

  unsigned threads() const { return pool_.size(); }

  // Casts every ray of `plan` through `bvh`. Results are independent of the
  // thread count: every random number is keyed by (seed, step, ray,
  // interaction) and indicators are merged in canonical order. `bvh`,
  // `layers` and `plan` must not change during the call. With `embree`
  // (built over `bvh`), rays cast to the nearest surface through it.
  void run(const Bvh& bvh, std::span<const shader::LayerAcoustics> layers, const StepPlan& plan,
           const shader::SimParams& params, CpuStepOutput& out, const EmbreeTraversal* embree = nullptr);

 private:
  void merge_in_canonical_order(std::size_t chunks, std::vector<shader::Indicator>& out) const;

  // What workers write on every cast sits on cache lines of its own: with
  // two workers' counters, or two chunks' list headers, side by side, each
  // write stalled on the line the other core had just taken (on 2 threads,
  // perf put 30 % of the step in trace_ray, half of it on the `casts`
  // increment; bench/RESULTS.md section 14).
  static constexpr std::size_t kCacheLine = 64;
  struct alignas(kCacheLine) WorkerCounters {
    TraceCounters counters;
  };
  struct alignas(kCacheLine) ChunkIndicators {
    DefaultInitVector<shader::Indicator> list;
  };

  ThreadPool pool_;
  std::size_t layer_count_;
  std::vector<WorkerCounters> worker_counters_;
  std::vector<ChunkIndicators> chunk_indicators_;
};

}  // namespace sp
