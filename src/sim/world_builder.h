// make_world in two parts, for callers that build a level's geometry once
// and make several worlds around it: the penetration probe of `check`,
// `info` and `simulate` runs its own config on the geometry the command
// already built, where it used to weld and build the whole level again.
#pragma once

#include "bvh/bvh.h"
#include "bvh/mesh_topology.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

// The geometry make_world builds for `scene` (the BVH, with exposed edges
// when config.diffraction is on, and what moving parts need), and the
// mesh's topology in *topology_out when it is not null. Throws as
// make_world does.
WorldGeometryHandle build_world_geometry(const Scene& scene, const Config& config, const BvhBuildSettings& bvh_settings,
                                         MeshTopology* topology_out);

// A World for `scene` and `config` around `geometry`, which must have been
// built from the same scene (its triangle layers checked, so this takes
// its layers, sources and camera and never reads its vertices) with the
// same diffraction setting. Throws as make_world does.
World make_world_around(const Scene& scene, const Config& config, WorldGeometryHandle geometry);

}  // namespace sp::detail
