#include "bvh/mesh_topology.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <compare>
#include <limits>
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

// The weld grid's cell of coordinate x on one axis (x a corner's
// coordinate, or one moved by kWeldDistance): floor(x / (2 kWeldDistance))
// where that is small, so that the corners within kWeldDistance of a corner
// lie in at most two cells per axis. From 4096 m out, floats are more than
// 2.4e-4 apart (past kWeldDistance), so only equal coordinates may weld and
// the float's own bits name the cell; x moved by kWeldDistance rounds back
// to x there. Cell numbers then stay far inside int64 at any coordinate (a
// level near 1e15 m overflowed x / 1e-4), and the two ranges never meet:
// |floor(x / 2e-4)| < 2^25 below 4096 m, the bits' cells lie beyond 2^40.
// A corner just below 4096 m and one at it are 2.4e-4 apart, too far to
// weld, so no neighbour is lost at the seam.
std::int64_t weld_cell(double x) {
  constexpr double kBitsFrom = 4096.0;
  constexpr std::int64_t kBitsBase = std::int64_t{1} << 40;
  if (std::abs(x) < kBitsFrom) return static_cast<std::int64_t>(std::floor(x / (2.0 * kWeldDistance)));
  // Within float's range first: rounding may carry a value just past it.
  const double largest = std::numeric_limits<float>::max();
  const float f = static_cast<float>(std::clamp(std::abs(x), 0.0, largest));
  const std::int64_t ordinal = kBitsBase + std::int64_t{std::bit_cast<std::uint32_t>(f)};
  return x < 0.0 ? -ordinal : ordinal;
}

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

  // Cells of the distinct corners, and a flat hash table from each occupied
  // cell to the run of corners in it (sorted by cell, then by u): a few
  // allocations for all, where a map of small vectors took a minute and
  // gigabytes at 2,000,000 scattered triangles.
  using Cell = std::array<std::int64_t, 3>;
  auto hash = [](const Cell& c) {
    std::uint64_t h = 0x9E3779B97F4A7C15u;
    for (std::int64_t v : c) h = (h ^ static_cast<std::uint64_t>(v)) * 0xBF58476D1CE4E5B9u;  // wraps, as a hash may
    return h ^ (h >> 29);
  };
  const auto unique_count = static_cast<std::uint32_t>(unique.size());
  std::vector<Cell> cells(unique_count);
  for (std::uint32_t u = 0; u < unique_count; ++u)
    cells[u] = Cell{weld_cell(unique[u].x), weld_cell(unique[u].y), weld_cell(unique[u].z)};
  std::vector<std::uint32_t> by_cell(unique_count);
  std::iota(by_cell.begin(), by_cell.end(), 0u);
  std::sort(by_cell.begin(), by_cell.end(),
            [&](std::uint32_t a, std::uint32_t b) { return cells[a] != cells[b] ? cells[a] < cells[b] : a < b; });
  std::vector<std::uint32_t> run_starts;  // into by_cell, one per occupied cell, then the end
  for (std::uint32_t k = 0; k < unique_count; ++k)
    if (k == 0 || cells[by_cell[k]] != cells[by_cell[k - 1]]) run_starts.push_back(k);
  run_starts.push_back(unique_count);
  std::size_t slots = 16;
  while (slots < 2 * run_starts.size()) slots *= 2;
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::vector<std::uint32_t> table(slots, kNone);  // run index, open addressing
  for (std::uint32_t r = 0; r + 1 < run_starts.size(); ++r) {
    std::size_t at = hash(cells[by_cell[run_starts[r]]]) & (slots - 1);
    while (table[at] != kNone) at = (at + 1) & (slots - 1);
    table[at] = r;
  }
  auto run_of = [&](const Cell& c) -> std::uint32_t {
    for (std::size_t at = hash(c) & (slots - 1);; at = (at + 1) & (slots - 1)) {
      if (table[at] == kNone || cells[by_cell[run_starts[table[at]]]] == c) return table[at];
    }
  };

  // Each corner, in order, welds to the first earlier corner that stayed
  // itself (a representative) within kWeldDistance, looking through the (at
  // most two per axis) cells that the box of that radius around it meets,
  // in a fixed order, and within a cell in the order of u.
  std::vector<std::uint32_t> welded(unique_count);
  std::vector<bool> representative(unique_count, false);
  for (std::uint32_t u = 0; u < unique_count; ++u) {
    const glm::dvec3 p(unique[u]);
    std::int64_t range[3][2];
    for (int a = 0; a < 3; ++a) {
      range[a][0] = weld_cell(p[a] - kWeldDistance);
      range[a][1] = weld_cell(p[a] + kWeldDistance);
    }
    std::uint32_t found = kNone;
    for (int i = 0; i < 8 && found == kNone; ++i) {
      const int ix = i & 1, iy = (i >> 1) & 1, iz = (i >> 2) & 1;
      // Each distinct cell once: the upper one only where it differs.
      if ((ix && range[0][1] == range[0][0]) || (iy && range[1][1] == range[1][0]) ||
          (iz && range[2][1] == range[2][0]))
        continue;
      const std::uint32_t r = run_of(Cell{range[0][ix], range[1][iy], range[2][iz]});
      if (r == kNone) continue;
      for (std::uint32_t k = run_starts[r]; k < run_starts[r + 1u]; ++k) {
        const std::uint32_t v = by_cell[k];
        if (v >= u) break;  // only corners already placed
        if (representative[v] && glm::distance(glm::dvec3(unique[v]), p) <= kWeldDistance) {
          found = welded[v];
          break;
        }
      }
    }
    if (found == kNone) {
      found = static_cast<std::uint32_t>(positions.size());
      positions.push_back(unique[u]);
      representative[u] = true;
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
// 0.2 mm (weld_cell: far out, to the float it rounds to), far below any gap
// that matters and far above float rounding.
struct LineKey {
  std::array<std::int64_t, 6> q;
  auto operator<=>(const LineKey&) const = default;
};

LineKey line_key(const glm::dvec3& direction, const glm::dvec3& foot) {
  auto round = [](double x) { return static_cast<std::int64_t>(std::llround(x / 1e-5)); };
  return LineKey{{round(direction.x), round(direction.y), round(direction.z), weld_cell(foot.x), weld_cell(foot.y),
                  weld_cell(foot.z)}};
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
  // Elementary stretches k between neighbouring cuts k and k + 1 (cuts
  // closer than the weld tolerance are one). Each interval's endpoints are
  // cuts, so it covers exactly the stretches from the first cut at its low
  // end to the last cut at its high end: a difference array gives every
  // stretch's net direction, and a prefix count of the unbalanced ones
  // tells each interval whether it covers one, in O(n log n) for n edges
  // on one line (a comb of 100,000 teeth puts them all on its spine).
  constexpr double kSame = 1e-4;
  const std::size_t stretches = cuts.size() - 1;
  std::vector<int> net(stretches + 1, 0);
  auto first_stretch = [&](const Interval& i) {
    return static_cast<std::size_t>(std::lower_bound(cuts.begin(), cuts.end(), i.lo) - cuts.begin());
  };
  auto end_stretch = [&](const Interval& i) {  // one past the last stretch covered
    return static_cast<std::size_t>(std::upper_bound(cuts.begin(), cuts.end(), i.hi) - cuts.begin()) - 1u;
  };
  for (const Interval& i : intervals) {
    net[first_stretch(i)] += i.sign;
    net[end_stretch(i)] -= i.sign;
  }
  std::vector<std::size_t> unbalanced_before(stretches + 1, 0);  // unbalanced stretches in [0, k)
  int running = 0;
  for (std::size_t k = 0; k < stretches; ++k) {
    running += net[k];
    const bool unbalanced = cuts[k + 1] - cuts[k] >= kSame && running != 0;
    unbalanced_before[k + 1] = unbalanced_before[k] + (unbalanced ? 1u : 0u);
  }
  for (const Interval& i : intervals) {
    const std::size_t from = first_stretch(i), to = end_stretch(i);
    if (to > from && unbalanced_before[to] > unbalanced_before[from]) open[i.edge] = true;
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
