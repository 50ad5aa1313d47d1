#include "sim/indicator_ring.h"

#include <algorithm>

namespace sp {

void IndicatorRing::push(std::span<const Indicator> indicators) {
  const std::uint64_t capacity = slots_.size();
  if (indicators.size() > capacity) {
    total_ += indicators.size() - capacity;
    indicators = indicators.last(capacity);
  }
  for (const Indicator& indicator : indicators) {
    slots_[total_ % capacity] = indicator;
    ++total_;
  }
}

std::vector<Indicator> IndicatorRing::live(std::uint64_t now, double dt, double lifetime) const {
  const std::uint64_t capacity = slots_.size();
  const std::uint64_t stored = std::min(total_, capacity);
  std::vector<Indicator> result;
  for (std::uint64_t k = total_ - stored; k < total_; ++k) {
    const Indicator& indicator = slots_[k % capacity];
    double age = static_cast<double>(now - std::min<std::uint64_t>(now, indicator.step)) * dt;
    if (age < lifetime) result.push_back(indicator);
  }
  return result;
}

}  // namespace sp
