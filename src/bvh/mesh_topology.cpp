#include "bvh/mesh_topology.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <compare>
#include <unordered_map>
#include <numeric>

#include <glm/geometric.hpp>

#include "bvh/bvh_geometry.h"

namespace sp {
namespace {

// Bits of a coordinate with -0 folded onto +0, so that equal floats weld.
std::uint32_t weld_bits(float x) { return std::bit_cast<std::uint32_t>(x == 0.0f ? 0.0f : x); }

// Corners closer than this weld: converters and editors that compute a
// solid's corners once per face leave them a few float roundings apart
// (~1e-6 m), and no feature of a level is this small.
constexpr double kWeldDistance = 1e-4;

}  // namespace

// Exact duplicates first (a sort), then corners within kWeldDistance of an
// earlier one (a grid of that cell size: a neighbour lies in one of the 27
// cells around).
std::vector<std::uint32_t> weld(std::span<const glm::vec3> vertices, std::vector<glm::vec3>& positions) {
  using Key = std::array<std::uint32_t, 3>;
  std::vector<std::uint32_t> order(vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](std::uint32_t i) {
    return Key{weld_bits(vertices[i].x), weld_bits(vertices[i].y), weld_bits(vertices[i].z)};
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Key ka = key(a), kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  std::vector<std::uint32_t> exact(vertices.size());
  std::vector<glm::vec3> unique;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || key(order[k]) != key(order[k - 1])) unique.push_back(vertices[order[k]]);
    exact[order[k]] = static_cast<std::uint32_t>(unique.size() - 1);
  }

  using Cell = std::array<std::int64_t, 3>;
  auto cell_of = [](const glm::vec3& p) {
    return Cell{static_cast<std::int64_t>(std::floor(double(p.x) / kWeldDistance)),
                static_cast<std::int64_t>(std::floor(double(p.y) / kWeldDistance)),
                static_cast<std::int64_t>(std::floor(double(p.z) / kWeldDistance))};
  };
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      return std::hash<std::int64_t>()(c[0] * 73856093 ^ c[1] * 19349663 ^ c[2] * 83492791);
    }
  };
  std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> grid;  // cell -> welded ids there
  grid.reserve(unique.size());
  std::vector<std::uint32_t> welded(unique.size());
  for (std::size_t u = 0; u < unique.size(); ++u) {
    const Cell c = cell_of(unique[u]);
    std::uint32_t found = 0xFFFFFFFFu;
    for (std::int64_t dx = -1; dx <= 1 && found == 0xFFFFFFFFu; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && found == 0xFFFFFFFFu; ++dy)
        for (std::int64_t dz = -1; dz <= 1 && found == 0xFFFFFFFFu; ++dz) {
          const auto it = grid.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (std::uint32_t id : it->second)
            if (glm::distance(glm::dvec3(positions[id]), glm::dvec3(unique[u])) <= kWeldDistance) {
              found = id;
              break;
            }
        }
    if (found == 0xFFFFFFFFu) {
      found = static_cast<std::uint32_t>(positions.size());
      positions.push_back(unique[u]);
      grid[c].push_back(found);
    }
    welded[u] = found;
  }
  std::vector<std::uint32_t> ids(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) ids[i] = welded[exact[i]];
  return ids;
}

namespace {

struct UnionFind {
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  // The smaller root wins, so that the numbering is independent of order.
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::uint32_t> parent;
};

// A triangle's edge: welded endpoints, lower first, and whether the triangle
// runs it from the higher to the lower.
struct Edge {
  std::uint32_t low;
  std::uint32_t high;
  std::uint32_t triangle;
  bool reversed;
};

// An edge of one triangle, as the triangle runs it: from `from` to `to`.
struct OpenEdge {
  glm::dvec3 from;
  glm::dvec3 to;
  std::uint32_t triangle;
};

// Collinear edges share a supporting line; lines are compared after
// rounding their direction to 1e-5 and their point nearest the origin to
// 0.1 mm, far below any gap that matters and far above float rounding.
struct LineKey {
  std::array<std::int64_t, 6> q;
  auto operator<=>(const LineKey&) const = default;
};

LineKey line_key(const glm::dvec3& direction, const glm::dvec3& foot) {
  auto round = [](double x, double step) { return static_cast<std::int64_t>(std::llround(x / step)); };
  return LineKey{{round(direction.x, 1e-5), round(direction.y, 1e-5), round(direction.z, 1e-5), round(foot.x, 1e-4),
                  round(foot.y, 1e-4), round(foot.z, 1e-4)}};
}

// Marks the edges of `group` (all on one line) that are really open: some
// stretch of the edge is covered by more edges running one way along the
// line than the other. A closed surface runs every stretch once each way.
void mark_open(const std::vector<OpenEdge>& edges, const std::vector<std::size_t>& group, const glm::dvec3& direction,
               std::vector<bool>& open) {
  struct Interval {
    double lo, hi;
    int sign;  // +1 along `direction`, -1 against
    std::size_t edge;
  };
  std::vector<Interval> intervals;
  std::vector<double> cuts;
  for (std::size_t e : group) {
    const double a = glm::dot(edges[e].from, direction), b = glm::dot(edges[e].to, direction);
    intervals.push_back({std::min(a, b), std::max(a, b), a < b ? 1 : -1, e});
    cuts.push_back(a);
    cuts.push_back(b);
  }
  std::sort(cuts.begin(), cuts.end());
  // Elementary stretches between neighbouring cuts; cuts closer than the
  // weld tolerance are one.
  constexpr double kSame = 1e-4;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double lo = cuts[k], hi = cuts[k + 1];
    if (hi - lo < kSame) continue;
    const double mid = 0.5 * (lo + hi);
    int net = 0;
    for (const Interval& i : intervals)
      if (i.lo < mid && mid < i.hi) net += i.sign;
    if (net == 0) continue;
    for (const Interval& i : intervals)
      if (i.lo < mid && mid < i.hi) open[i.edge] = true;
  }
}

// How many of `edges` (each used by one triangle) are really open.
std::vector<bool> really_open(const std::vector<OpenEdge>& edges) {
  std::vector<std::pair<LineKey, std::size_t>> keyed;
  std::vector<glm::dvec3> directions(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    glm::dvec3 d = glm::normalize(edges[e].to - edges[e].from);
    // One direction per line: the first non-zero component positive.
    const double lead = std::abs(d.x) > 1e-9 ? d.x : std::abs(d.y) > 1e-9 ? d.y : d.z;
    if (lead < 0.0) d = -d;
    directions[e] = d;
    const glm::dvec3 foot = edges[e].from - d * glm::dot(edges[e].from, d);
    keyed.emplace_back(line_key(d, foot), e);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<bool> open(edges.size(), false);
  for (std::size_t first = 0; first < keyed.size();) {
    std::size_t last = first + 1;
    while (last < keyed.size() && keyed[last].first == keyed[first].first) ++last;
    std::vector<std::size_t> group;
    for (std::size_t k = first; k < last; ++k) group.push_back(keyed[k].second);
    mark_open(edges, group, directions[group.front()], open);
    first = last;
  }
  return open;
}

}  // namespace

MeshTopology analyse_mesh(std::span<const glm::vec3> vertices, std::span<const std::uint32_t> layers,
                          std::size_t layer_count) {
  const std::size_t triangles = std::min(vertices.size() / 3, layers.size());
  MeshTopology topology;
  topology.open_edges_by_layer.assign(layer_count, 0);
  topology.inconsistent_edges_by_layer.assign(layer_count, 0);
  std::vector<glm::vec3> positions;
  const std::vector<std::uint32_t> ids = weld(vertices.first(3 * triangles), positions);

  std::vector<Edge> edges;
  edges.reserve(3 * triangles);
  for (std::uint32_t t = 0; t < triangles; ++t) {
    if (is_degenerate(&vertices[3u * std::size_t{t}])) {
      topology.degenerate_triangles += 1;
      continue;
    }
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t a = ids[3u * t + k], b = ids[3u * t + (k + 1) % 3];
      if (a == b) continue;  // cannot happen for a non-degenerate triangle; kept for safety
      edges.push_back(Edge{std::min(a, b), std::max(a, b), t, a > b});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return x.low != y.low ? x.low < y.low : x.high != y.high ? x.high < y.high : x.triangle < y.triangle;
  });

  UnionFind pieces(triangles);
  auto layer_of = [&](std::uint32_t t) { return layers[t] < layer_count ? layers[t] : 0u; };
  std::vector<OpenEdge> unpaired;
  for (std::size_t first = 0; first < edges.size();) {
    std::size_t last = first + 1;
    while (last < edges.size() && edges[last].low == edges[first].low && edges[last].high == edges[first].high) ++last;
    const std::size_t count = last - first;
    if (count == 1) {
      const Edge& e = edges[first];
      const glm::dvec3 low = glm::dvec3(positions[e.low]), high = glm::dvec3(positions[e.high]);
      unpaired.push_back(e.reversed ? OpenEdge{high, low, e.triangle} : OpenEdge{low, high, e.triangle});
    } else if (count == 2) {
      const Edge& a = edges[first];
      const Edge& b = edges[first + 1];
      if (a.reversed == b.reversed) {
        topology.inconsistent_edges += 1;
        if (layer_count > 0) topology.inconsistent_edges_by_layer[layer_of(a.triangle)] += 1;
      }
      pieces.unite(a.triangle, b.triangle);
    } else {
      topology.non_manifold_edges += 1;
    }
    first = last;
  }
  const std::vector<bool> open = really_open(unpaired);
  for (std::size_t e = 0; e < unpaired.size(); ++e) {
    if (!open[e]) continue;
    topology.open_edges += 1;
    if (layer_count > 0) topology.open_edges_by_layer[layer_of(unpaired[e].triangle)] += 1;
  }

  topology.triangle_solids.resize(triangles);
  std::vector<std::uint32_t> number(triangles, 0xFFFFFFFFu);
  for (std::uint32_t t = 0; t < triangles; ++t) {
    const std::uint32_t root = pieces.find(t);
    if (number[root] == 0xFFFFFFFFu) number[root] = topology.solid_count++;
    topology.triangle_solids[t] = number[root];
  }
  return topology;
}

}  // namespace sp
