// The edges sound bends round (docs/model.md#diffraction): found once per
// scene (and again after each refit while diffraction is on), stored per
// triangle in leaf order for both backends.
#pragma once

#include <vector>

#include "soundpaint/bvh.h"

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

}  // namespace sp
