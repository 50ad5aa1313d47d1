// The indicator ring and its admission rule (shaders/shared/sp_ring.h,
// docs/model.md#the-ring-spots-that-live-out-their-lifetime): each step admits
// at most its quota of the step's indicators, the most informative first, so
// that admitted spots live out their lifetime; the oldest slots are
// overwritten.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "soundpaint/simulation.h"
#include "sp_types.h"

namespace sp {

// How long the display shows a spot: indicator_lifetime, but never under
// SP_MIN_DISPLAY_LIFETIME (sp_ring.h).
float display_lifetime(const Config& config);

// How many of a step's indicators the ring admits: ceil(capacity * dt /
// display lifetime), in [1, capacity], so that the ring turns over once per
// lifetime.
std::uint32_t ring_quota(const Config& config);

// 1 / indicator_size, or 0 when indicator_size is 0 (every spot is then
// invisible and equally informative).
float inverse_indicator_size(const Config& config);

// The indicators of `step` (in canonical order) that the ring admits, in
// that order: those whose admission bin is at or above the threshold that
// keeps them within `quota` (sp_admission_threshold).
std::vector<shader::Indicator> admit(std::span<const shader::Indicator> step, std::uint32_t quota,
                                     float inverse_indicator_size);

class IndicatorRing {
 public:
  explicit IndicatorRing(std::uint32_t capacity) : slots_(capacity) {}

  // Appends in order; when more than capacity arrive, only the newest stay.
  void push(std::span<const shader::Indicator> indicators);

  // Indicators still visible at step `now`: age (now - birth) * dt below
  // `lifetime`, oldest first.
  std::vector<shader::Indicator> live(std::uint64_t now, double dt, double lifetime) const;

  std::uint64_t total_pushed() const { return total_; }
  std::uint32_t capacity() const { return static_cast<std::uint32_t>(slots_.size()); }

 private:
  std::vector<shader::Indicator> slots_;
  std::uint64_t total_ = 0;  // slot of the next push is total_ % capacity
};

}  // namespace sp
