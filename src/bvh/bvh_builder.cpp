// Binned SAH build of the BVH, written directly in the flattened layout of
// shaders/shared/sp_types.h.
//
// References: Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", IEEE Symposium on Interactive Ray Tracing 2007 (binning over
// centroid bounds, incremental sweeps); MacDonald and Booth, "Heuristics for
// ray tracing using space subdivision", The Visual Computer 6(3), 1990 (SAH).
//
// Shape of the work: one array of per-triangle bounds (with a parallel array
// of input indices) is partitioned in place, so every node owns a contiguous
// range and a leaf's range is directly its slice of Bvh::triangles. Children
// are appended as a pair, which gives the adjacency the traversal relies on
// without a separate flattening pass; each leaf writes its triangles into
// Bvh::triangles as it is made, so there is no gather pass after the build
// either. The partition measures the children's bounds as it goes, so each
// binned node reads its triangles twice (binning, partition). Scratch memory
// is allocated once per build; nodes of at most kSmallNode triangles, the
// large majority, take an exact sweep instead of bins. Threads
// (build_workers.h, started once per build): the root's passes over all
// triangles (binning, partition) run as two halves, every subtree of
// kForkMin triangles or more is offered to the other threads as a task that
// builds into a node run of its own (node_runs.h, placed once at the end),
// and the big arrays sit on huge pages (large_array.h), whose first-touch
// faults otherwise cost more than the build in a virtual machine.
#include <atomic>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/build_workers.h"
#include "bvh/bvh_geometry.h"
#include "bvh/node_runs.h"
#include "bvh/wide_bvh.h"
#include "bvh/bvh.h"

namespace sp {
namespace {

// More bins rarely improve the tree but make every node visit slower; 256
// also keeps the scratch arrays small.
constexpr std::uint32_t kMaxBins = 256;
// Up to this many triangles, sorting the centroids on each axis and sweeping
// every split is cheaper than binning, and exact.
constexpr std::uint32_t kSmallNode = 8;
// Builds of fewer triangles run on the calling thread alone: starting a
// thread costs more than it saves.
constexpr std::uint32_t kParallelMin = 16384;
// A right subtree this large or larger is offered to the other threads
// (Builder::subdivide_pair_in_parallel), at any depth: splits are uneven,
// and a thread that runs out of work needs pieces left to take. Smaller
// pieces cost more in scratch and hand-over than they save in waiting.
// On the benchmark VM at 252k triangles, 8192 took 23.1 ms on 2 threads,
// 16384 24.1, 65536 24.9 and 4096 25.4 (bench/RESULTS.md section 24).
constexpr std::uint32_t kForkMin = 8192;
// The root's passes (binning, partition) and the wide copies' tasks go to
// a second thread only from this many triangles on: on the
// benchmark VM, doing so at 30k triangles made the build 3x slower (4.7 ->
// 15 ms; bench/RESULTS.md section 12), while at 252k and 1M it pays.
constexpr std::uint32_t kConcurrentPassMin = 131072;
// More threads than a build can keep busy only wait.
constexpr unsigned kMaxThreads = 256;

// Runs f(begin, end) over [0, count): split in two halves, one offered to
// another thread, when `parallel`, else in one call. For loops whose
// iterations write disjoint elements only.
template <class F>
void for_halves(BuildWorkers& workers, bool parallel, std::uint32_t count, F&& f) {
  if (!parallel) return f(0u, count);
  const std::uint32_t mid = count / 2u;
  workers.run_both([&f, mid] { f(0u, mid); }, [&f, mid, count] { f(mid, count); });
}

// Runs `a` and `b`, offering `a` to another thread when `concurrent`.
template <class A, class B>
void run_both(BuildWorkers& workers, bool concurrent, A&& a, B&& b) {
  if (concurrent) return workers.run_both(a, b);
  a();
  b();
}

// One triangle's bounds. The centroid used for splitting is the bounds
// centre, kept doubled (lo + hi) because only its order matters. 32 bytes, so
// partitioning moves whole cache lines sequentially.
struct Record {
  Vec4 lo;
  Vec4 hi;
};

// Maps doubled centroids to bins. Binning and partitioning call the same
// function so both agree on every triangle's side.
struct Binning {
  Vec4 origin = {};  // doubled centroid minimum
  Vec4 scale = {};   // bins / doubled centroid extent per axis; 0 for a flat axis
  Vec4 last = {};    // bins - 1
  std::uint32_t bins = 0;

  Binning() = default;
  Binning(const Box& centroids, std::uint32_t bin_count) : bins(bin_count) {
    const auto top = static_cast<float>(bins - 1u);
    origin = centroids.lo;
    scale = Vec4{};
    last = Vec4{top, top, top, top};
    for (int a = 0; a < 3; ++a) {
      float extent = centroids.hi[a] - centroids.lo[a];
      float s = static_cast<float>(bins) / extent;
      // A zero or subnormal extent cannot be binned (and would make NaNs).
      scale.set(a, (extent > 0.0f && std::isfinite(s)) ? s : 0.0f);
    }
  }
  // Bins on all three axes at once. (c - origin) * scale lies in
  // [0, bins * (1 + rounding)]; the top edge goes to the last bin. Clamped
  // in float, where SSE2 has a vector min (minps) and integers have none.
  Int4 bin(Vec4 doubled_centroid) const { return to_int4(vmin((doubled_centroid - origin) * scale, last)); }
};

// Per-axis bins of one binning pass: each bin's bounds and triangle count.
struct BinTable {
  std::vector<Box> boxes[3];
  std::vector<std::uint32_t> counts[3];

  void reset(std::uint32_t bins) {
    for (int a = 0; a < 3; ++a) {
      boxes[a].assign(bins, Box{});
      counts[a].assign(bins, 0u);
    }
  }
  // Adds `other`'s triangles: bounds and counts combine exactly, so two
  // halves binned apart and merged equal one pass over the whole.
  void merge(const BinTable& other, std::uint32_t bins) {
    for (int a = 0; a < 3; ++a) {
      for (std::uint32_t b = 0; b < bins; ++b) {
        boxes[a][b].grow(other.boxes[a][b]);
        counts[a][b] += other.counts[a][b];
      }
    }
  }
};

// The best split found for a node.
struct Split {
  bool valid = false;
  int axis = 0;
  std::int32_t last_left = 0;  // binned: bins [0, last_left] go left; small: left count
  float cost = 0.0f;           // A_L * N_L + A_R * N_R, not yet divided by A_parent
};

// The bounds of some triangles' records and of their doubled centroids:
// a node's box, and what its binning spans.
struct Extent {
  Box bounds;
  Box centroids;

  void add(const Record& r) {
    bounds.grow(r.lo, r.hi);
    centroids.grow(r.lo + r.hi);
  }
  void add(const Extent& other) {
    bounds.grow(other.bounds);
    centroids.grow(other.centroids);
  }
};

// The extents of a split node's two sides.
struct Sides {
  Extent left, right;

  void add(const Sides& other) {
    left.add(other.left);
    right.add(other.right);
  }
};

// Writes each leaf's triangles into Bvh::triangles as the leaf is made, on
// whichever thread makes it, while its indices are still in cache.
struct LeafWriter {
  std::span<const glm::vec3> vertices;
  std::span<const std::uint32_t> layers;
  std::span<const std::uint32_t> solids;
  BvhTriangle* out;

  void write(std::uint32_t first, std::uint32_t count, const std::uint32_t* sources) const {
    for (std::uint32_t i = 0; i < count; ++i) {
      const std::uint32_t source = sources[i];
      const std::uint32_t solid = source < solids.size() ? solids[source] : source;
      out[first + i] = make_bvh_triangle(&vertices[3u * std::size_t{source}], layers[source], source, solid);
    }
  }
};

class Builder {
 public:
  // `workers` runs the build's forks; with one thread there are none.
  // `nodes` receives the tree.
  Builder(std::span<const glm::vec3> vertices, std::uint32_t count, const BvhBuildSettings& settings,
          BuildWorkers& workers, const LeafWriter& leaves, NodeRun& nodes)
      : run_(&nodes), workers_(&workers), leaves_(&leaves), forks_(workers.size() > 1u) {
    bins_ = std::clamp(settings.bins, 2u, kMaxBins);
    max_leaf_size_ = std::max(settings.max_leaf_size, 1u);
    max_depth_ = std::clamp(settings.max_depth, 1u, static_cast<std::uint32_t>(SP_BVH_MAX_DEPTH));
    traversal_cost_ = settings.traversal_cost;

    records_.resize(count);
    indices_.resize(count);
    for_halves(workers, parallel(count), count, [&](std::uint32_t first, std::uint32_t last) {
      for (std::uint32_t i = first; i < last; ++i) {
        const glm::vec3* v = &vertices[3u * std::size_t{i}];
        // Bounds of the vertices make_bvh_triangle stores: a degenerate
        // triangle is collapsed onto v[0].
        const Vec4 v0 = to_vec4(v[0]);
        records_[i] = is_degenerate(v) ? Record{v0, v0}
                                       : Record{vmin(vmin(v0, to_vec4(v[1])), to_vec4(v[2])),
                                                vmax(vmax(v0, to_vec4(v[1])), to_vec4(v[2]))};
        indices_[i] = i;
      }
    });
    records_ptr_ = records_.data();
    indices_ptr_ = indices_.data();
    allocate_scratch();
    // A binary tree with n leaves has 2n - 1 nodes; reserving that bound
    // means no reallocation during the build.
    run_->nodes.reserve(2u * std::size_t{count} - 1u);
  }

  void build() {
    const auto count = static_cast<std::uint32_t>(records_.size());
    const Extent all = measure(0, count);
    run_->nodes.push_back(make_node(all.bounds));
    subdivide(0, 0, count, 1, all.centroids);
    run_->finish();
  }

  std::uint32_t depth() const { return depth_; }
  // Whether a pass over `count` triangles is worth splitting across threads.
  bool parallel(std::uint32_t count) const { return forks_ && count >= kParallelMin; }
  // Whether a single pass over `count` triangles (the root's, the wide
  // copy's) is worth a second thread.
  bool concurrent_pass(std::uint32_t count) const { return parallel(count) && count >= kConcurrentPassMin; }

 private:
  // A builder for one subtree, run on another thread: it shares the
  // settings and the records and indices (it touches only its own range of
  // them), and has its own scratch, depth and node run. `nodes` holds the
  // subtree's root at index 0, and its descendants follow in the order the
  // serial build would append them.
  Builder(const Builder& parent, NodeRun& nodes)
      : run_(&nodes),
        workers_(parent.workers_),
        leaves_(parent.leaves_),
        bins_(parent.bins_),
        max_leaf_size_(parent.max_leaf_size_),
        max_depth_(parent.max_depth_),
        traversal_cost_(parent.traversal_cost_),
        forks_(parent.forks_),
        records_ptr_(parent.records_ptr_),
        indices_ptr_(parent.indices_ptr_) {
    allocate_scratch();
  }

  void allocate_scratch() {
    bin_table_.reset(bins_);
    right_area_.resize(bins_);
    right_count_.resize(bins_);
  }

  // Builds the subtree of run_->nodes[right] (already appended, with its
  // bounds) into a run of its own, offered to another thread, while this
  // one builds the left sibling's, then inserts it where the serial build
  // appends it: after the left subtree.
  void subdivide_pair_in_parallel(std::uint32_t left, std::uint32_t begin, std::uint32_t middle, std::uint32_t end,
                                  std::uint32_t level, const Box& left_centroids, const Box& right_centroids) {
    const std::uint32_t right = left + 1u;
    auto sub = std::make_unique<NodeRun>();
    sub->nodes.reserve(2u * std::size_t{end - middle} - 1u);
    sub->nodes.push_back(run_->nodes[right]);
    Builder worker(*this, *sub);
    workers_->run_both(
        [&worker, middle, end, level, &right_centroids] { worker.subdivide(0, middle, end, level, right_centroids); },
        [&] { subdivide(left, begin, middle, level, left_centroids); });
    depth_ = std::max(depth_, worker.depth_);
    sub->finish();
    run_->insert_at_end(right, std::move(sub));
  }
  static BvhNode make_node(const Box& box) { return BvhNode{to_vec3(box.lo), 0u, to_vec3(box.hi), 0u}; }

  // The extent of records [begin, end), accumulated in a local: the
  // compiler cannot keep boxes behind references in registers.
  Extent measure(std::uint32_t begin, std::uint32_t end) const {
    Extent extent;
    for (std::uint32_t i = begin; i < end; ++i) extent.add(records_ptr_[i]);
    return extent;
  }

  void subdivide(std::uint32_t node, std::uint32_t begin, std::uint32_t end, std::uint32_t level,
                 const Box& centroids) {
    depth_ = std::max(depth_, level);
    const std::uint32_t count = end - begin;
    // The depth cap overrides the leaf size: the traversal stack holds one
    // entry per level and must never overflow.
    if (count == 1u || level >= max_depth_) return make_leaf(node, begin, count);

    // The root's passes over all triangles run on two threads; below it, the
    // subtrees do (subdivide_pair_in_parallel).
    const bool concurrent = level == 1u && concurrent_pass(count);
    const bool small = count <= kSmallNode;
    Binning binning;
    Split split;
    if (small) {
      split = find_small_split(begin, count);
    } else {
      // A node with fewer triangles than bins gets as many bins as
      // triangles: the planes it loses lie between empty bins.
      binning = Binning(centroids, std::min(bins_, count));
      split = find_split(begin, end, binning, concurrent);
    }
    if (count <= max_leaf_size_) {
      // Small enough for a leaf: split only where the SAH says it pays off.
      const BvhNode& n = run_->nodes[node];
      const float parent_area = half_area(Box{to_vec4(n.bmin), to_vec4(n.bmax)});
      const bool split_pays =
          split.valid && parent_area > 0.0f && traversal_cost_ + split.cost / parent_area < static_cast<float>(count);
      if (!split_pays) return make_leaf(node, begin, count);
    }

    std::uint32_t middle;
    Sides sides;
    if (split.valid && !small) {
      // Only the root's partition is halved, and by its size alone, so the
      // tree is the same for every thread count.
      const bool halve = level == 1u && count >= kConcurrentPassMin;
      middle = partition(begin, end, binning, split, halve, concurrent, sides);
    } else {
      if (small) {
        apply_small_split(begin, count, split);
        middle = begin + static_cast<std::uint32_t>(split.last_left);
      } else {
        // All centroids coincide (or are too close to bin): no plane
        // separates them, so halve the range to keep leaves within
        // max_leaf_size.
        middle = begin + count / 2u;
      }
      run_both(
          *workers_, concurrent, [&] { sides.right = measure(middle, end); },
          [&] { sides.left = measure(begin, middle); });
    }

    const auto children = static_cast<std::uint32_t>(run_->nodes.size());
    run_->nodes[node].left_or_first = children;
    run_->nodes[node].count = 0u;
    run_->nodes.push_back(make_node(sides.left.bounds));
    run_->nodes.push_back(make_node(sides.right.bounds));
    if (forks_ && end - middle >= kForkMin) {
      return subdivide_pair_in_parallel(children, begin, middle, end, level + 1u, sides.left.centroids,
                                        sides.right.centroids);
    }
    subdivide(children, begin, middle, level + 1u, sides.left.centroids);
    subdivide(children + 1u, middle, end, level + 1u, sides.right.centroids);
  }

  void make_leaf(std::uint32_t node, std::uint32_t begin, std::uint32_t count) {
    run_->nodes[node].left_or_first = begin;
    run_->nodes[node].count = count;
    leaves_->write(begin, count, indices_ptr_ + begin);
  }

  // Exact SAH for a small node: on each axis, sort by centroid (insertion
  // sort; count <= kSmallNode) and sweep every split position. Coincident
  // centroids still split by position, so the split is always valid.
  Split find_small_split(std::uint32_t begin, std::uint32_t count) {
    const Record* r = &records_ptr_[begin];
    Split best;
    if (count == 2u) {  // the most common case has one candidate, in place
      best = Split{true, 0, 1, half_area(Box{r[0].lo, r[0].hi}) + half_area(Box{r[1].lo, r[1].hi})};
      small_order_[0][0] = 0;
      small_order_[0][1] = 1;
      return best;
    }
    for (int a = 0; a < 3; ++a) {
      std::uint8_t* order = small_order_[a];
      float key[kSmallNode];
      for (std::uint32_t i = 0; i < count; ++i) {
        const float k = r[i].lo[a] + r[i].hi[a];
        std::uint32_t j = i;
        for (; j > 0 && key[j - 1] > k; --j) {
          key[j] = key[j - 1];
          order[j] = order[j - 1];
        }
        key[j] = k;
        order[j] = static_cast<std::uint8_t>(i);
      }
      float right_area[kSmallNode];
      Box acc;
      for (std::uint32_t i = count - 1u; i > 0u; --i) {
        acc.grow(r[order[i]].lo, r[order[i]].hi);
        right_area[i] = half_area(acc);
      }
      acc = Box{};
      for (std::uint32_t left = 1; left < count; ++left) {
        acc.grow(r[order[left - 1u]].lo, r[order[left - 1u]].hi);
        const float cost =
            half_area(acc) * static_cast<float>(left) + right_area[left] * static_cast<float>(count - left);
        if (!best.valid || cost < best.cost) best = Split{true, a, static_cast<std::int32_t>(left), cost};
      }
    }
    return best;
  }

  // Reorders a small node by the winning axis's sort order.
  void apply_small_split(std::uint32_t begin, std::uint32_t count, const Split& split) {
    Record records[kSmallNode];
    std::uint32_t indices[kSmallNode];
    const std::uint8_t* order = small_order_[split.axis];
    for (std::uint32_t i = 0; i < count; ++i) {
      records[i] = records_ptr_[begin + order[i]];
      indices[i] = indices_ptr_[begin + order[i]];
    }
    std::copy_n(records, count, &records_ptr_[begin]);
    std::copy_n(indices, count, &indices_ptr_[begin]);
  }

  // Evaluates the bins - 1 planes of each axis with one pass over the
  // triangles and two sweeps over the bins.
  // With `concurrent`, the two halves of the pass run on two threads.
  Split find_split(std::uint32_t begin, std::uint32_t end, const Binning& binning, bool concurrent) {
    const std::uint32_t bins = binning.bins;
    if (concurrent) {
      const std::uint32_t mid = begin + (end - begin) / 2u;
      workers_->run_both([&] { bin_range(mid, end, binning, other_half_); },
                         [&] { bin_range(begin, mid, binning, bin_table_); });
      bin_table_.merge(other_half_, bins);
    } else {
      bin_range(begin, end, binning, bin_table_);
    }

    Split best;
    for (int a = 0; a < 3; ++a) {
      if (binning.scale[a] == 0.0f) continue;
      const Box* boxes = bin_table_.boxes[a].data();
      const std::uint32_t* counts = bin_table_.counts[a].data();
      // Right-to-left sweep: area and count of bins [b, bins). An empty
      // bin's box is empty, and growing by it changes nothing.
      Box acc;
      std::uint32_t n = 0;
      for (std::uint32_t b = bins - 1u; b > 0u; --b) {
        n += counts[b];
        acc.grow(boxes[b]);
        right_area_[b] = n > 0u ? half_area(acc) : 0.0f;
        right_count_[b] = n;
      }
      // Left-to-right sweep: the plane after bin b.
      acc = Box{};
      n = 0;
      for (std::uint32_t b = 0; b + 1u < bins; ++b) {
        n += counts[b];
        acc.grow(boxes[b]);
        if (n == 0u || right_count_[b + 1u] == 0u) continue;
        const float cost =
            half_area(acc) * static_cast<float>(n) + right_area_[b + 1u] * static_cast<float>(right_count_[b + 1u]);
        if (!best.valid || cost < best.cost) best = Split{true, a, static_cast<std::int32_t>(b), cost};
      }
    }
    return best;
  }

  // Bins records [begin, end) into `table`'s first binning.bins bins.
  void bin_range(std::uint32_t begin, std::uint32_t end, const Binning& binning, BinTable& table) const {
    table.reset(binning.bins);
    // Plain pointers: stores through them cannot move the vectors' own.
    Box* const boxes[3] = {table.boxes[0].data(), table.boxes[1].data(), table.boxes[2].data()};
    std::uint32_t* const counts[3] = {table.counts[0].data(), table.counts[1].data(), table.counts[2].data()};
    const Binning bins = binning;
    for (std::uint32_t i = begin; i < end; ++i) {
      const Record& r = records_ptr_[i];
      const Int4 b = bins.bin(r.lo + r.hi);
      for (int a = 0; a < 3; ++a) {
        const auto k = static_cast<std::uint32_t>(b[a]);
        boxes[a][k].grow(r.lo, r.hi);
        counts[a][k] += 1u;
      }
    }
  }

  // In-place partition by the chosen plane; returns the first right one and
  // adds each side's bounds to `sides`. With `halve`, the two halves of the
  // range are partitioned apart (on two threads when `concurrent`), then the
  // first half's right part and the second half's left part trade places,
  // which a whole-range partition does not need. The caller halves the root
  // only, by its size, on one thread or two alike, so that the tree is the
  // same for every thread count.
  std::uint32_t partition(std::uint32_t begin, std::uint32_t end, const Binning& binning, const Split& split,
                          bool halve, bool concurrent, Sides& sides) {
    if (!halve) return partition_range(begin, end, binning, split, sides);
    const std::uint32_t mid = begin + (end - begin) / 2u;
    std::uint32_t first_right = 0, second_right = 0;
    Sides second;
    run_both(
        *workers_, concurrent, [&] { second_right = partition_range(mid, end, binning, split, second); },
        [&] { first_right = partition_range(begin, mid, binning, split, sides); });
    sides.add(second);
    // [begin, first_right) left, [first_right, mid) right, [mid,
    // second_right) left, [second_right, end) right: swap the shorter of the
    // two middle runs with the far end of the other, half of it on each
    // thread.
    const std::uint32_t swapped = std::min(mid - first_right, second_right - mid);
    auto swap_part = [&](std::uint32_t from, std::uint32_t to) {
      std::swap_ranges(records_ptr_ + first_right + from, records_ptr_ + first_right + to,
                       records_ptr_ + second_right - swapped + from);
      std::swap_ranges(indices_ptr_ + first_right + from, indices_ptr_ + first_right + to,
                       indices_ptr_ + second_right - swapped + from);
    };
    run_both(
        *workers_, concurrent, [&] { swap_part(swapped / 2u, swapped); }, [&] { swap_part(0u, swapped / 2u); });
    return first_right + (second_right - mid);
  }

  // Hoare's partition, which moves only the records on the wrong side, each
  // once, and measures each side's bounds on the way (the children's boxes
  // and their binnings need them), so that no second pass reads them.
  std::uint32_t partition_range(std::uint32_t begin, std::uint32_t end, const Binning& binning, const Split& split,
                                Sides& sides) {
    Sides s = sides;  // in locals: boxes behind a reference stay in memory
    auto is_left = [&](const Record& r) { return binning.bin(r.lo + r.hi)[split.axis] <= split.last_left; };
    std::uint32_t i = begin, j = end;  // [begin, i) left, [j, end) right
    for (;;) {
      while (i < j && is_left(records_ptr_[i])) s.left.add(records_ptr_[i++]);
      while (i < j && !is_left(records_ptr_[j - 1u])) s.right.add(records_ptr_[--j]);
      if (i >= j) break;
      // records i (right) and j - 1 (left) trade places.
      --j;
      std::swap(records_ptr_[i], records_ptr_[j]);
      std::swap(indices_ptr_[i], indices_ptr_[j]);
      s.left.add(records_ptr_[i++]);
      s.right.add(records_ptr_[j]);
    }
    sides = s;
    return i;
  }

  NodeRun* run_;  // the whole tree's, or a subtree's on a worker thread
  BuildWorkers* workers_;
  const LeafWriter* leaves_;
  std::uint32_t depth_ = 0;
  std::uint32_t bins_ = 16;
  std::uint32_t max_leaf_size_ = 4;
  std::uint32_t max_depth_ = SP_BVH_MAX_DEPTH;
  float traversal_cost_ = 1.0f;
  bool forks_ = false;          // whether subtrees go to other threads
  LargeArray<Record> records_;  // owned by the top-level builder only
  LargeArray<std::uint32_t> indices_;
  Record* records_ptr_ = nullptr;  // records_ of the top-level builder
  std::uint32_t* indices_ptr_ = nullptr;
  BinTable bin_table_;
  BinTable other_half_;  // the second half's bins of a pass split in two
  std::vector<float> right_area_;
  std::vector<std::uint32_t> right_count_;
  std::uint8_t small_order_[3][kSmallNode] = {};  // per axis, from find_small_split
};

}  // namespace

namespace {
std::atomic<std::uint64_t> g_builds{0};
}  // namespace

std::uint64_t bvh_builds() { return g_builds.load(); }

Bvh build_bvh(std::span<const glm::vec3> vertices, std::span<const std::uint32_t> layers,
              std::span<const std::uint32_t> solids, const BvhBuildSettings& settings) {
  g_builds.fetch_add(1);
  const auto start = std::chrono::steady_clock::now();
  // Never read past either array (documented in bvh.h: the shorter wins).
  const auto count = static_cast<std::uint32_t>(std::min(vertices.size() / 3u, layers.size()));
  Bvh bvh;
  if (count == 0u) return bvh;

  // Threads only for a build that forks (Builder::parallel), and no more
  // than it has subtrees to hand out.
  const unsigned threads = settings.threads != 0u ? settings.threads : std::thread::hardware_concurrency();
  BuildWorkers workers(count >= kParallelMin ? std::clamp(threads, 1u, kMaxThreads) : 1u);
  // resize() leaves the elements to be written by the build's leaves
  // (large_array.h).
  bvh.triangles.resize(count);
  const LeafWriter leaves{vertices, layers, solids, bvh.triangles.data()};
  NodeRun nodes;
  Builder builder(vertices, count, settings, workers, leaves, nodes);
  builder.build();
  bvh.nodes = assemble_node_runs(nodes, workers);
  bvh.depth = builder.depth();
  // The CPU backend's wide copies (wide_bvh.h, wide_collapse.cpp).
  bvh.wide = std::make_shared<const WideBvh>(build_wide_bvh(bvh, builder.concurrent_pass(count) ? &workers : nullptr));
  bvh.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace sp
