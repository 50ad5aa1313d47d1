// What a simulation will allocate for its rays and indicators, estimated
// from its configuration before anything is allocated (README "Security").
//
// A config is player-supplied text: "max_bounces": 64 with ray_budget and
// max_indicators at their maxima is valid, and needs hundreds of gigabytes
// at worst. Checked against the host's budget at creation, it fails at once
// with a message naming the knobs, instead of after a minute of swapping.
#pragma once

#include <cstdint>
#include <string>

#include "soundpaint/simulation.h"

namespace sp {

struct MemoryEstimate {
  std::uint64_t ring_bytes = 0;  // the indicator ring, and one copy of it handed out (live_indicators)
  std::uint64_t step_bytes = 0;  // the worst step: every indicator it can create, in every copy held; GPU ray states
  std::uint64_t total() const { return ring_bytes + step_bytes; }
};

// The worst case, not the usual one: a step creates at most
// ray_budget * (2 * max_bounces + 2) indicators (a hit, and an exit after
// each penetration, per interaction), which the CPU backend holds four times
// over (per-chunk lists, the merged list, and the copy a caller takes of
// it) and the GPU backend twice (the device's capture buffer and its read
// back). The scene's own memory is bounded separately (max_triangles).
MemoryEstimate estimate_memory(const Config& config, Backend backend);

// Throws sp::Exception(LimitExceeded), naming the config keys that drive the
// estimate and the budget's knobs, when estimate_memory() exceeds
// `budget_bytes`.
void check_memory_budget(const Config& config, Backend backend, std::uint64_t budget_bytes);

// "1.5 GiB", "640 KiB": sizes in messages.
std::string describe_bytes(std::uint64_t bytes);

}  // namespace sp
