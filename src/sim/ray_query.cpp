#include "soundpaint/ray_query.h"

#include <cmath>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "core/finite.h"
#include "core/glm_interop.h"
#include "sim/world_geometry.h"
#include "sp_types.h"

namespace sp {

Result<std::optional<RayHit>> cast_ray(const World& world, const Vec3& origin, const Vec3& direction,
                                       float max_distance) {
  const glm::vec3 from = to_glm(origin);
  const glm::vec3 way = to_glm(direction);
  if (!all_finite(origin) || !all_finite(direction))
    return Error{ErrorCode::InvalidArgument, "cast_ray: origin and direction must be finite", 0};
  const float length = glm::length(way);
  if (!(length > 0.0f) || !std::isfinite(length))
    return Error{ErrorCode::InvalidArgument, "cast_ray: the direction must not be zero", 0};
  if (!(max_distance > 0.0f)) return Error{ErrorCode::InvalidArgument, "cast_ray: max_distance must be > 0", 0};
  if (world.geometry->bvh.nodes.empty()) return std::optional<RayHit>{};
  const glm::vec3 unit = way / length;
  const Bvh& bvh = world.geometry->bvh;
  const HitInfo hit = closest_hit(bvh, from, unit, 0.0f, max_distance);
  if (hit.triangle == SP_INVALID) return std::optional<RayHit>{};
  const shader::BvhTriangle& triangle = bvh.triangles[hit.triangle];
  const float normal_length = glm::length(triangle.normal);
  glm::vec3 normal = normal_length > 0.0f ? triangle.normal / normal_length : -unit;
  if (glm::dot(normal, unit) > 0.0f) normal = -normal;
  RayHit result;
  result.distance = hit.t;
  result.position = from + unit * hit.t;
  result.normal = normal;
  result.triangle = triangle.scene_index;
  result.layer = triangle.layer;
  return std::optional<RayHit>{result};
}

}  // namespace sp
