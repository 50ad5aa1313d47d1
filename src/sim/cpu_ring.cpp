#include "sim/cpu_ring.h"

#include <algorithm>

namespace sp {

RingWriter::RingWriter(const Config& config)
    : capacity_(config.max_indicators),
      quota_(ring_quota(config)),
      inverse_indicator_size_(sp::inverse_indicator_size(config)) {}

void IndicatorRing::write(const CpuStepOutput& step) {
  writer_.write(step, [this](std::uint32_t slot, std::span<const shader::Indicator> run) { store(slot, run); });
}

void IndicatorRing::place(std::span<const shader::Indicator> indicators) {
  writer_.place(indicators, [this](std::uint32_t slot, std::span<const shader::Indicator> run) { store(slot, run); });
}

void IndicatorRing::store(std::uint32_t slot, std::span<const shader::Indicator> run) {
  std::copy(run.begin(), run.end(), slots_.begin() + slot);
}

std::vector<shader::Indicator> IndicatorRing::live(std::uint64_t steps_run, const Config& config) const {
  const std::uint64_t capacity = slots_.size();
  const std::uint64_t written = writer_.written();
  std::vector<shader::Indicator> result;
  for (std::uint64_t k = written - writer_.filled(); k < written; ++k) {
    const shader::Indicator& indicator = slots_[k % capacity];
    if (is_live(indicator.step, steps_run, config)) result.push_back(indicator);
  }
  return result;
}

}  // namespace sp
