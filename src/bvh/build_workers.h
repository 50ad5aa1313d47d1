// Fork-join for one BVH build: its threads are started once, when the build
// starts, and work is handed to them through a queue.
//
// Why not a thread per fork (std::async): on the 2-vCPU benchmark VM a new
// thread started running 0.3-1.7 ms after it was asked for, while a waiting
// thread woke in ~4 us (bench/RESULTS.md section 17). A build forks a dozen
// times, so starting threads cost as much as the second core saved.
//
// run_both(a, b) offers `a` to the other threads and runs `b` here; if no
// one has taken `a` by then, it runs here too. A thread waiting for a task
// that another took runs other queued tasks meanwhile, so calls nest (a
// subtree's build forks again) without idling or deadlock. Where a task runs
// never changes what it computes.
//
// A thread with nothing to do spins for a while (kSpinBeforeSleep) before it
// sleeps: a build hands out work every few hundred microseconds, and on the
// benchmark VM waking a thread that had gone to sleep took 4-8 ms in about
// one build of three (bench/RESULTS.md section 24).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace sp {

class BuildWorkers {
 public:
  // `threads` counts the calling thread; 1 runs everything on the caller. A
  // thread that cannot be started is done without.
  explicit BuildWorkers(unsigned threads);
  ~BuildWorkers();
  BuildWorkers(const BuildWorkers&) = delete;
  BuildWorkers& operator=(const BuildWorkers&) = delete;

  // Threads that run tasks, the caller included.
  unsigned size() const { return static_cast<unsigned>(threads_.size()) + 1u; }

  // Runs `a` and `b`, `a` possibly on another thread; returns when both are
  // done. An exception from either is rethrown here once both have
  // finished (b's first), so neither outlives the caller's frame.
  template <class A, class B>
  void run_both(A&& a, B&& b) {
    if (threads_.empty()) {
      a();
      b();
      return;
    }
    Task task{&call<std::remove_reference_t<A>>, &a};
    offer(task);
    std::exception_ptr b_failure;
    try {
      b();
    } catch (...) {
      b_failure = std::current_exception();
    }
    finish(task);
    if (b_failure) std::rethrow_exception(b_failure);
    if (task.failure) std::rethrow_exception(task.failure);
  }

 private:
  struct Task {
    void (*run)(void* body);
    void* body;
    std::atomic<bool> done = false;        // set under mutex_, read by spinners without it
    std::exception_ptr failure = nullptr;  // set by the thread that ran it
  };

  template <class F>
  static void call(void* body) {
    (*static_cast<F*>(body))();
  }

  // How long a thread without work polls for it before it sleeps.
  static constexpr std::chrono::microseconds kSpinBeforeSleep{2000};

  void offer(Task& task);
  // Polls, without the mutex, until `ready()` or kSpinBeforeSleep has
  // passed; returns ready().
  template <class Ready>
  static bool spin_until(Ready ready);
  // Runs `task` here if it is still queued, else waits for it, running
  // other queued tasks meanwhile.
  void finish(Task& task);
  void execute(Task& task);
  void thread_loop();

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable changed_;  // a task was queued or finished, or stopping_
  std::deque<Task*> queue_;
  std::atomic<std::size_t> queued_ = 0;  // queue_.size(), for spinners
  std::atomic<bool> stopping_ = false;
};

}  // namespace sp
