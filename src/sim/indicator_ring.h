// The indicator ring's rules (shaders/shared/sp_ring.h,
// docs/model.md#the-ring-spots-that-live-out-their-lifetime): how long a spot
// is live and drawn, and which of a step's indicators the ring admits: at
// most its quota, the most informative first, so that admitted spots live
// out their lifetime. The CPU backend's ring and writer are in cpu_ring.h.
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

// How long the display shows a spot, and how long it is live:
// indicator_lifetime, but never under SP_MIN_DISPLAY_LIFETIME
// (sp_display_lifetime).
float display_lifetime(const Config& config);

// The step whose picture the display shows, and from which ages count,
// after `steps_run` steps: the last one run.
inline std::uint32_t shown_step(std::uint64_t steps_run) {
  return steps_run > 0 ? static_cast<std::uint32_t>(steps_run - 1) : 0u;
}

// Whether an indicator of step `birth` is live after `steps_run` steps: the
// draw's rule, sp_indicator_live, with the draw's step, dt and lifetime.
// Nothing is live before the first step.
inline bool is_live(std::uint32_t birth, std::uint64_t steps_run, const Config& config) {
  return steps_run > 0 && shader::sp_indicator_live(shown_step(steps_run), birth, static_cast<float>(config.dt),
                                                    config.indicator_lifetime);
}

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
// visited in any order: those of the CPU backend's chunks, unmerged, whose
// admission bins the workers count as they trace (CpuStepOutput).
//
// The phases: count every indicator's bin (admission_bin) into bins(), then
// plan_bins(); count the tie-break bin of each indicator in_tiebreak_bin(),
// then plan_tiebreaks(); then ask admits(). A plan that admits_all() needs
// none of it.
class AdmissionPlan {
 public:
  AdmissionPlan(std::size_t count, std::uint32_t quota, float inverse_indicator_size)
      : quota_(quota), inverse_size_(inverse_indicator_size), all_(count <= quota) {}

  // `for_each(f)` calls f(const shader::Indicator&) once for each of the
  // step's `count` indicators, in any order; it is called twice at most.
  template <class ForEach>
  AdmissionPlan(ForEach&& for_each, std::size_t count, std::uint32_t quota, float inverse_indicator_size)
      : AdmissionPlan(count, quota, inverse_indicator_size) {
    if (all_) return;
    std::uint32_t* histogram = bins();
    for_each([&](const shader::Indicator& ind) { histogram[bin(ind)] += 1; });
    plan_bins();
    for_each([&](const shader::Indicator& ind) {
      if (in_tiebreak_bin(bin(ind))) count_tiebreak(ind);
    });
    plan_tiebreaks();
  }

  bool admits_all() const { return all_; }
  std::uint32_t bin(const shader::Indicator& ind) const { return shader::sp_admission_bin(ind, inverse_size_); }

  // The histogram of admission bins, zero until counted.
  std::uint32_t* bins() { return buffer_.data(); }
  void plan_bins() {
    for (std::uint32_t c = 0; c < SP_ADMISSION_CLASSES; ++c) {
      const std::uint32_t first = shader::sp_section_first(c);
      buffer_[SP_ADMISSION_CLASS_COUNTS + c] =
          shader::sp_admission_count(buffer_.data(), first, first + shader::sp_section_levels(c));
    }
    shader::sp_plan_admission(buffer_.data(), quota_);
  }
  // After plan_bins(): whether indicators of admission bin `bin` may be
  // admitted, at or above their class's overflowing bin; those below never are.
  bool may_admit(std::uint32_t bin) const {
    return bin + 1u >= buffer_[SP_ADMISSION_PLAN_THRESHOLD + shader::sp_bin_class(bin)];
  }
  // After plan_bins(): whether indicators of admission bin `bin` need their
  // tie-break bin counted, and decided by it.
  bool in_tiebreak_bin(std::uint32_t bin) const { return shader::sp_in_tiebreak_bin(buffer_.data(), bin); }
  void count_tiebreak(const shader::Indicator& ind) {
    buffer_[SP_ADMISSION_TIEBREAKS + shader::sp_admission_tiebreak(ind)] += 1;
  }
  void plan_tiebreaks() { shader::sp_plan_tiebreak(buffer_.data(), SP_ADMISSION_CLASSES); }

  // Whether the ring admits `ind`, one of the step's indicators, whose
  // admission bin is `bin`. Its tie-break bin, a hash, matters only in its
  // class's overflowing bin.
  bool admits(std::uint32_t bin, const shader::Indicator& ind) const {
    if (all_) return true;
    const bool tie = in_tiebreak_bin(bin);
    return shader::sp_admitted(buffer_.data(), bin, tie ? shader::sp_admission_tiebreak(ind) : 0u);
  }
  bool admits(const shader::Indicator& ind) const { return all_ || admits(bin(ind), ind); }

 private:
  std::array<std::uint32_t, SP_ADMISSION_BUFFER_SIZE> buffer_{};  // histograms, then the plan
  std::uint32_t quota_;
  float inverse_size_;
  bool all_;  // the whole step fits in the quota
};

// The indicators of `step` (in canonical order) that the ring admits, in
// that order: those whose admission bin is at or above the threshold that
// keeps them within `quota` (sp_admission_threshold).
std::vector<shader::Indicator> admit(std::span<const shader::Indicator> step, std::uint32_t quota,
                                     float inverse_indicator_size);

}  // namespace sp
