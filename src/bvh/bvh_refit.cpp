// Refit of a built BVH to moved vertices, and the SAH cost that tells the
// caller when a refitted tree has degraded enough to rebuild.
//
// A refit keeps the topology (which triangles share a leaf, which nodes are
// siblings) and recomputes everything else with the builder's own helpers
// (bvh_geometry.h), so that a tree refitted to the vertices it was built
// from is byte-identical to the built one and traversal stays exact: node
// boxes are exact unions without padding, as build_bvh makes them, and the
// box test's own margin (sp_intersect_box) does the rest.
//
// Everything is computed aside and swapped in at the end, so a throw (bad
// input, or bad_alloc) leaves the caller's Bvh as it was.
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh_geometry.h"
#include "bvh/diffraction_edges.h"
#include "bvh/wide_bvh.h"
#include "bvh/bvh.h"
#include "soundpaint/result.h"

namespace sp {
namespace {

// Changed entries at most this many unchanged entries apart share a range:
// re-uploading 16 unchanged triangles (1 KiB) costs less than another copy
// region.
constexpr std::uint32_t kMergeGap = 16;

[[noreturn]] void fail(const std::string& message) {
  throw Exception(ErrorCode::InvalidArgument, "refit_bvh: " + message);
}

// Appended piece by piece: GCC 12's -Wrestrict misfires on "(" + std::string
// (GCC bug 105329).
std::string describe(glm::vec3 v) {
  std::string text = "(";
  text += std::to_string(v.x);
  text += ", ";
  text += std::to_string(v.y);
  text += ", ";
  text += std::to_string(v.z);
  text += ")";
  return text;
}

void check_vertices(const Bvh& bvh, std::span<const glm::vec3> vertices) {
  if (vertices.size() != 3u * bvh.triangle_count()) {
    fail("expected 3 vertices per triangle, " + std::to_string(3u * bvh.triangle_count()) + " for " +
         std::to_string(bvh.triangle_count()) + " triangles, got " + std::to_string(vertices.size()));
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const glm::vec3 v = vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      fail("vertex " + std::to_string(i) + " (of triangle " + std::to_string(i / 3u) +
           ") is not finite: " + describe(v));
  }
}

// The refit reads vertices through scene_index and computes every node from
// nodes after it in one reverse pass, and the wide copies it rebuilds
// (wide_collapse.cpp) scan the nodes assuming each but the root is the child
// of exactly one; build_bvh guarantees all of it (it appends a node's
// children after the node), but a tree made by hand may not.
void check_shape(const Bvh& bvh) {
  const std::size_t node_count = bvh.nodes.size();
  std::vector<std::uint8_t> parents(node_count, 0u);
  for (std::size_t i = 0; i < node_count; ++i) {
    const BvhNode& n = bvh.nodes[i];
    if (n.count > 0u) {
      if (std::size_t{n.left_or_first} + n.count > bvh.triangles.size())
        fail("leaf " + std::to_string(i) + " holds triangles past the end");
    } else if (n.left_or_first <= i || std::size_t{n.left_or_first} + 1u >= node_count) {
      fail("node " + std::to_string(i) + "'s children are not after it in the node array (not a build_bvh tree)");
    } else {
      for (std::uint32_t k = 0; k < 2u; ++k) {
        const std::uint32_t child = n.left_or_first + k;
        if (++parents[child] > 1u)
          fail("node " + std::to_string(child) + " is the child of two nodes (not a build_bvh tree)");
      }
    }
  }
  for (std::size_t i = 1; i < node_count; ++i) {
    if (parents[i] == 0u) fail("node " + std::to_string(i) + " is no node's child (not a build_bvh tree)");
  }
  for (std::size_t i = 0; i < bvh.triangles.size(); ++i) {
    if (bvh.triangles[i].scene_index >= bvh.triangle_count())
      fail("triangle " + std::to_string(i) + " has scene index " + std::to_string(bvh.triangles[i].scene_index) +
           " >= the triangle count");
  }
}

LargeArray<BvhTriangle> refit_triangles(const LargeArray<BvhTriangle>& old, std::span<const glm::vec3> vertices) {
  LargeArray<BvhTriangle> fresh;
  fresh.reserve(old.size());
  for (const BvhTriangle& t : old)
    fresh.push_back(make_bvh_triangle(&vertices[3u * std::size_t{t.scene_index}], t.layer, t.scene_index, t.solid));
  return fresh;
}

// A leaf's box grown over its triangles' stored corners in leaf order, as
// the builder's per-triangle records are (a degenerate triangle is stored
// collapsed onto v0, and its record is that point).
Box leaf_box(const BvhNode& leaf, const LargeArray<BvhTriangle>& triangles) {
  Box box;
  for (std::uint32_t i = leaf.left_or_first; i < leaf.left_or_first + leaf.count; ++i) {
    const BvhTriangle& t = triangles[i];
    box.grow(to_vec4(t.v0));
    box.grow(to_vec4(t.v1));
    box.grow(to_vec4(t.v2));
  }
  return box;
}

// Per component: the old bits where old and new are equal as floats. Only
// +0 and -0 differ that way, and which of them a min or max keeps depends on
// the order it scans; the builder scanned inner nodes' triangles before
// partitioning them further, so recomputing would flip some zeros and
// report nodes as changed that did not move.
glm::vec3 keep_equal_bits(glm::vec3 old, glm::vec3 fresh) {
  for (int a = 0; a < 3; ++a) {
    if (fresh[a] == old[a]) fresh[a] = old[a];
  }
  return fresh;
}

// Every node's box, bottom-up: one reverse pass, since children come after
// their parent (check_shape).
LargeArray<BvhNode> refit_nodes(const LargeArray<BvhNode>& old, const LargeArray<BvhTriangle>& triangles) {
  std::vector<Box> boxes(old.size());
  for (std::size_t i = old.size(); i-- > 0;) {
    const BvhNode& n = old[i];
    if (n.count > 0u) {
      boxes[i] = leaf_box(n, triangles);
    } else {
      boxes[i].grow(boxes[n.left_or_first]);
      boxes[i].grow(boxes[n.left_or_first + 1u]);
    }
  }
  LargeArray<BvhNode> fresh(old);
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    fresh[i].bmin = keep_equal_bits(old[i].bmin, to_vec3(boxes[i].lo));
    fresh[i].bmax = keep_equal_bits(old[i].bmax, to_vec3(boxes[i].hi));
  }
  return fresh;
}

// Indices whose entries differ bitwise, as merged half-open ranges.
template <class T>
std::vector<BvhIndexRange> changed_ranges(std::span<const T> old, std::span<const T> fresh) {
  // No padding to compare: every vec3 is paired with a 4-byte scalar (sp_types.h).
  static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % 16u == 0u);
  std::vector<BvhIndexRange> ranges;
  for (std::size_t i = 0; i < old.size(); ++i) {
    if (std::memcmp(&old[i], &fresh[i], sizeof(T)) == 0) continue;
    const auto index = static_cast<std::uint32_t>(i);
    if (!ranges.empty() && index - ranges.back().last <= kMergeGap) {
      ranges.back().last = index + 1u;
    } else {
      ranges.push_back(BvhIndexRange{index, index + 1u});
    }
  }
  return ranges;
}

// Half the surface area (the ratios are the same as for full areas), in
// double: a large scene sums a million ratios, which float would blur.
double node_half_area(const BvhNode& n) {
  const glm::dvec3 d = glm::dvec3(n.bmax) - glm::dvec3(n.bmin);
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

BvhChanges refit(Bvh& bvh, std::span<const glm::vec3> vertices) {
  check_vertices(bvh, vertices);
  check_shape(bvh);

  Bvh next;
  next.triangles = refit_triangles(bvh.triangles, vertices);
  next.nodes = refit_nodes(bvh.nodes, next.triangles);
  BvhChanges changes{
      changed_ranges<BvhNode>(bvh.nodes, next.nodes), changed_ranges<BvhTriangle>(bvh.triangles, next.triangles), {}};
  if (changes.nodes.empty() && changes.triangles.empty()) return changes;  // the wide copy and edges still hold
  // Moved faces may meet at other angles, or bury or uncover an edge.
  if (!bvh.edges.empty()) {
    next.edges = bvh.edges;
    glm::vec3 lo(SP_FAR), hi(-SP_FAR);
    for (std::size_t i = 0; i < next.triangles.size(); ++i) {
      if (std::memcmp(&bvh.triangles[i], &next.triangles[i], sizeof(BvhTriangle)) == 0) continue;
      for (const BvhTriangle* t : {&bvh.triangles[i], &next.triangles[i]}) {
        lo = glm::min(lo, glm::min(glm::min(t->v0, t->v1), t->v2));
        hi = glm::max(hi, glm::max(glm::max(t->v0, t->v1), t->v2));
      }
    }
    // Grown by the burying distance, and a weld's width for the rounding.
    const glm::vec3 margin(kBuriedEdgeDistance + 1.0e-3f);
    refresh_exposed_edges(next, lo - margin, hi + margin, next.edges);
    changes.edges = changed_ranges<shader::TriangleEdges>(bvh.edges, next.edges);
  }

  // A wide copy is immutable and may be shared with copies of `bvh`: build a
  // new one. A Bvh without one keeps walking `nodes`, as its owner chose.
  if (bvh.wide) next.wide = std::make_shared<const WideBvh>(build_wide_bvh(next));
  bvh.nodes.swap(next.nodes);
  bvh.triangles.swap(next.triangles);
  if (!bvh.edges.empty()) bvh.edges.swap(next.edges);
  bvh.wide = std::move(next.wide);
  return changes;
}

}  // namespace

Result<BvhChanges> refit_bvh(Bvh& bvh, std::span<const glm::vec3> vertices) {
  return capture_errors([&] { return refit(bvh, vertices); });
}

double bvh_sah_cost(const Bvh& bvh, float traversal_cost) {
  if (bvh.nodes.empty()) return 0.0;
  const double root_area = node_half_area(bvh.nodes[0]);
  double cost = 0.0;
  for (const BvhNode& n : bvh.nodes) {
    // Inside a zero-area root every box has zero area too: 0/0 counts as 1.
    const double ratio = root_area > 0.0 ? node_half_area(n) / root_area : 1.0;
    cost += ratio * (n.count > 0u ? static_cast<double>(n.count) : static_cast<double>(traversal_cost));
  }
  return cost;
}

}  // namespace sp
