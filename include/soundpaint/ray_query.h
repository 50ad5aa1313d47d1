// Where a ray meets the level: the simulation's own closest-hit traversal
// over a World's geometry, for picking in an editor or viewer and for
// checks such as "is there a floor under this source".
#pragma once

#include <cstdint>
#include <optional>

#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/simulation.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

struct RayHit {
  float distance = 0.0f;       // metres from the origin along the unit direction
  Vec3 position;               // origin + distance * direction
  Vec3 normal;                 // unit; the surface's, turned to face the ray's origin
  std::uint32_t triangle = 0;  // the triangle's index in the Scene
  std::uint32_t layer = 0;     // index into World::layer_names
};

// The nearest surface along the ray from `origin` in `direction` (any
// length but 0; normalised here) within `max_distance` metres, or nothing.
// The same traversal and intersection test as the sound rays, over the
// world's geometry as it stands (moving parts included, once a SoundScene
// has refitted it). Thread-safe with other readers of the world; not
// while its SoundScene refits the geometry. Errors: InvalidArgument (a
// non-finite origin or direction, a zero direction, max_distance not > 0).
Result<std::optional<RayHit>> cast_ray(const World& world, const Vec3& origin, const Vec3& direction,
                                       float max_distance = 1.0e30f);

}  // namespace sp

SP_CPP_API_END
