// The public sp::Indicator and the shaders' shader::Indicator are one
// layout (the GPU ring's); the backends hand out copies of the second as
// the first.
#pragma once

#include <bit>
#include <cstddef>
#include <span>
#include <vector>

#include "soundpaint/simulation.h"
#include "sp_types.h"

namespace sp {

static_assert(sizeof(Indicator) == sizeof(shader::Indicator));
static_assert(offsetof(Indicator, normal) == offsetof(shader::Indicator, normal));
static_assert(offsetof(Indicator, color) == offsetof(shader::Indicator, color));
static_assert(offsetof(Indicator, dir) == offsetof(shader::Indicator, dir));
static_assert(offsetof(Indicator, path_length) == offsetof(shader::Indicator, path_length));
static_assert(offsetof(Indicator, kind) == offsetof(shader::Indicator, kind));
static_assert(offsetof(Indicator, iteration) == offsetof(shader::Indicator, iteration));
static_assert(offsetof(Indicator, arrival) == offsetof(shader::Indicator, arrival));
static_assert(offsetof(Indicator, heard_energy) == offsetof(shader::Indicator, heard));
static_assert(offsetof(Indicator, toward) == offsetof(shader::Indicator, toward));
static_assert(kIndicatorHit == SP_INDICATOR_HIT && kIndicatorExit == SP_INDICATOR_EXIT);

inline Indicator to_public(const shader::Indicator& indicator) { return std::bit_cast<Indicator>(indicator); }
inline shader::Indicator to_shader(const Indicator& indicator) { return std::bit_cast<shader::Indicator>(indicator); }

inline std::vector<Indicator> to_public(std::span<const shader::Indicator> indicators) {
  std::vector<Indicator> out;
  out.reserve(indicators.size());
  for (const shader::Indicator& indicator : indicators) out.push_back(to_public(indicator));
  return out;
}

inline std::vector<shader::Indicator> to_shader(std::span<const Indicator> indicators) {
  std::vector<shader::Indicator> out;
  out.reserve(indicators.size());
  for (const Indicator& indicator : indicators) out.push_back(to_shader(indicator));
  return out;
}

}  // namespace sp
