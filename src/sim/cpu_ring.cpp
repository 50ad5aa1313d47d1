#include "sim/cpu_ring.h"

#include <algorithm>
#include <vector>

namespace sp {

RingWriter::RingWriter(const Config& config)
    : capacity_(config.max_indicators),
      quota_(ring_quota(config)),
      inverse_indicator_size_(sp::inverse_indicator_size(config)),
      dt_(static_cast<float>(config.dt)),
      lifetime_(config.indicator_lifetime) {}

void RingWriter::record_births(std::span<const shader::Indicator> laid) {
  for (const shader::Indicator& ind : laid) {
    if (!births_.empty() && births_.back().step == ind.step) {
      births_.back().count += 1u;
    } else {
      births_.push_back(Births{ind.step, 1u});
    }
  }
  // Drop what was overwritten: the ring holds the newest filled() slots.
  std::uint64_t held = 0;
  for (const Births& b : births_) held += b.count;
  while (held > filled()) {
    Births& oldest = births_.front();
    const std::uint64_t drop = std::min<std::uint64_t>(oldest.count, held - filled());
    oldest.count -= static_cast<std::uint32_t>(drop);
    held -= drop;
    if (oldest.count == 0u) births_.pop_front();
  }
}

std::uint32_t RingWriter::live_slots(std::uint32_t now) const {
  // Births only grow from the oldest slot to the newest, so the live ones
  // are the newest runs.
  std::uint32_t live = 0;
  for (auto it = births_.rbegin(); it != births_.rend(); ++it) {
    if (!shader::sp_indicator_live(now, it->step, dt_, lifetime_)) break;
    live += it->count;
  }
  return live;
}

void CpuRing::write(const CpuStepOutput& step, std::uint32_t now) {
  writer_.write(step, now, [this](std::uint32_t slot, std::span<const shader::Indicator> run) { store(slot, run); });
}

void CpuRing::place(std::span<const shader::Indicator> indicators) {
  writer_.place(indicators, [this](std::uint32_t slot, std::span<const shader::Indicator> run) { store(slot, run); });
}

void CpuRing::store(std::uint32_t slot, std::span<const shader::Indicator> run) {
  std::copy(run.begin(), run.end(), slots_.begin() + slot);
}

std::vector<shader::Indicator> CpuRing::filled() const {
  const std::uint64_t capacity = slots_.size();
  const std::uint64_t written = writer_.written();
  std::vector<shader::Indicator> result;
  result.reserve(writer_.filled());
  for (std::uint64_t k = written - writer_.filled(); k < written; ++k) result.push_back(slots_[k % capacity]);
  return result;
}

std::vector<shader::Indicator> CpuRing::live(std::uint64_t steps_run, const Config& config) const {
  const std::uint64_t capacity = slots_.size();
  const std::uint64_t written = writer_.written();
  std::vector<shader::Indicator> result;
  for (std::uint64_t k = written - writer_.filled(); k < written; ++k) {
    const shader::Indicator& indicator = slots_[k % capacity];
    if (is_live(indicator.step, steps_run, config)) result.push_back(indicator);
  }
  return result;
}

CpuRing CpuRing::resized(const Config& config) const {
  CpuRing ring(config);
  // place() lays only the newest `capacity` of them, as it does for a step.
  ring.place(filled());
  return ring;
}

}  // namespace sp
