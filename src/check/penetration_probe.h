// The penetration probe on geometry already built: check, info and
// simulate build a level once and probe it with their own config.
#pragma once

#include "soundpaint/check.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

// probe_penetration on `geometry`, which was built from `scene`
// (detail::build_world_geometry, or a World's own), shared, not copied.
// Throws as probe_penetration's errors say.
PenetrationProbe probe_penetration_on(const Scene& scene, const Config& config, const CheckSettings& settings,
                                      const WorldGeometryHandle& geometry);

}  // namespace sp::detail
