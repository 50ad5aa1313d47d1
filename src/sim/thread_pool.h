// A fork-join pool for the CPU backend: one parallel_for per step, the
// calling thread working alongside the workers.
//
// Waits spin for a short while (kSpinWait) before they sleep. On the
// 2-vCPU VM of bench/RESULTS.md, a thread asleep on a condition variable
// ran again 40-50 us after it was notified, in a paper-workload step of
// about 1.1 ms: the caller, done with its chunks, slept through the
// worker's last one and then that long again; a worker slept through the
// start of the next step (section 19). The price: after each call every
// worker keeps one core busy for up to kSpinWait, time a host's other
// threads (its render thread, say) do not get on a small machine.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sp {

// How long a thread that waits for the others spins before it sleeps.
inline constexpr std::chrono::microseconds kSpinWait{50};

class ThreadPool {
 public:
  // `threads` counts the calling thread; 0 means hardware_concurrency().
  explicit ThreadPool(unsigned threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()) + 1; }

  using Body = std::function<void(std::size_t first, std::size_t last, unsigned worker)>;

  // Calls body over [0, count) in chunks of `grain` items; `worker` is in
  // [0, size()) and no two concurrent calls share one. Returns when all
  // chunks are done. Chunks are claimed dynamically, so which worker runs
  // which chunk varies: bodies must write to per-chunk or per-worker storage.
  // If a body throws (std::bad_alloc, say), no further chunk is started,
  // the running ones finish, and the first exception is rethrown here on
  // the calling thread: nothing escapes a worker, which would terminate
  // the host process. The pool stays usable.
  void parallel_for(std::size_t count, std::size_t grain, const Body& body);

 private:
  void worker_loop(unsigned worker);
  void run_chunks(unsigned worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  // Written under mutex_; atomic so that a spinning thread may read them.
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<unsigned> busy_workers_{0};
  std::atomic<bool> stopping_{false};

  const Body* body_ = nullptr;
  std::size_t count_ = 0;
  std::size_t grain_ = 1;
  std::atomic<std::size_t> next_{0};
  std::exception_ptr failure_;  // the first body exception of this call (under mutex_)
};

}  // namespace sp
