// Simulator::set_config's first half, the same for both backends: a new
// config checked against the running World and resolved into what the
// World will hold, before anything changes. Each backend then makes its
// resized storage aside and commits it with the change, so that a refused
// config leaves the simulator exactly as it was.
#pragma once

#include <cstdint>
#include <vector>

#include "soundpaint/simulation.h"

namespace sp {

struct ConfigChange {
  // What World::config becomes: the requested config, but for `sources`
  // and `listener_position`, which keep the values the World was made with
  // (set_config leaves the sources and the listener to the SoundScene).
  Config config;
  std::vector<LayerProperties> layer_properties;  // per layer id, resolved from `config`
};

// Checks `requested` with make_world's one validator (detail::check_config)
// and the running simulation's own rule: dt is fixed once a step has run
// (step n runs at n * dt: another dt would move every play window and
// pattern in time). Throws sp::Exception(InvalidConfig) naming the key.
ConfigChange prepare_config_change(const World& world, const Config& requested, std::uint64_t steps_run);

}  // namespace sp
