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

// The weld grid's cell width where coordinates are small: at least twice
// kWeldDistance, so that the corners within kWeldDistance of a corner lie
// in at most two cells per axis, and four times it, so that the box of that
// radius meets a second cell on an axis only a quarter of the time (about
// two cells in all, where a width of twice it always met eight: eight
// dependent cache misses a corner, 20 s at 2,000,000 triangles).
constexpr double kWeldCellWidth = 8.0 * kWeldDistance;

// The weld grid's cell of coordinate x on one axis (x a corner's
// coordinate, or one moved by kWeldDistance): floor(x / kWeldCellWidth)
// where that is small. From 4096 m out, floats are more than
// 2.4e-4 apart (past kWeldDistance), so only equal coordinates may weld and
// the float's own bits name the cell; x moved by kWeldDistance rounds back
// to x there. Cell numbers then stay far inside int64 at any coordinate (a
// level near 1e15 m overflowed x / 1e-4), and the two ranges never meet:
// |floor(x / 8e-4)| < 2^23 below 4096 m, the bits' cells lie beyond 2^40.
// A corner just below 4096 m and one at it are 2.4e-4 apart, too far to
// weld, so no neighbour is lost at the seam.
std::int64_t weld_cell(double x) {
  constexpr double kBitsFrom = 4096.0;
  constexpr std::int64_t kBitsBase = std::int64_t{1} << 40;
  if (std::abs(x) < kBitsFrom) return static_cast<std::int64_t>(std::floor(x / kWeldCellWidth));
  // Within float's range first: rounding may carry a value just past it.
  const double largest = std::numeric_limits<float>::max();
  const float f = static_cast<float>(std::clamp(std::abs(x), 0.0, largest));
  const std::int64_t ordinal = kBitsBase + std::int64_t{std::bit_cast<std::uint32_t>(f)};
  return x < 0.0 ? -ordinal : ordinal;
}

// Numbers n items by equality, in order of first occurrence (item i's
// group in groups[i]) through one flat open-addressing table, so O(n)
// whatever the input, where sorting 6,000,000 corners took seconds of
// comparisons at the 2,000,000-triangle limit. The table stays to find a
// group by a value later. Each slot holds an item and its hash's high half,
// which settles nearly every mismatch without reaching for the item: one
// cache miss a probe.
class EqualityTable {
 public:
  template <typename Hash, typename Equal>
  EqualityTable(std::uint32_t n, Hash hash, Equal equal, std::vector<std::uint32_t>& groups) {
    std::size_t slots = 16;
    while (slots < 2 * std::size_t{n}) slots *= 2;
    slots_.resize(slots);
    mask_ = slots - 1;
    groups.assign(n, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint64_t h = hash(i);
      const std::size_t at = probe(h, [&](std::uint32_t item) { return equal(item, i); });
      if (slots_[at].item == kNone) {
        slots_[at] = Slot{i, static_cast<std::uint32_t>(h >> 32)};
        groups[i] = group_count_++;
      } else {
        groups[i] = groups[slots_[at].item];
      }
    }
  }
  std::uint32_t group_count() const { return group_count_; }

  // An item equal to the value of hash h (`matches(item)` says whether it
  // is), or kNone.
  template <typename Matches>
  std::uint32_t find(std::uint64_t h, Matches matches) const {
    return slots_[probe(h, matches)].item;
  }

  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

 private:
  struct Slot {
    std::uint32_t item = kNone;
    std::uint32_t tag = 0;
  };
  template <typename Matches>
  std::size_t probe(std::uint64_t h, Matches matches) const {
    const auto tag = static_cast<std::uint32_t>(h >> 32);
    std::size_t at = h & mask_;
    while (slots_[at].item != kNone && !(slots_[at].tag == tag && matches(slots_[at].item))) at = (at + 1) & mask_;
    return at;
  }
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::uint32_t group_count_ = 0;
};

// splitmix64's finaliser over h ^ v: every input bit reaches the low bits
// the tables index by. A single multiply left neighbouring cells in runs of
// neighbouring slots, and linear probing through them cost 30 s at
// 2,000,000 triangles.
std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  std::uint64_t x = h ^ v;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9u;  // wraps, as a hash may
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBu;
  return x ^ (x >> 31);
}

}  // namespace

// Exact duplicates first, then corners within kWeldDistance of an earlier
// one (a grid of twice that cell size: a neighbour lies in one of the at
// most 8 cells the box of that radius meets). Both are hashed, O(n).
std::vector<std::uint32_t> weld(std::span<const glm::vec3> vertices, std::vector<glm::vec3>& positions) {
  using Key = std::array<std::uint32_t, 3>;
  auto key = [&](std::uint32_t i) {
    return Key{weld_bits(vertices[i].x), weld_bits(vertices[i].y), weld_bits(vertices[i].z)};
  };
  const auto vertex_count = static_cast<std::uint32_t>(vertices.size());
  std::vector<std::uint32_t> exact;
  const std::uint32_t unique_count = EqualityTable(
                                         vertex_count,
                                         [&](std::uint32_t i) {
                                           const Key k = key(i);
                                           return mix(mix(mix(0x9E3779B97F4A7C15u, k[0]), k[1]), k[2]);
                                         },
                                         [&](std::uint32_t a, std::uint32_t b) { return key(a) == key(b); }, exact)
                                         .group_count();
  std::vector<glm::vec3> unique(unique_count);
  for (std::uint32_t i = 0; i < vertex_count; ++i) unique[exact[i]] = vertices[i];

  // Cells of the distinct corners, and for each occupied cell the run of
  // its corners in order of u (a counting sort by cell number), found
  // through a flat hash table: a few allocations for all, where a map of
  // small vectors took a minute and gigabytes at 2,000,000 triangles.
  using Cell = std::array<std::int64_t, 3>;
  auto hash = [](const Cell& c) {
    return mix(mix(mix(0x9E3779B97F4A7C15u, static_cast<std::uint64_t>(c[0])), static_cast<std::uint64_t>(c[1])),
               static_cast<std::uint64_t>(c[2]));
  };
  std::vector<Cell> cells(unique_count);
  for (std::uint32_t u = 0; u < unique_count; ++u)
    cells[u] = Cell{weld_cell(unique[u].x), weld_cell(unique[u].y), weld_cell(unique[u].z)};
  std::vector<std::uint32_t> cell_of;  // a run index per corner
  const EqualityTable occupied(
      unique_count, [&](std::uint32_t u) { return hash(cells[u]); },
      [&](std::uint32_t a, std::uint32_t b) { return cells[a] == cells[b]; }, cell_of);
  const std::uint32_t run_count = occupied.group_count();
  std::vector<std::uint32_t> run_starts(std::size_t{run_count} + 1, 0);  // into by_cell
  for (std::uint32_t u = 0; u < unique_count; ++u) run_starts[cell_of[u] + 1u] += 1;
  std::partial_sum(run_starts.begin(), run_starts.end(), run_starts.begin());
  std::vector<std::uint32_t> by_cell(unique_count);
  {
    std::vector<std::uint32_t> next(run_starts.begin(), run_starts.end() - 1);
    for (std::uint32_t u = 0; u < unique_count; ++u) by_cell[next[cell_of[u]]++] = u;
  }
  constexpr std::uint32_t kNone = EqualityTable::kNone;
  auto run_of = [&](const Cell& c) -> std::uint32_t {
    const std::uint32_t u = occupied.find(hash(c), [&](std::uint32_t v) { return cells[v] == c; });
    return u == kNone ? kNone : cell_of[u];
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
    for (int i = -1; i < 8 && found == kNone; ++i) {
      // The corner's own cell first, known without a lookup (its run's
      // corners lie near it in memory); then each other cell once.
      std::uint32_t r = cell_of[u];
      if (i >= 0) {
        const int ix = i & 1, iy = (i >> 1) & 1, iz = (i >> 2) & 1;
        const Cell cell{range[0][ix], range[1][iy], range[2][iz]};
        // The upper one only where it differs.
        if ((ix && range[0][1] == range[0][0]) || (iy && range[1][1] == range[1][0]) ||
            (iz && range[2][1] == range[2][0]) || cell == cells[u])
          continue;
        r = run_of(cell);
      }
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

// An edge of one triangle, as the triangle runs it: from welded corner
// `from` to `to` (12 bytes: a level of 2,000,000 scattered triangles has
// 6,000,000 of them).
struct OpenEdge {
  std::uint32_t from;
  std::uint32_t to;
  std::uint32_t triangle;
};

// Collinear edges share a supporting line; lines are compared after
// rounding their direction to 1e-5 and their point nearest the origin to
// 0.2 mm (weld_cell: far out, to the float it rounds to), far below any gap
// that matters and far above float rounding.
struct LineKey {
  std::array<std::int64_t, 6> q;
  bool operator==(const LineKey&) const = default;
};

LineKey line_key(const glm::dvec3& direction, const glm::dvec3& foot) {
  auto round = [](double x) { return static_cast<std::int64_t>(std::llround(x / 1e-5)); };
  return LineKey{{round(direction.x), round(direction.y), round(direction.z), weld_cell(foot.x), weld_cell(foot.y),
                  weld_cell(foot.z)}};
}

// Marks the edges of `group` (all on one line) that are really open: some
// stretch of the edge is covered by more edges running one way along the
// line than the other. A closed surface runs every stretch once each way.
void mark_open(std::span<const OpenEdge> edges, std::span<const glm::vec3> positions,
               std::span<const std::uint32_t> group, const glm::dvec3& direction, std::vector<bool>& open) {
  struct Interval {
    double lo, hi;
    int sign;  // +1 along `direction`, -1 against
    std::size_t edge;
  };
  std::vector<Interval> intervals;
  std::vector<double> cuts;
  for (std::uint32_t e : group) {
    const double a = glm::dot(glm::dvec3(positions[edges[e].from]), direction);
    const double b = glm::dot(glm::dvec3(positions[edges[e].to]), direction);
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
  constexpr double kSame = kWeldDistance;
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

// The line an edge lies on: its direction (one per line: the first
// non-zero component positive) and its key.
struct EdgeLine {
  glm::dvec3 direction;
  LineKey key;
};

EdgeLine line_of(const OpenEdge& edge, std::span<const glm::vec3> positions) {
  const glm::dvec3 from(positions[edge.from]), to(positions[edge.to]);
  glm::dvec3 d = glm::normalize(to - from);
  const double lead = std::abs(d.x) > 1e-9 ? d.x : std::abs(d.y) > 1e-9 ? d.y : d.z;
  if (lead < 0.0) d = -d;
  const glm::dvec3 foot = from - d * glm::dot(from, d);
  return EdgeLine{d, line_key(d, foot)};
}

// Which of `edges` (each used by one triangle) are really open. Edges are
// grouped by line through a hash table, not a sort (O(n)); an edge alone on
// its line is open where it is longer than the weld tolerance, as
// mark_open would find, without its allocations.
std::vector<bool> really_open(std::span<const OpenEdge> edges, std::span<const glm::vec3> positions) {
  const auto n = static_cast<std::uint32_t>(edges.size());
  std::vector<std::uint32_t> line;
  const std::uint32_t line_count = EqualityTable(
                                       n,
                                       [&](std::uint32_t e) {
                                         std::uint64_t h = 0x9E3779B97F4A7C15u;
                                         for (std::int64_t v : line_of(edges[e], positions).key.q)
                                           h = mix(h, static_cast<std::uint64_t>(v));
                                         return h;
                                       },
                                       [&](std::uint32_t a, std::uint32_t b) {
                                         return line_of(edges[a], positions).key == line_of(edges[b], positions).key;
                                       },
                                       line)
                                       .group_count();
  // Edges by line, in order within each (a counting sort).
  std::vector<std::uint32_t> starts(std::size_t{line_count} + 1, 0);
  for (std::uint32_t e = 0; e < n; ++e) starts[line[e] + 1u] += 1;
  std::partial_sum(starts.begin(), starts.end(), starts.begin());
  std::vector<std::uint32_t> by_line(n);
  {
    std::vector<std::uint32_t> next(starts.begin(), starts.end() - 1);
    for (std::uint32_t e = 0; e < n; ++e) by_line[next[line[e]]++] = e;
  }
  std::vector<bool> open(edges.size(), false);
  for (std::uint32_t l = 0; l < line_count; ++l) {
    const std::span<const std::uint32_t> group(by_line.data() + starts[l], starts[l + 1] - starts[l]);
    if (group.size() == 1) {
      const OpenEdge& e = edges[group.front()];
      open[group.front()] = glm::distance(glm::dvec3(positions[e.from]), glm::dvec3(positions[e.to])) >= kWeldDistance;
      continue;
    }
    mark_open(edges, positions, group, line_of(edges[group.front()], positions).direction, open);
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
      unpaired.push_back(e.reversed ? OpenEdge{e.high, e.low, e.triangle} : OpenEdge{e.low, e.high, e.triangle});
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
  const std::vector<bool> open = really_open(unpaired, positions);
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
