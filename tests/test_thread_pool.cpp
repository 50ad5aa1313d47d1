// The CPU backend's fork-join pool: every item is visited once, and an
// exception thrown by a body on any thread reaches the caller of
// parallel_for (instead of std::terminate on a worker), after which the
// pool keeps working.
#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include "sim/thread_pool.h"

namespace {

std::uint64_t sum_of_indices(sp::ThreadPool& pool, std::size_t count) {
  std::vector<std::uint64_t> per_item(count, 0);
  pool.parallel_for(count, 7, [&](std::size_t first, std::size_t last, unsigned) {
    for (std::size_t i = first; i < last; ++i) per_item[i] += i;
  });
  return std::accumulate(per_item.begin(), per_item.end(), std::uint64_t{0});
}

TEST(ThreadPool, VisitsEveryItemOnce) {
  sp::ThreadPool pool(4);
  EXPECT_EQ(pool.size(), 4u);
  EXPECT_EQ(sum_of_indices(pool, 10000), 10000ull * 9999 / 2);
}

TEST(ThreadPool, RethrowsAWorkersExceptionOnTheCaller) {
  sp::ThreadPool pool(4);
  for (int round = 0; round < 20; ++round) {
    std::atomic<int> started{0};
    // Item 500's chunk throws, wherever it runs; which thread that is varies.
    EXPECT_THROW(pool.parallel_for(1000, 10,
                                   [&](std::size_t first, std::size_t last, unsigned) {
                                     started.fetch_add(1);
                                     if (first <= 500 && 500 < last) throw std::runtime_error("chunk 50 failed");
                                   }),
                 std::runtime_error);
    EXPECT_GE(started.load(), 1);
    EXPECT_LE(started.load(), 100);
  }
  EXPECT_EQ(sum_of_indices(pool, 1000), 1000ull * 999 / 2);  // still usable
}

TEST(ThreadPool, RethrowsBadAllocAndOnlyTheFirstOfMany) {
  sp::ThreadPool pool(3);
  std::atomic<int> thrown{0};
  try {
    pool.parallel_for(300, 1, [&](std::size_t, std::size_t, unsigned worker) {
      thrown.fetch_add(1);
      if (worker != 0) throw std::bad_alloc();
      throw std::runtime_error("on the caller");
    });
    FAIL() << "no exception";
  } catch (const std::bad_alloc&) {
  } catch (const std::runtime_error&) {
  }
  // Every thread stops at its first failure: no chunk runs after that.
  EXPECT_LE(thrown.load(), 3);
  EXPECT_EQ(sum_of_indices(pool, 100), 100ull * 99 / 2);
}

TEST(ThreadPool, SingleThreadRunsOnTheCallerAndThrowsThere) {
  sp::ThreadPool pool(1);
  EXPECT_THROW(pool.parallel_for(10, 1, [](std::size_t, std::size_t, unsigned) { throw std::logic_error("x"); }),
               std::logic_error);
  EXPECT_EQ(sum_of_indices(pool, 50), 50ull * 49 / 2);
}

// Calls that follow each other closely find the workers spinning rather
// than asleep (kSpinWait); calls after a pause find them asleep. Both must
// visit every item once, and a pool destroyed while its workers spin, or
// right after it was made, must stop them.
TEST(ThreadPool, BackToBackCallsAndPausesAndQuickDestruction) {
  {
    sp::ThreadPool pool(3);
    for (std::size_t call = 0; call < 2000; ++call)
      ASSERT_EQ(sum_of_indices(pool, 64 + call % 50), (64 + call % 50) * (63 + call % 50) / 2) << "call " << call;
    for (int call = 0; call < 3; ++call) {
      std::this_thread::sleep_for(2 * sp::kSpinWait);
      ASSERT_EQ(sum_of_indices(pool, 500), 500ull * 499 / 2);
    }
  }                                                     // destroyed while its workers spin after the last call
  for (int i = 0; i < 50; ++i) sp::ThreadPool pool(4);  // destroyed before its workers ever ran
}

}  // namespace
