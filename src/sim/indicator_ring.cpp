#include "sim/indicator_ring.h"

#include <algorithm>
#include <cmath>

namespace sp {

float display_lifetime(const Config& config) { return shader::sp_display_lifetime(config.indicator_lifetime); }

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

}  // namespace sp
