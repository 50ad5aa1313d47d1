// Where a moving part's transform puts its triangles, computed one way for
// the check a host's call gets and for the refit the step makes, so that a
// transform the check accepts can never give the BVH a vertex it refuses.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "soundpaint/math.h"

namespace sp {

namespace detail {
struct WorldGeometry;
}

// A rest-pose vertex placed by `transform` (its w row is ignored: moving
// parts are affine).
glm::vec3 place_vertex(const Mat4& transform, glm::vec3 rest);

// Per instance, the triangles it moves (scene order); empty for a scene
// without moving parts.
std::vector<std::vector<std::uint32_t>> triangles_by_instance(const detail::WorldGeometry& geometry,
                                                              std::size_t instance_count);

// Why `transform` cannot place the given triangles (their first vertex that
// would be non-finite or beyond kMaxCoordinate), or nothing when it can.
std::optional<std::string> placement_problem(const detail::WorldGeometry& geometry,
                                             std::span<const std::uint32_t> triangles, const Mat4& transform);

}  // namespace sp
