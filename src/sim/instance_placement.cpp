#include "sim/instance_placement.h"

#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "core/glm_interop.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {

bool within_bound(glm::vec3 v) {
  for (int k = 0; k < 3; ++k)
    if (!(std::fabs(v[k]) <= kMaxCoordinate)) return false;  // NaN fails too
  return true;
}

std::string describe(glm::vec3 v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return text;
}

std::string bound_text() {
  char text[32];
  std::snprintf(text, sizeof text, "%g m", double(kMaxCoordinate));
  return text;
}

}  // namespace

glm::vec3 place_vertex(const Mat4& transform, glm::vec3 rest) {
  return glm::vec3(to_glm(transform) * glm::vec4(rest, 1.0f));
}

std::vector<std::vector<std::uint32_t>> triangles_by_instance(const detail::WorldGeometry& geometry,
                                                              std::size_t instance_count) {
  std::vector<std::vector<std::uint32_t>> triangles(instance_count);
  for (std::size_t tri = 0; tri < geometry.triangle_instances.size(); ++tri) {
    const std::uint32_t instance = geometry.triangle_instances[tri];
    if (instance < instance_count) triangles[instance].push_back(static_cast<std::uint32_t>(tri));
  }
  return triangles;
}

std::optional<std::string> placement_problem(const detail::WorldGeometry& geometry,
                                             std::span<const std::uint32_t> triangles, const Mat4& transform) {
  for (std::uint32_t tri : triangles) {
    for (std::size_t k = 3 * std::size_t{tri}; k < 3 * std::size_t{tri} + 3; ++k) {
      const glm::vec3 placed = place_vertex(transform, geometry.rest_vertices[k]);
      if (within_bound(placed)) continue;
      const bool finite = std::isfinite(placed.x) && std::isfinite(placed.y) && std::isfinite(placed.z);
      return "it would place vertex " + std::to_string(k) + " (of triangle " + std::to_string(tri) + ") at " +
             describe(placed) +
             (finite ? ", beyond the coordinate bound of " + bound_text() : std::string(", which is not finite"));
    }
  }
  return std::nullopt;
}

}  // namespace sp
