#include "sim/config_change.h"

#include <string>

#include "config/json_fields.h"
#include "sim/world_builder.h"

namespace sp {

ConfigChange prepare_config_change(const World& world, const Config& requested, std::uint64_t steps_run) {
  detail::check_config(requested);
  if (steps_run > 0 && requested.dt != world.config.dt)
    json_fields::JsonPath("config").key("dt").fail(
        "cannot change once the simulation has stepped (step n runs at n * dt: another dt would move every play "
        "window and source pattern in time); create a new simulator for it, now " +
        std::to_string(world.config.dt));
  ConfigChange change{requested, detail::resolve_layers(requested, world.layer_names)};
  change.config.sources = world.config.sources;
  change.config.listener_position = world.config.listener_position;
  return change;
}

}  // namespace sp
