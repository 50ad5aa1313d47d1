#include "embed/cpu_step_thread.h"
#include "sp_types.h"

#include <chrono>

namespace sp::embed {

CpuStepThread::CpuStepThread(unsigned threads, std::size_t layer_count)
    : runner_(threads, layer_count), thread_([this] { loop(); }) {}

CpuStepThread::~CpuStepThread() {
  {
    const std::lock_guard lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void CpuStepThread::start(const Bvh& bvh, std::span<const shader::LayerAcoustics> layers, StepPlan plan,
                          const shader::SimParams& params, float inverse_indicator_size,
                          const EmbreeTraversal* embree) {
  {
    const std::lock_guard lock(mutex_);
    bvh_ = &bvh;
    embree_ = embree;
    layers_ = layers;
    plan_ = std::move(plan);
    params_ = params;
    inverse_indicator_size_ = inverse_indicator_size;
    error_ = nullptr;
    state_ = State::Running;
  }
  changed_.notify_all();
}

bool CpuStepThread::idle() const {
  const std::lock_guard lock(mutex_);
  return state_ == State::Idle;
}

const CpuStepOutput* CpuStepThread::poll() {
  const std::lock_guard lock(mutex_);
  if (state_ != State::Done) return nullptr;
  if (error_) {
    state_ = State::Idle;
    std::rethrow_exception(std::exchange(error_, nullptr));
  }
  return &output_;
}

void CpuStepThread::release() {
  const std::lock_guard lock(mutex_);
  if (state_ == State::Done) state_ = State::Idle;
}

double CpuStepThread::last_step_ms() const {
  std::lock_guard lock(mutex_);
  return last_step_ms_;
}

void CpuStepThread::wait() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return state_ != State::Running; });
}

void CpuStepThread::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return quit_ || state_ == State::Running; });
    if (state_ != State::Running) return;  // quit while idle
    lock.unlock();
    std::exception_ptr error;
    const auto started = std::chrono::steady_clock::now();
    try {
      runner_.run(*bvh_, layers_, plan_, params_, inverse_indicator_size_, output_, embree_);
    } catch (...) {
      error = std::current_exception();
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
    lock.lock();
    last_step_ms_ = ms;
    error_ = error;
    state_ = State::Done;
    changed_.notify_all();
    if (quit_) return;
  }
}

}  // namespace sp::embed
