#include "sim/geometry_update.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "bvh/diffraction_edges.h"
#include "sim/instance_placement.h"
#include "sim/world_geometry.h"

namespace sp {
namespace {

// Refits that have made the tree this much costlier than its build trigger
// a rebuild: a door swung open keeps its leaves' old neighbours otherwise.
constexpr double kRebuildCostRatio = 2.0;

}  // namespace

double absolute_sah_cost(const Bvh& bvh) {
  if (bvh.nodes.empty()) return 0.0;
  const glm::vec3 e = bvh.nodes[0].bmax - bvh.nodes[0].bmin;
  const double half_area =
      static_cast<double>(e.x) * e.y + static_cast<double>(e.y) * e.z + static_cast<double>(e.z) * e.x;
  return bvh_sah_cost(bvh) * std::max(half_area, 1e-12);
}

BvhChanges move_geometry(detail::WorldGeometry& geometry, const std::vector<Mat4>& transforms) {
  std::vector<glm::vec3> vertices(geometry.rest_vertices.size());
  for (std::size_t tri = 0; tri < geometry.triangle_instances.size(); ++tri) {
    const std::uint32_t instance = geometry.triangle_instances[tri];
    for (std::size_t k = 3 * tri; k < 3 * tri + 3; ++k) {
      vertices[k] = instance == kStaticInstance ? geometry.rest_vertices[k]
                                                : place_vertex(transforms[instance], geometry.rest_vertices[k]);
    }
  }
  BvhChanges changes = refit_bvh(geometry.bvh, vertices).value();
  if (absolute_sah_cost(geometry.bvh) > kRebuildCostRatio * geometry.build_sah_cost) {
    const bool had_edges = !geometry.bvh.edges.empty();
    geometry.bvh = build_bvh(vertices, geometry.triangle_layers, geometry.triangle_solids);
    geometry.build_sah_cost = absolute_sah_cost(geometry.bvh);
    changes.nodes = {{0, static_cast<std::uint32_t>(geometry.bvh.nodes.size())}};
    changes.triangles = {{0, static_cast<std::uint32_t>(geometry.bvh.triangles.size())}};
    if (had_edges) {
      geometry.bvh.edges = find_exposed_edges(geometry.bvh);
      changes.edges = {{0, static_cast<std::uint32_t>(geometry.bvh.edges.size())}};
    }
  }
  return changes;
}

}  // namespace sp
