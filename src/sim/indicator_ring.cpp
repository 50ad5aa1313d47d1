#include "sim/indicator_ring.h"

#include <algorithm>
#include <cmath>

namespace sp {

float display_lifetime(const Config& config) { return std::max(config.indicator_lifetime, SP_MIN_DISPLAY_LIFETIME); }

std::uint32_t ring_quota(const Config& config) {
  const double per_lifetime = static_cast<double>(display_lifetime(config)) / config.dt;
  const double quota = std::ceil(static_cast<double>(config.max_indicators) / std::max(per_lifetime, 1.0));
  return static_cast<std::uint32_t>(std::clamp(quota, 1.0, static_cast<double>(config.max_indicators)));
}

float inverse_indicator_size(const Config& config) {
  return config.indicator_size > 0.0f ? 1.0f / config.indicator_size : 0.0f;
}

std::vector<shader::Indicator> admit(std::span<const shader::Indicator> step, std::uint32_t quota,
                                     float inverse_indicator_size) {
  const AdmissionPlan plan(
      [&](auto&& visit) {
        for (const shader::Indicator& ind : step) visit(ind);
      },
      step.size(), quota, inverse_indicator_size);
  std::vector<shader::Indicator> admitted;
  admitted.reserve(std::min<std::size_t>(quota, step.size()));
  for (const shader::Indicator& ind : step)
    if (plan.admits(ind)) admitted.push_back(ind);
  return admitted;
}

void IndicatorRing::push(std::span<const shader::Indicator> indicators) {
  const std::uint64_t capacity = slots_.size();
  if (indicators.size() > capacity) {
    total_ += indicators.size() - capacity;
    indicators = indicators.last(capacity);
  }
  for (const shader::Indicator& indicator : indicators) {
    slots_[total_ % capacity] = indicator;
    ++total_;
  }
}

std::vector<shader::Indicator> IndicatorRing::live(std::uint64_t now, double dt, double lifetime) const {
  const std::uint64_t capacity = slots_.size();
  const std::uint64_t stored = std::min(total_, capacity);
  std::vector<shader::Indicator> result;
  for (std::uint64_t k = total_ - stored; k < total_; ++k) {
    const shader::Indicator& indicator = slots_[k % capacity];
    // The draw's age and rule (sp_ring.h): what is live is what is drawn.
    const float age = shader::sp_indicator_age(static_cast<std::uint32_t>(now), indicator.step, static_cast<float>(dt));
    if (age < static_cast<float>(lifetime)) result.push_back(indicator);
  }
  return result;
}

}  // namespace sp
