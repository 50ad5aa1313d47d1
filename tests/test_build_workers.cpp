// The BVH build's fork-join: every forked task runs exactly once, whether
// another thread takes it or its owner runs it back; nested forks (a
// subtree forking again) finish without deadlock; and an exception from
// either side reaches the caller only after both sides are done.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <thread>
#include <vector>

#include "bvh/build_workers.h"

namespace {

// Sums [first, last) by halving down to 16 items, forking at every level,
// the way a build forks its subtrees.
std::uint64_t forked_sum(sp::BuildWorkers& workers, std::vector<int>& visits, std::uint32_t first, std::uint32_t last) {
  if (last - first <= 16u) {
    std::uint64_t sum = 0;
    for (std::uint32_t i = first; i < last; ++i) {
      ++visits[i];
      sum += i;
    }
    return sum;
  }
  const std::uint32_t mid = first + (last - first) / 2u;
  std::uint64_t upper = 0, lower = 0;
  workers.run_both([&] { upper = forked_sum(workers, visits, mid, last); },
                   [&] { lower = forked_sum(workers, visits, first, mid); });
  return lower + upper;
}

TEST(BuildWorkers, NestedForksVisitEveryItemOnce) {
  for (unsigned threads : {1u, 2u, 4u}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    sp::BuildWorkers workers(threads);
    EXPECT_GE(workers.size(), 1u);
    EXPECT_LE(workers.size(), threads);
    constexpr std::uint32_t kCount = 20000;
    std::vector<int> visits(kCount, 0);
    EXPECT_EQ(forked_sum(workers, visits, 0, kCount), std::uint64_t{kCount} * (kCount - 1u) / 2u);
    for (std::uint32_t i = 0; i < kCount; ++i) ASSERT_EQ(visits[i], 1) << "item " << i;
  }
}

TEST(BuildWorkers, OfferedTasksRunOnAnotherThreadWhenOneIsFree) {
  sp::BuildWorkers workers(2);
  ASSERT_EQ(workers.size(), 2u);
  // `b` waits until `a` has started: that can only happen if another
  // thread took `a`, since this one runs `b` first. (A bug that never hands
  // tasks over hangs here; the test's timeout catches it.)
  std::atomic<bool> a_started{false};
  std::thread::id a_thread;
  workers.run_both(
      [&] {
        a_thread = std::this_thread::get_id();
        a_started = true;
      },
      [&] {
        while (!a_started) std::this_thread::yield();
      });
  EXPECT_NE(a_thread, std::this_thread::get_id());
}

TEST(BuildWorkers, RethrowsEitherSidesExceptionAfterBothFinish) {
  sp::BuildWorkers workers(2);
  for (int round = 0; round < 50; ++round) {
    std::atomic<int> finished{0};
    EXPECT_THROW(workers.run_both([&] { throw std::runtime_error("a failed"); }, [&] { ++finished; }),
                 std::runtime_error);
    EXPECT_EQ(finished, 1);
    // `a` is still running (or queued) when `b` throws: run_both must wait
    // for it, since it uses this frame.
    EXPECT_THROW(workers.run_both(
                     [&] {
                       std::this_thread::sleep_for(std::chrono::microseconds(50));
                       ++finished;
                     },
                     [&] { throw std::length_error("b failed"); }),
                 std::length_error);
    EXPECT_EQ(finished, 2);
  }
  // Still usable afterwards.
  std::vector<int> visits(1000, 0);
  EXPECT_EQ(forked_sum(workers, visits, 0, 1000), 1000u * 999u / 2u);
}

}  // namespace
