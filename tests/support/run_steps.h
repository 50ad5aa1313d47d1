// Runs a simulator for some steps and keeps what the tests look at.
#pragma once

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

}  // namespace sp::test
