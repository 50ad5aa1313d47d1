// Turns the host's variable frame times into the simulation's fixed steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sp::embed {

class FrameClock {
 public:
  FrameClock(double step_seconds, std::uint32_t max_steps_per_frame)
      : step_seconds_(step_seconds), max_steps_(max_steps_per_frame) {}

  // Adds `dt` seconds and returns the whole steps now due, at most
  // max_steps_per_frame; time beyond that is dropped so that a long hitch
  // does not make every later frame catch up.
  std::uint32_t advance(double dt) {
    carried_ += dt;
    // A frame of exactly one step must not lose it to rounding.
    const double due = std::floor(carried_ / step_seconds_ + 1e-9);
    const auto steps = static_cast<std::uint32_t>(std::min(due, static_cast<double>(max_steps_)));
    carried_ = std::max(0.0, carried_ - static_cast<double>(steps) * step_seconds_);
    // Capped: keep only the fraction of a step, so the frame after a hitch
    // runs no extra step either.
    const double whole = std::floor(carried_ / step_seconds_ + 1e-9);
    carried_ = std::max(0.0, carried_ - whole * step_seconds_);
    return steps;
  }

 private:
  double step_seconds_;
  std::uint32_t max_steps_;
  double carried_ = 0.0;
};

}  // namespace sp::embed
