// The indicator ring and its admission rule (shaders/shared/sp_ring.h,
// docs/model.md#the-ring-spots-that-live-out-their-lifetime): each step admits
// at most its quota of the step's indicators, the most informative first, so
// that admitted spots live out their lifetime; the oldest slots are
// overwritten.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "soundpaint/simulation.h"
#include "sp_admission.h"
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

// Which of a step's indicators the ring admits: the GPU's admit.comp, phase
// by phase. Each indicator's fate follows from histograms over the whole
// step and from the indicator alone, so the step's indicators may be
// visited in any order: those of the CPU backend's chunks, unmerged.
class AdmissionPlan {
 public:
  // `for_each(f)` calls f(const shader::Indicator&) once for each of the
  // step's `count` indicators, in any order; it is called twice at most.
  template <class ForEach>
  AdmissionPlan(ForEach&& for_each, std::size_t count, std::uint32_t quota, float inverse_indicator_size)
      : inverse_size_(inverse_indicator_size), all_(count <= quota) {
    if (all_) return;
    std::uint32_t* histogram = buffer_.data();
    for_each([&](const shader::Indicator& ind) { histogram[shader::sp_admission_bin(ind, inverse_size_)] += 1; });
    shader::sp_plan_admission(histogram, quota);
    std::fill_n(histogram, SP_ADMISSION_BINS, 0u);
    for_each([&](const shader::Indicator& ind) {
      if (shader::sp_in_tiebreak_bin(histogram, shader::sp_admission_bin(ind, inverse_size_)))
        histogram[shader::sp_admission_tiebreak(ind)] += 1;
    });
    shader::sp_plan_tiebreak(histogram, SP_ADMISSION_CLASSES);
  }

  // Whether the ring admits `ind`, one of the step's indicators. Its
  // tie-break bin, a hash, matters only in its class's overflowing bin.
  bool admits(const shader::Indicator& ind) const {
    if (all_) return true;
    const std::uint32_t bin = shader::sp_admission_bin(ind, inverse_size_);
    const bool tie = shader::sp_in_tiebreak_bin(buffer_.data(), bin);
    return shader::sp_admitted(buffer_.data(), bin, tie ? shader::sp_admission_tiebreak(ind) : 0u);
  }

 private:
  std::array<std::uint32_t, SP_ADMISSION_BUFFER_SIZE> buffer_{};  // histogram, then the plan
  float inverse_size_;
  bool all_;  // the whole step fits in the quota
};

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
