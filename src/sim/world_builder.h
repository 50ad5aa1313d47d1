// make_world in two parts, for callers that build a level's geometry once
// and make several worlds around it: the penetration probe of `check`,
// `info` and `simulate` runs its own config on the geometry the command
// already built, where it used to weld and build the whole level again.
#pragma once

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

}  // namespace sp::detail
