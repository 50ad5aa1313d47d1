// A playing source's E0 for one step (docs/model.md#loudness-from-the-signal):
// its loudness, or, when the host gave a level or the source carries a
// signal, its loudness scaled by the level the config's `signal` law maps.
// Computed on the host once per step, so both backends read the same float.
#pragma once

#include "soundpaint/config.h"
#include "soundpaint/simulation.h"

namespace sp {

struct StepLoudness {
  float energy = 0.0f;  // E0 of the step's rays
  // The level's gain in [0, 1] (1 without a signal or level): what the
  // source's share of the ray budget is weighted by.
  double share = 1.0;
  bool emits = true;  // false below the floor: no rays, no spots
};

// `in_window`: t lies in `window` (the host's play window), which then
// places the signal; otherwise the source's pattern does.
StepLoudness step_loudness(const SourceDesc& source, const PlayWindow& window, bool in_window, double t,
                           const Config& config);

}  // namespace sp
