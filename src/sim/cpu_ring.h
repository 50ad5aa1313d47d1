// The CPU backend's indicator ring and its one writer. The CPU simulator
// keeps the ring on the host (CpuRing); the CPU visualizer keeps it
// on its device and uploads what the writer lays (RingWriter). Both admit
// and place a step's indicators through RingWriter alone, as the GPU
// backend does in admit.comp; which slots are live, sp_indicator_live
// decides (is_live on the host, the draw's shaders on the device).
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "sim/cpu_step_runner.h"
#include "sim/indicator_ring.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"

namespace sp {

// Admits each step's indicators under the ring's budget (AdmissionPlan,
// sp_admission.h; sp_admission_budget: the quota, or all the free room) and
// lays them in the slots after the last step's, the oldest overwritten.
// Where the slots live is the caller's: `store(slot, run)` copies `run` (a
// std::span<const shader::Indicator>) into slots [slot, slot + run.size()),
// which never wrap. The writer keeps the ring's births as runs, oldest
// first, so it knows how many slots are live without reading them back.
class RingWriter {
 public:
  // A ring of config.max_indicators slots, with its quota and bins.
  explicit RingWriter(const Config& config);

  // Admits `step`'s indicators (those of step `now`) and lays them.
  // Admission comes first: when it fails (out of memory), the ring is as
  // it was.
  template <class Store>
  void write(const CpuStepOutput& step, std::uint32_t now, Store&& store) {
    const std::uint32_t budget = shader::sp_admission_budget(quota_, capacity_, live_slots(now));
    const std::vector<shader::Indicator> admitted = step.admitted(budget, inverse_indicator_size_);
    place(admitted, store);
  }

  // Lays `indicators`, already admitted, in order; when more than the
  // capacity arrive, only the newest.
  template <class Store>
  void place(std::span<const shader::Indicator> indicators, Store&& store) {
    if (indicators.size() > capacity_) {
      written_ += indicators.size() - capacity_;
      indicators = indicators.last(capacity_);
    }
    for (std::size_t done = 0; done < indicators.size();) {
      const auto slot = static_cast<std::uint32_t>((written_ + done) % capacity_);
      const std::size_t run = std::min<std::size_t>(indicators.size() - done, capacity_ - slot);
      store(slot, indicators.subspan(done, run));
      done += run;
    }
    written_ += indicators.size();
    record_births(indicators);
  }

  // Slots whose indicator is live at step `now` (sp_indicator_live), the
  // GPU's admission finds the same by searching its ring's births.
  std::uint32_t live_slots(std::uint32_t now) const;

  std::uint32_t capacity() const { return capacity_; }
  // Indicators ever laid; the next goes to slot written() % capacity().
  std::uint64_t written() const { return written_; }
  // Slots holding an indicator: the oldest is in slot written() - filled().
  std::uint32_t filled() const { return static_cast<std::uint32_t>(std::min<std::uint64_t>(written_, capacity_)); }
  // 1 / indicator_size, with which admission bins: a step runner that bins
  // its indicators as it traces (CpuStepRunner::run) must use this one.
  float inverse_indicator_size() const { return inverse_indicator_size_; }

 private:
  struct Births {
    std::uint32_t step;
    std::uint32_t count;
  };
  void record_births(std::span<const shader::Indicator> laid);

  std::uint32_t capacity_;
  std::uint32_t quota_;
  float inverse_indicator_size_;
  float dt_;
  float lifetime_;
  std::uint64_t written_ = 0;
  std::deque<Births> births_;  // what the filled slots hold, oldest first
};

// The ring on the host, for the CPU simulator.
class CpuRing {
 public:
  explicit CpuRing(const Config& config) : writer_(config), slots_(writer_.capacity()) {}

  // Admits and lays a step's indicators, those of step `now`
  // (RingWriter::write).
  void write(const CpuStepOutput& step, std::uint32_t now);
  // Lays indicators already admitted (RingWriter::place).
  void place(std::span<const shader::Indicator> indicators);

  // The indicators live after `steps_run` steps of `config` (is_live: what
  // the draw shows), oldest first.
  std::vector<shader::Indicator> live(std::uint64_t steps_run, const Config& config) const;

  // A ring for `config` (Simulator::set_config) holding this one's spots
  // in the same order, as many of the newest as its capacity takes: a
  // player keeps seeing what was on screen, and a smaller ring drops the
  // spots that would have faded first. The GPU backend keeps the same ones.
  CpuRing resized(const Config& config) const;

  const RingWriter& writer() const { return writer_; }

 private:
  void store(std::uint32_t slot, std::span<const shader::Indicator> run);
  // Every filled slot, oldest first.
  std::vector<shader::Indicator> filled() const;

  RingWriter writer_;
  std::vector<shader::Indicator> slots_;
};

}  // namespace sp
