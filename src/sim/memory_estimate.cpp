#include "sim/memory_estimate.h"
#include "sp_types.h"

#include <cstdio>
#include <iterator>

namespace sp {
namespace {

constexpr std::uint64_t kCpuStepCopies = 4;
constexpr std::uint64_t kGpuStepCopies = 2;
// Per GPU ray: its state, its cast's result (counted as large as a state)
// and two queue slots.
constexpr std::uint64_t kGpuRayBytes = 2 * sizeof(shader::RayState) + 2 * sizeof(std::uint32_t);

// a * b, saturating instead of wrapping: hostile values only make it larger.
std::uint64_t times(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > UINT64_MAX / a) return UINT64_MAX;
  return a * b;
}

std::uint64_t plus(std::uint64_t a, std::uint64_t b) { return b > UINT64_MAX - a ? UINT64_MAX : a + b; }

}  // namespace

MemoryEstimate estimate_memory(const Config& config, Backend backend) {
  const std::uint64_t indicator = sizeof(Indicator);
  const std::uint64_t per_ray = 2 * std::uint64_t{config.max_bounces} + 2;
  const std::uint64_t step_indicators = times(config.ray_budget, per_ray);
  MemoryEstimate estimate;
  estimate.ring_bytes = times(2 * std::uint64_t{config.max_indicators}, indicator);
  if (backend == Backend::Cpu) {
    estimate.step_bytes = times(times(step_indicators, indicator), kCpuStepCopies);
  } else {
    estimate.step_bytes =
        plus(times(times(step_indicators, indicator), kGpuStepCopies), times(config.ray_budget, kGpuRayBytes));
  }
  return estimate;
}

std::string describe_bytes(std::uint64_t bytes) {
  static constexpr const char* kUnits[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  std::size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < std::size(kUnits)) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, kUnits[unit]);
  return text;
}

void check_memory_budget(const Config& config, Backend backend, std::uint64_t budget_bytes) {
  const MemoryEstimate estimate = estimate_memory(config, backend);
  if (estimate.total() <= budget_bytes) return;
  throw Exception(ErrorCode::LimitExceeded,
                  std::string("the config needs up to ") + describe_bytes(estimate.total()) + " on the " +
                      (backend == Backend::Cpu ? "CPU" : "GPU") + " backend (" + describe_bytes(estimate.step_bytes) +
                      " for a step of ray_budget " + std::to_string(config.ray_budget) + " with max_bounces " +
                      std::to_string(config.max_bounces) + ", " + describe_bytes(estimate.ring_bytes) +
                      " for max_indicators " + std::to_string(config.max_indicators) + "), over the memory budget of " +
                      describe_bytes(budget_bytes) +
                      ": lower those keys, or raise the budget (--memory-budget, memory_budget_bytes)");
}

}  // namespace sp
