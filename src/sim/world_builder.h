// make_world in two parts, for callers that build a level's geometry once
// and make several worlds around it: the penetration probe of `check`,
// `info` and `simulate` runs its own config on the geometry the command
// already built, where it used to weld and build the whole level again.
// Also the config's checks and layer resolution, which Simulator::set_config
// shares with make_world.
#pragma once

#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/mesh_topology.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

// The geometry make_world builds for `scene` (the BVH and what moving parts
// need; exposed edges come when a world with diffraction asks), and the
// mesh's topology in *topology_out when it is not null. Throws as
// make_world does.
WorldGeometryHandle build_world_geometry(const Scene& scene, const BvhBuildSettings& bvh_settings,
                                         MeshTopology* topology_out);

// A World for `scene` and `config` around `geometry`, which must have been
// built from the same scene (its triangle count checked unless
// `check_geometry` is false, for make_world's cheap checks before the
// build; this takes the scene's layers, sources and camera and never reads
// its vertices). Throws as make_world does.
World make_world_around(const Scene& scene, const Config& config, WorldGeometryHandle geometry,
                        bool check_geometry = true);

// The one validator of a whole Config, make_world's and
// Simulator::set_config's: every number's range (config_rules.h), the
// display, the signal law and the CPU traversal this build offers. Throws
// sp::Exception(InvalidConfig) naming the key.
void check_config(const Config& config);

// Per layer id, the acoustics `config` gives each of `layer_names`
// (resolve_layer): what a World holds in layer_properties.
std::vector<LayerProperties> resolve_layers(const Config& config, const std::vector<std::string>& layer_names);

}  // namespace sp::detail
