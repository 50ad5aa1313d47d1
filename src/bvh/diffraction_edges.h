// The edges sound bends round (docs/model.md#diffraction): found once per
// scene (and again after each refit while diffraction is on), stored per
// triangle in leaf order for both backends.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"

namespace sp {

// A face of another solid this close to an exposed edge's midpoint buries
// the edge: a wall standing on a floor, brushes that touch, a pane in its
// frame. Far below any opening sound goes round, far above the gaps a
// level editor leaves between touching brushes. Faces of the edge's own
// solid never bury it, so a 1 cm pane keeps its edges.
inline constexpr float kBuriedEdgeDistance = 0.01f;

// The work one edge's burial query may do, in leaf packets of four
// triangles: a query in a level's BVH tests a leaf or two; one among
// coincident or overlapping triangles would test them all. A query that
// runs out leaves its edge unexposed (counted as undecided).
inline constexpr std::uint64_t kBurialQueryPackets = 64;
// The work of all burial queries of one search together: about 2^26
// triangle distance tests, a second or so, whatever the level. Edges left
// when it runs out are left unexposed and counted.
inline constexpr std::uint64_t kBurialPacketsPerSearch = std::uint64_t{1} << 24;

// Per triangle of `bvh` (leaf order): its exposed edges, each a free
// boundary (no other triangle shares it) or a convex edge of exactly two
// triangles, with the angle the surface turns there, unless buried.
// Concave and flat edges, and edges of three or more triangles (solids
// touching), are never exposed. Corners within 0.1 mm weld, as in
// analyse_mesh. `undecided`, when given, receives how many edges were left
// unexposed because their burial query ran out of work (kBurialQueryPackets,
// kBurialPacketsPerSearch): 0 on a level whose BVH separates its triangles.
std::vector<shader::TriangleEdges> find_exposed_edges(const Bvh& bvh, std::uint64_t* undecided = nullptr);

// Finds again, in `table` (find_exposed_edges' answer for this tree before
// some triangles moved), the edges whose midpoints lie in the box [lo, hi],
// leaving the rest: after a refit, the box around the moved triangles' old
// and new places, grown by kBuriedEdgeDistance, holds every edge that can
// have changed. Same answer as find_exposed_edges, in time that grows with
// the triangles near the box rather than with the scene. Returns the edges
// left undecided, as find_exposed_edges.
std::uint64_t refresh_exposed_edges(const Bvh& bvh, glm::vec3 lo, glm::vec3 hi,
                                    std::vector<shader::TriangleEdges>& table);

}  // namespace sp
