// Moving parts into the BVH: the rest pose placed by each instance's
// transform, then a refit, or a rebuild once refits have made the tree
// much costlier than its build.
#pragma once

#include <vector>

#include "bvh/bvh.h"
#include "soundpaint/math.h"

namespace sp {

namespace detail {
struct WorldGeometry;
}

// The SAH cost scaled by the root's area: the absolute expected work per
// ray, which grows when geometry leaves the level (bvh_sah_cost, relative
// to the root box, can fall then while every node grew).
double absolute_sah_cost(const Bvh& bvh);

// Places every moving triangle by its instance's transform (one per
// instance) and refits or rebuilds geometry.bvh; returns what changed.
// Throws sp::Exception (InvalidArgument) when a placed vertex is not
// finite, leaving the BVH as it was: callers check transforms first
// (placement_problem, instance_placement.h).
BvhChanges move_geometry(detail::WorldGeometry& geometry, const std::vector<Mat4>& transforms);

}  // namespace sp
