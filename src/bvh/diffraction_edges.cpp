#include "bvh/diffraction_edges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "bvh/mesh_topology.h"
#include "sp_types.h"

namespace sp {
namespace {

// One triangle's use of an edge, sorted by the edge's welded corners.
struct EdgeUse {
  std::uint64_t key;  // (lower welded id << 32) | higher
  std::uint32_t triangle;
  std::uint32_t edge;  // 0..2: from corner edge to corner (edge + 1) % 3
  bool operator<(const EdgeUse& other) const {
    return key != other.key             ? key < other.key
           : triangle != other.triangle ? triangle < other.triangle
                                        : edge < other.edge;
  }
};

glm::vec3 corner(const BvhTriangle& tri, std::uint32_t i) { return i == 0 ? tri.v0 : (i == 1 ? tri.v1 : tri.v2); }

bool degenerate(const BvhTriangle& tri) { return !(glm::dot(tri.normal, tri.normal) > 0.5f); }

// Squared distance from p to triangle (a, b, c): the closest point by the
// triangle's Voronoi regions (Ericson, Real-Time Collision Detection, 5.1.5).
float distance2_to_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  auto d2_to = [&](glm::vec3 q) { return glm::dot(p - q, p - q); };
  if (d1 <= 0.0f && d2 <= 0.0f) return d2_to(a);
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return d2_to(b);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return d2_to(a + ab * (d1 / (d1 - d3)));
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return d2_to(c);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return d2_to(a + ac * (d2 / (d2 - d6)));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
    return d2_to(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const float denom = 1.0f / (va + vb + vc);
  return d2_to(a + ab * (vb * denom) + ac * (vc * denom));
}

// What the burial queries of one search may still spend, in leaf packets
// (SP_LEAF_PACKETS, as a cast counts them): a query near many overlapping
// boxes (coincident copies, slivers) would otherwise test every triangle,
// and a level of such edges would take minutes. An edge whose query runs
// out counts as buried: no diffraction there, and it is counted.
struct BurialBudget {
  std::uint64_t packets_left;
  std::uint64_t undecided = 0;  // edges left unexposed because the budget ran out
};

// Whether a triangle other than the edge's own `a` and `b`, and of a solid
// other than theirs, comes within `radius` of `p`
// (docs/model.md#diffraction). Triangles of the edge's own solid never bury
// it: the far face of a 1 cm pane, or the end cap of a thin door, lies
// within the radius of the edge it bounds. True as well when the query
// would spend more than kBurialQueryPackets or what the budget has left.
bool buried(const Bvh& bvh, glm::vec3 p, float radius, std::uint32_t a, std::uint32_t b, BurialBudget& budget) {
  const std::uint32_t solid = bvh.triangles[a].solid;
  const float r2 = radius * radius;
  std::uint64_t spend = std::min<std::uint64_t>(kBurialQueryPackets, budget.packets_left);
  auto give_up = [&] {
    budget.packets_left -= std::min<std::uint64_t>(budget.packets_left, kBurialQueryPackets);
    budget.undecided += 1;
    return true;
  };
  std::uint32_t stack[SP_BVH_MAX_DEPTH * 2];
  std::uint32_t size = 0;
  stack[size++] = 0;
  std::uint64_t spent = 0;
  while (size > 0) {
    const BvhNode& node = bvh.nodes[stack[--size]];
    const glm::vec3 nearest = glm::clamp(p, node.bmin, node.bmax);
    if (glm::dot(nearest - p, nearest - p) > r2) continue;
    if (node.count == 0) {
      stack[size++] = node.left_or_first;
      stack[size++] = node.left_or_first + 1;
      continue;
    }
    spent += SP_LEAF_PACKETS(node.count);
    if (spent > spend) return give_up();
    for (std::uint32_t t = node.left_or_first; t < node.left_or_first + node.count; ++t) {
      const BvhTriangle& tri = bvh.triangles[t];
      if (t == a || t == b || tri.solid == solid) continue;
      if (distance2_to_triangle(p, tri.v0, tri.v1, tri.v2) <= r2) {
        budget.packets_left -= spent;
        return true;
      }
    }
  }
  budget.packets_left -= spent;
  return false;
}

}  // namespace

std::uint64_t refresh_exposed_edges(const Bvh& bvh, glm::vec3 lo, glm::vec3 hi,
                                    std::vector<shader::TriangleEdges>& table) {
  const std::size_t n = bvh.triangles.size();
  if (n == 0 || bvh.nodes.empty()) return 0;
  auto inside = [&](glm::vec3 p) { return glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi)); };
  auto midpoint = [&](std::uint32_t t, std::uint32_t edge) {
    const BvhTriangle& tri = bvh.triangles[t];
    return 0.5f * (corner(tri, edge) + corner(tri, (edge + 1) % 3));
  };

  // Every triangle using an edge whose midpoint lies in the box contains
  // that midpoint, so these are all the triangles the box's edges need.
  std::vector<std::uint32_t> nearby;
  for (std::uint32_t t = 0; t < n; ++t) {
    const BvhTriangle& tri = bvh.triangles[t];
    const glm::vec3 tmin = glm::min(glm::min(tri.v0, tri.v1), tri.v2);
    const glm::vec3 tmax = glm::max(glm::max(tri.v0, tri.v1), tri.v2);
    if (glm::all(glm::lessThanEqual(lo, tmax)) && glm::all(glm::lessThanEqual(tmin, hi))) nearby.push_back(t);
  }
  std::vector<glm::vec3> corners(3 * nearby.size());
  for (std::size_t k = 0; k < nearby.size(); ++k)
    for (std::uint32_t i = 0; i < 3; ++i) corners[3 * k + i] = corner(bvh.triangles[nearby[k]], i);
  std::vector<glm::vec3> positions;
  const std::vector<std::uint32_t> ids = weld(corners, positions);

  // The box's edges start unexposed; the groups below expose them again.
  std::vector<EdgeUse> uses;
  uses.reserve(corners.size());
  for (std::size_t k = 0; k < nearby.size(); ++k) {
    const std::uint32_t t = nearby[k];
    for (std::uint32_t i = 0; i < 3; ++i) {
      if (!inside(midpoint(t, i))) continue;
      table[t].exposed &= ~(1u << i);
      table[t].turn_cos[static_cast<int>(i)] = 1.0f;
      table[t].turn_sin[static_cast<int>(i)] = 0.0f;
      const std::uint64_t u = ids[3 * k + i], v = ids[3 * k + (i + 1) % 3];
      if (degenerate(bvh.triangles[t]) || u == v) continue;
      uses.push_back({(std::min(u, v) << 32) | std::max(u, v), t, i});
    }
  }
  std::sort(uses.begin(), uses.end());
  BurialBudget budget{kBurialPacketsPerSearch};

  auto expose = [&](const EdgeUse& use, float turn_cos, float turn_sin) {
    shader::TriangleEdges& entry = table[use.triangle];
    entry.exposed |= 1u << use.edge;
    entry.turn_cos[static_cast<int>(use.edge)] = turn_cos;
    entry.turn_sin[static_cast<int>(use.edge)] = turn_sin;
  };
  for (std::size_t first = 0; first < uses.size();) {
    std::size_t last = first + 1;
    while (last < uses.size() && uses[last].key == uses[first].key) ++last;
    const std::size_t count = last - first;
    if (count == 1) {
      const EdgeUse& a = uses[first];
      if (!buried(bvh, midpoint(a.triangle, a.edge), kBuriedEdgeDistance, a.triangle, a.triangle, budget))
        expose(a, -1.0f, 0.0f);
    } else if (count == 2) {
      const EdgeUse& a = uses[first];
      const EdgeUse& b = uses[first + 1];
      const BvhTriangle& ta = bvh.triangles[a.triangle];
      const BvhTriangle& tb = bvh.triangles[b.triangle];
      const glm::vec3 edge_start = corner(ta, a.edge);
      const glm::vec3 edge = corner(ta, (a.edge + 1) % 3) - edge_start;
      // Convex: each face lies behind the other's plane.
      const float behind_a = glm::dot(ta.normal, corner(tb, (b.edge + 2) % 3) - edge_start);
      const float behind_b = glm::dot(tb.normal, corner(ta, (a.edge + 2) % 3) - edge_start);
      const float tolerance = 1.0e-6f * glm::length(edge);
      const float turn_cos = std::clamp(glm::dot(ta.normal, tb.normal), -1.0f, 1.0f);
      if (behind_a < -tolerance && behind_b < -tolerance && turn_cos < 1.0f - 1.0e-6f &&
          !buried(bvh, midpoint(a.triangle, a.edge), kBuriedEdgeDistance, a.triangle, b.triangle, budget)) {
        const float turn_sin = std::sqrt(std::max(0.0f, 1.0f - turn_cos * turn_cos));
        expose(a, turn_cos, turn_sin);
        expose(b, turn_cos, turn_sin);
      }
    }
    first = last;
  }
  return budget.undecided;
}

std::vector<shader::TriangleEdges> find_exposed_edges(const Bvh& bvh, std::uint64_t* undecided) {
  std::vector<shader::TriangleEdges> table(bvh.triangles.size(),
                                           shader::TriangleEdges{glm::vec3(1.0f), 0u, glm::vec3(0.0f), 0u});
  if (undecided) *undecided = 0;
  if (bvh.nodes.empty()) return table;
  const std::uint64_t left_out = refresh_exposed_edges(bvh, bvh.nodes[0].bmin, bvh.nodes[0].bmax, table);
  if (undecided) *undecided = left_out;
  return table;
}

}  // namespace sp
