// Runs a simulator for some steps and keeps what the tests look at.
#pragma once

#include <algorithm>
#include <cstring>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "soundpaint/simulation.h"

namespace sp::test {

struct Recorded {
  std::vector<Indicator> indicators;  // every indicator created, step by step
  std::vector<Indicator> live;        // the ring's visible ones after the last step
  SimulationStats stats;
};

inline Recorded run_steps(Simulator& sim, std::uint64_t steps) {
  Recorded out;
  for (std::uint64_t n = 0; n < steps; ++n) {
    EXPECT_TRUE(sim.step().ok());
    auto step = sim.last_step_indicators().value();
    out.indicators.insert(out.indicators.end(), step.begin(), step.end());
  }
  out.live = sim.live_indicators().value();
  out.stats = sim.stats().value();
  return out;
}

// Indicators in (step, iteration, ray, kind) order: a GPU step writes its
// own in the order its subgroups finish.
inline void sort_indicators(std::vector<Indicator>& indicators) {
  std::sort(indicators.begin(), indicators.end(), [](const Indicator& a, const Indicator& b) {
    return std::tie(a.step, a.iteration, a.ray_index, a.kind) < std::tie(b.step, b.iteration, b.ray_index, b.kind);
  });
}

// The same indicators, byte for byte, in the same order.
inline void expect_same_bytes(const std::vector<Indicator>& got, const std::vector<Indicator>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    ASSERT_EQ(std::memcmp(&got[i], &want[i], sizeof(Indicator)), 0) << "indicator " << i;
}

}  // namespace sp::test
