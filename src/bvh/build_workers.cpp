#include "bvh/build_workers.h"

#include <algorithm>
#include <thread>

#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__) || defined(_M_IX86)
#include <immintrin.h>
#endif

namespace sp {
namespace {

// Tells the core this thread is spinning: it lets a sibling hyperthread
// run and saves power.
void cpu_relax() {
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__) || defined(_M_IX86)
  _mm_pause();
#elif defined(__aarch64__)
  __asm__ __volatile__("yield");
#endif
}

}  // namespace

template <class Ready>
bool BuildWorkers::spin_until(Ready ready) {
  const auto until = std::chrono::steady_clock::now() + kSpinBeforeSleep;
  for (;;) {
    // Reading the clock costs more than a check: check in rounds.
    for (int i = 0; i < 64; ++i) {
      if (ready()) return true;
      cpu_relax();
    }
    if (std::chrono::steady_clock::now() >= until) return ready();
    // With more threads than cores, let a thread with work run.
    std::this_thread::yield();
  }
}

BuildWorkers::BuildWorkers(unsigned threads) {
  if (threads <= 1u) return;
  // Reserved first, so that no growth can throw while threads run: a
  // joinable std::thread destroyed by an unwinding vector terminates.
  threads_.reserve(threads - 1u);
  for (unsigned i = 1; i < threads; ++i) {
    try {
      threads_.emplace_back([this] { thread_loop(); });
    } catch (...) {  // std::system_error, or std::bad_alloc for the thread's state
      break;         // fewer threads: run_both still runs everything
    }
  }
}

BuildWorkers::~BuildWorkers() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void BuildWorkers::offer(Task& task) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(&task);
    queued_.store(queue_.size(), std::memory_order_release);
  }
  changed_.notify_one();
}

void BuildWorkers::execute(Task& task) {
  try {
    task.run(task.body);
  } catch (...) {
    task.failure = std::current_exception();
  }
  {
    std::lock_guard lock(mutex_);
    task.done = true;
  }
  changed_.notify_all();
}

void BuildWorkers::finish(Task& task) {
  std::unique_lock lock(mutex_);
  if (const auto queued = std::find(queue_.begin(), queue_.end(), &task); queued != queue_.end()) {
    queue_.erase(queued);
    queued_.store(queue_.size(), std::memory_order_release);
    lock.unlock();
    // Nobody took it: run it here, as a serial build would. Its exception
    // is kept in the task like any other's.
    try {
      task.run(task.body);
    } catch (...) {
      task.failure = std::current_exception();
    }
    return;
  }
  while (!task.done) {
    if (!queue_.empty()) {
      // Help rather than idle: the newest task is the smallest piece of
      // the nesting, the one most likely done before `task` is.
      Task* other = queue_.back();
      queue_.pop_back();
      queued_.store(queue_.size(), std::memory_order_release);
      lock.unlock();
      execute(*other);
      lock.lock();
      continue;
    }
    lock.unlock();
    const bool seen = spin_until(
        [&] { return task.done.load(std::memory_order_acquire) || queued_.load(std::memory_order_acquire) > 0u; });
    lock.lock();
    // Work seen but taken by another thread meanwhile: spin again, since
    // work is still being handed out; sleep only after a whole quiet spin.
    if (task.done || !queue_.empty() || seen) continue;
    changed_.wait(lock);
  }
}

void BuildWorkers::thread_loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (!stopping_ && queue_.empty()) {
      lock.unlock();
      const bool seen = spin_until(
          [this] { return stopping_.load(std::memory_order_acquire) || queued_.load(std::memory_order_acquire) > 0u; });
      lock.lock();
      // As in finish(): a task another thread took first is no reason to
      // sleep.
      if (seen && !stopping_ && queue_.empty()) continue;
    }
    changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    // The oldest task is the largest: the nearest the root.
    Task* task = queue_.front();
    queue_.pop_front();
    queued_.store(queue_.size(), std::memory_order_release);
    lock.unlock();
    execute(*task);
    lock.lock();
  }
}

}  // namespace sp
