// The CPU backend one step ahead: a step runs on its own thread (and the
// runner's pool) while the render thread goes on; the render thread polls
// and takes the result without blocking.
#pragma once

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "sim/cpu_step_runner.h"
#include "sp_types.h"

namespace sp::embed {

class CpuStepThread {
 public:
  CpuStepThread(unsigned threads, std::size_t layer_count);
  ~CpuStepThread();  // waits for a running step, then joins
  CpuStepThread(const CpuStepThread&) = delete;
  CpuStepThread& operator=(const CpuStepThread&) = delete;

  // Starts a step. Precondition: idle(). `bvh` and `layers` must stay
  // unchanged until the result is taken.
  // With `embree` (over `bvh`, unchanged likewise) rays cast through it.
  // `inverse_indicator_size` as CpuStepRunner::run.
  void start(const Bvh& bvh, std::span<const shader::LayerAcoustics> layers, StepPlan plan,
             const shader::SimParams& params, float inverse_indicator_size, const EmbreeTraversal* embree = nullptr);

  bool idle() const;  // no step running, no result waiting
  // The finished step's output, or null while it runs (never blocks).
  // Rethrows an exception the step threw. Valid until release().
  const CpuStepOutput* poll();
  void release();  // the output was used: idle again
  void wait();     // blocks until the running step (if any) finished
  // Wall milliseconds of the last finished step, 0 before the first.
  double last_step_ms() const;

 private:
  enum class State { Idle, Running, Done };
  void loop();

  CpuStepRunner runner_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  State state_ = State::Idle;
  bool quit_ = false;
  const Bvh* bvh_ = nullptr;
  const EmbreeTraversal* embree_ = nullptr;
  std::span<const shader::LayerAcoustics> layers_;
  StepPlan plan_;
  shader::SimParams params_{};
  float inverse_indicator_size_ = 0.0f;
  CpuStepOutput output_;
  double last_step_ms_ = 0.0;
  std::exception_ptr error_;
  std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace sp::embed
