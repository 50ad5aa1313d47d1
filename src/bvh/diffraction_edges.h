// The edges sound bends round (docs/model.md#diffraction): found once per
// scene (and again after each refit while diffraction is on), stored per
// triangle in leaf order for both backends.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"

namespace sp {

// A face of another triangle this close to an exposed edge's midpoint
// buries the edge: a wall standing on a floor, brushes that touch, a pane
// in its frame. Far below any opening sound goes round, far above the
// gaps a level editor leaves between touching brushes.
inline constexpr float kBuriedEdgeDistance = 0.01f;

// Per triangle of `bvh` (leaf order): its exposed edges, each a free
// boundary (no other triangle shares it) or a convex edge of exactly two
// triangles, with the angle the surface turns there, unless buried.
// Concave and flat edges, and edges of three or more triangles (solids
// touching), are never exposed. Corners within 0.1 mm weld, as in
// analyse_mesh.
std::vector<shader::TriangleEdges> find_exposed_edges(const Bvh& bvh);

// Finds again, in `table` (find_exposed_edges' answer for this tree before
// some triangles moved), the edges whose midpoints lie in the box [lo, hi],
// leaving the rest: after a refit, the box around the moved triangles' old
// and new places, grown by kBuriedEdgeDistance, holds every edge that can
// have changed. Same answer as find_exposed_edges, in time that grows with
// the triangles near the box rather than with the scene.
void refresh_exposed_edges(const Bvh& bvh, glm::vec3 lo, glm::vec3 hi, std::vector<shader::TriangleEdges>& table);

}  // namespace sp
