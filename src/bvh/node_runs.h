// The binary BVH's node array as the build's threads write it: each thread's
// builder appends to a run of its own, and the subtrees it hands to other
// threads come back as runs of their own, kept apart until one pass places
// every node (assemble_node_runs).
//
// Why not splice each subtree into its parent's run as it finishes: subtrees
// handed out several levels deep were then copied once per level on their
// way to the root, which cost more than the finer hand-out saved in idle
// threads (bench/RESULTS.md section 24).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "bvh/bvh.h"

namespace sp {

class BuildWorkers;

// Nodes in the order a serial build appends them, with child indices local
// to the run. `inserts` go in between: insert k's nodes (all but its first)
// come right before nodes[at], and its first node is the subtree's root,
// which replaces the placeholder nodes[right].
struct NodeRun {
  struct Insert {
    std::uint32_t at;
    std::uint32_t right;
    std::unique_ptr<NodeRun> run;
  };

  LargeArray<BvhNode> nodes;
  std::vector<Insert> inserts;  // `at` ascending
  std::size_t total = 0;        // nodes once placed, set by finish()

  // Adds `run`, whose builder is done, as an insert at the end of the
  // nodes appended so far.
  void insert_at_end(std::uint32_t right, std::unique_ptr<NodeRun> run);
  // Sets `total`; once every insert's builder is done.
  void finish();
};

// Places `root` (its builder and those of all its inserts done, root.finish()
// called) into one array in serial-build order, child indices made global;
// the parts are copied concurrently on `workers`' threads.
LargeArray<BvhNode> assemble_node_runs(NodeRun& root, BuildWorkers& workers);

}  // namespace sp
