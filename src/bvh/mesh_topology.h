// How a triangle soup's triangles join up: which ones form one piece of
// surface (a solid, for the matter rules of docs/model.md), and what keeps
// it from bounding closed solids (open edges, winding that disagrees), which
// `soundpaint check` reports.
//
// Vertices within 0.1 mm weld: level editors and exporters write shared
// corners with identical or nearly identical coordinates. Solids that touch
// share corners too; they stay apart because an edge of more than two
// triangles joins none.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace sp {

struct MeshTopology {
  // Per triangle: its piece of surface, numbered from 0 in order of first
  // triangle. Triangles are joined through edges that exactly two triangles
  // share; an edge of three or more (solids touching along it) joins none,
  // so touching solids stay apart. A degenerate triangle is a piece alone.
  std::vector<std::uint32_t> triangle_solids;
  std::uint32_t solid_count = 0;
  // Edges of one triangle where the surface is really open: an edge that a
  // collinear run of edges of other triangles covers the other way round (a
  // T-junction, as triangulated brushes have) is closed.
  std::uint64_t open_edges = 0;
  std::uint64_t inconsistent_edges = 0;    // edges two triangles traverse in the same direction
  std::uint64_t non_manifold_edges = 0;    // edges of three or more triangles
  std::uint64_t degenerate_triangles = 0;  // zero area: never hit
  // Per layer id (as in the `layers` argument): open edges of its triangles.
  std::vector<std::uint64_t> open_edges_by_layer;
  std::vector<std::uint64_t> inconsistent_edges_by_layer;
};

// Welded vertex id of each of `vertices` (corners within 0.1 mm share one);
// `positions` receives each id's position.
std::vector<std::uint32_t> weld(std::span<const glm::vec3> vertices, std::vector<glm::vec3>& positions);

// `vertices`: 3 per triangle; `layers`: one per triangle (ids < layer_count).
MeshTopology analyse_mesh(std::span<const glm::vec3> vertices, std::span<const std::uint32_t> layers,
                          std::size_t layer_count);

}  // namespace sp
