// build_wide_bvh: the 4-wide and 8-wide copies of a binary BVH for the CPU
// walks (wide_bvh.h has the layouts and why they are as they are).
//
// Three independent parts, run as tasks of the build's threads:
//  - the packets: each binary leaf's triangles as TrianglePackets, leaves in
//    binary node order, so that every leaf's first packet is known from one
//    scan of the nodes before any is written;
//  - the 4-wide nodes, the root's subtrees concurrently;
//  - the 8-wide nodes (wide8_walk.cpp), where the CPU runs their walk.
// The nodes only point at packets, so none waits for another. Every part
// writes what a serial build writes, wherever it runs.
#include <algorithm>
#include <cassert>
#include <limits>

#include "bvh/build_workers.h"
#include "bvh/wide8_walk.h"
#include "bvh/wide_bvh.h"
#include "bvh/wide_walk_parts.h"

namespace sp {
namespace {

using wide_walk::is_interior_slot;
using wide_walk::packets_of_leaf;
using wide_walk::wide_slots;

// What the collapses will write, from one scan of the binary nodes.
struct CollapseLayout {
  std::uint32_t packets = 0;
  std::uint32_t wide8_nodes = 0;
  // 4-wide nodes below each slot of the root's wide node (see collapse_wide4).
  std::uint32_t wide4_subtree_nodes[kWideArity] = {};

  std::uint32_t wide4_nodes() const {
    std::uint32_t nodes = 1u;
    for (const std::uint32_t n : wide4_subtree_nodes) nodes += n;
    return nodes;
  }
};

// Sets leaf_packets[n] to the first packet of each binary leaf n, leaves in
// node order, and counts the wide nodes. A 4-wide node replaces each binary
// interior node at an even depth (root 0), an 8-wide one each at a depth
// divisible by three (wide_bvh.h). Nodes follow their parents in the array,
// so one forward scan sees each node's depth, written by its parent into
// the node's own leaf_packets entry, which it holds until a leaf's packet
// overwrites it.
CollapseLayout lay_out(const Bvh& bvh, std::span<std::uint32_t> leaf_packets) {
  // An interior node's entry: its depth, and which slot of the root's
  // 4-wide node it lies below (from depth 2 on; at depth 1, which child of
  // the root it is).
  constexpr std::uint32_t kSlotShift = 8u;
  static_assert(SP_BVH_MAX_DEPTH < (1u << kSlotShift));
  CollapseLayout layout;
  leaf_packets[0] = 0u;
  for (std::size_t n = 0; n < bvh.nodes.size(); ++n) {
    const BvhNode& node = bvh.nodes[n];
    if (node.count > 0u) {
      leaf_packets[n] = layout.packets;
      layout.packets += packets_of_leaf(node);
      continue;
    }
    const std::uint32_t depth = leaf_packets[n] & ((1u << kSlotShift) - 1u);
    const std::uint32_t slot = leaf_packets[n] >> kSlotShift;
    if (depth % 3u == 0u) ++layout.wide8_nodes;
    if (depth % 2u == 0u && depth > 0u) ++layout.wide4_subtree_nodes[slot];
    for (std::uint32_t k = 0; k < 2u; ++k) {
      const std::uint32_t child_slot = depth == 0u ? k : depth == 1u ? 2u * slot + k : slot;
      leaf_packets[node.left_or_first + k] = (child_slot << kSlotShift) | (depth + 1u);
    }
  }
  return layout;
}

// Packs the triangles of the leaves among binary nodes [first, last) into
// their packets.
void write_packets(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, std::size_t first, std::size_t last,
                   WideBvh& wide) {
  for (std::size_t n = first; n < last; ++n) {
    const BvhNode& leaf = bvh.nodes[n];
    if (leaf.count == 0u) continue;
    TrianglePacket* out = &wide.packets[leaf_packets[n]];
    for (std::uint32_t base = 0; base < leaf.count; base += kWideArity, ++out) {
      TrianglePacket p{};  // padding lanes: vertices at the origin
      for (std::uint32_t lane = 0; lane < kWideArity; ++lane) {
        if (base + lane >= leaf.count) {
          p.triangle[lane] = SP_INVALID;
          continue;
        }
        const std::uint32_t i = leaf.left_or_first + base + lane;
        const BvhTriangle& t = bvh.triangles[i];
        const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k)
          for (int a = 0; a < 3; ++a) p.v[k][a].set(static_cast<int>(lane), v[k][a]);
        p.triangle[lane] = i;
      }
      *out = p;
    }
  }
}

// write_packets over binary nodes [first, last) in `pieces` parts, halved
// recursively and offered to `forks`: a thread that runs out of work takes
// the largest part left, so the threads finish together.
void write_packets_in_parts(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, std::size_t first,
                            std::size_t last, std::uint32_t pieces, BuildWorkers& forks, WideBvh& wide) {
  if (pieces <= 1u) return write_packets(bvh, leaf_packets, first, last, wide);
  const std::size_t middle = first + (last - first) / 2u;
  forks.run_both([&] { write_packets_in_parts(bvh, leaf_packets, middle, last, pieces / 2u, forks, wide); },
                 [&] { write_packets_in_parts(bvh, leaf_packets, first, middle, pieces / 2u, forks, wide); });
}

// Writes the 4-wide nodes of one binary subtree into wide.nodes, already
// sized, from position `cursor` on, depth first (children after their
// parent). Collapsers of disjoint subtrees, given the positions a serial
// collapse would reach, write disjoint parts of the array and together
// write exactly what one serial collapse writes.
class Collapser {
 public:
  Collapser(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, WideBvh& wide, std::uint32_t cursor)
      : bvh_(bvh), leaf_packets_(leaf_packets), wide_(wide), cursor_(cursor) {}

  // The wide node of binary interior node `binary` at wide level `level`,
  // and its subtree; returns its index.
  std::uint32_t collapse(std::uint32_t binary, std::uint32_t level) {
    std::uint32_t slots[kWideArity];
    const std::uint32_t index = write_node(binary, level, slots);
    for (std::uint32_t s = 0; s < kWideArity; ++s) {
      if (is_interior_slot(bvh_, slots[s])) wide_.nodes[index].slot[s].child = collapse(slots[s], level + 1u);
    }
    return index;
  }

  // The wide node of binary interior node `binary` alone, with its leaf
  // slots; its interior slots' children are left for the caller.
  std::uint32_t write_node(std::uint32_t binary, std::uint32_t level, std::uint32_t (&slots)[kWideArity]) {
    depth_ = std::max(depth_, level);
    wide_slots(bvh_, binary, slots);
    const std::uint32_t index = cursor_++;
    WideNode& node = wide_.nodes[index];
    node = empty_node();
    for (std::uint32_t s = 0; s < kWideArity; ++s)
      if (slots[s] != SP_INVALID) fill_slot(node, s, slots[s]);
    return index;
  }

  // The root when it is a single leaf: a wide root with one slot.
  void collapse_leaf_root() {
    depth_ = 1u;
    WideNode& root = wide_.nodes[cursor_++];
    root = empty_node();
    fill_slot(root, 0u, 0u);
  }

  std::uint32_t depth() const { return depth_; }

 private:
  static WideNode empty_node() {
    WideNode node{};
    for (Vec4& b : node.bounds) b = splat(std::numeric_limits<float>::quiet_NaN());
    return node;
  }

  // Slot `slot` of `node` becomes binary node `binary`; a leaf gets its
  // packets now, an interior node its wide index later.
  void fill_slot(WideNode& node, std::uint32_t slot, std::uint32_t binary) {
    const BvhNode& n = bvh_.nodes[binary];
    for (int a = 0; a < 3; ++a) {
      node.bounds[a].set(static_cast<int>(slot), n.bmin[a]);
      node.bounds[3 + a].set(static_cast<int>(slot), n.bmax[a]);
    }
    if (n.count > 0u) node.slot[slot] = WideSlot{leaf_packets_[binary], packets_of_leaf(n)};
  }

  const Bvh& bvh_;
  std::span<const std::uint32_t> leaf_packets_;
  WideBvh& wide_;
  std::uint32_t cursor_;
  std::uint32_t depth_ = 0;
};

// The 4-wide nodes: the root's node, then the subtree of each interior slot
// in slot order, the four subtrees offered to `forks`' threads.
void collapse_wide4(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, const CollapseLayout& layout,
                    BuildWorkers& forks, WideBvh& wide) {
  if (bvh.nodes[0].count > 0u) {
    wide.nodes.resize(1u);
    Collapser collapser(bvh, leaf_packets, wide, 0u);
    collapser.collapse_leaf_root();
    wide.depth = collapser.depth();
    return;
  }
  std::uint32_t slots[kWideArity];
  wide_slots(bvh, 0u, slots);
  auto interior = [&](std::uint32_t s) { return is_interior_slot(bvh, slots[s]); };
  std::uint32_t start[kWideArity] = {};
  std::uint32_t total = 1u;
  for (std::uint32_t s = 0; s < kWideArity; ++s) {
    start[s] = total;
    total += layout.wide4_subtree_nodes[s];
  }
  wide.nodes.resize(total);

  Collapser root(bvh, leaf_packets, wide, 0u);
  root.write_node(0u, 1u, slots);
  for (std::uint32_t s = 0; s < kWideArity; ++s)
    if (interior(s)) wide.nodes[0].slot[s].child = start[s];
  std::uint32_t subtree_depth[kWideArity] = {};
  auto collapse_subtree = [&](std::uint32_t s) {
    if (!interior(s)) return;
    Collapser collapser(bvh, leaf_packets, wide, start[s]);
    collapser.collapse(slots[s], 2u);
    subtree_depth[s] = collapser.depth();
  };
  static_assert(kWideArity == 4u);
  auto collapse_pair = [&](std::uint32_t first) {
    forks.run_both([&] { collapse_subtree(first + 1u); }, [&] { collapse_subtree(first); });
  };
  forks.run_both([&] { collapse_pair(2u); }, [&] { collapse_pair(0u); });
  wide.depth = root.depth();
  for (const std::uint32_t depth : subtree_depth) wide.depth = std::max(wide.depth, depth);
}

}  // namespace

WideBvh build_wide_bvh(const Bvh& bvh, BuildWorkers* workers) {
  assert(!bvh.nodes.empty());
  BuildWorkers serial(1u);
  BuildWorkers& forks = workers != nullptr ? *workers : serial;
  WideBvh wide;
  // Each binary leaf's first packet; entries of interior nodes are
  // lay_out's scratch.
  LargeArray<std::uint32_t> leaf_packets(bvh.nodes.size());
  const CollapseLayout layout = lay_out(bvh, leaf_packets);
  wide.packets.resize(layout.packets);

  // The 8-wide tree where this CPU walks it, up to its size limit; the
  // 4-wide one always, for the walks select_wide_walk may choose instead.
  const std::size_t wide4_bytes =
      std::size_t{layout.wide4_nodes()} * sizeof(WideNode) + std::size_t{layout.packets} * sizeof(TrianglePacket);
  const bool with_wide8 = wide8::cpu_runs() && wide4_bytes <= kWide8MaxTreeBytes;
  // The packets are most of the work (about 70 % at 252k triangles), so
  // they go in parts that fill in around the two collapses.
  constexpr std::uint32_t kPacketParts = 8;
  forks.run_both(
      [&] {
        if (with_wide8) wide8::collapse(bvh, leaf_packets, layout.wide8_nodes, wide);
      },
      [&] {
        write_packets_in_parts(bvh, leaf_packets, 0u, bvh.nodes.size(), kPacketParts, forks, wide);
        collapse_wide4(bvh, leaf_packets, layout, forks, wide);
      });
  return wide;
}

}  // namespace sp
