// The ring buffer of SPEC 1.4: max_indicators entries, the oldest overwritten.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "soundpaint/simulation.h"

namespace sp {

class IndicatorRing {
 public:
  explicit IndicatorRing(std::uint32_t capacity) : slots_(capacity) {}

  // Appends in order; when more than capacity arrive, only the newest stay.
  void push(std::span<const Indicator> indicators);

  // Indicators still visible at step `now`: age (now - birth) * dt below
  // `lifetime`, oldest first.
  std::vector<Indicator> live(std::uint64_t now, double dt, double lifetime) const;

  std::uint64_t total_pushed() const { return total_; }
  std::uint32_t capacity() const { return static_cast<std::uint32_t>(slots_.size()); }

 private:
  std::vector<Indicator> slots_;
  std::uint64_t total_ = 0;  // slot of the next push is total_ % capacity
};

}  // namespace sp
