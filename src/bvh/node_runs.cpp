#include "bvh/node_runs.h"

#include <algorithm>
#include <cassert>

#include "bvh/build_workers.h"

namespace sp {

void NodeRun::insert_at_end(std::uint32_t right, std::unique_ptr<NodeRun> run) {
  assert(run != nullptr && !run->nodes.empty() && right < nodes.size());
  inserts.push_back(Insert{static_cast<std::uint32_t>(nodes.size()), right, std::move(run)});
}

void NodeRun::finish() {
  total = nodes.size();
  // An insert's first node replaces a placeholder, so adds no position.
  for (const Insert& insert : inserts) total += insert.run->total - 1u;
}

namespace {

// Where one run's nodes go: its node i (from `skip` on; an insert's first
// node goes to its parent's placeholder) lands at
// base + (i - skip) + the nodes of the inserts placed before node i.
struct RunPlace {
  const NodeRun* run = nullptr;
  std::size_t base = 0;
  std::uint32_t skip = 0;
  std::vector<std::size_t> inserted_before;  // per insert: the inserted nodes up to and including it
  std::vector<std::size_t> insert_places;    // per insert: its RunPlace

  std::size_t position(std::uint32_t i) const {
    const auto& inserts = run->inserts;
    // Inserts placed before node i: those at i or before.
    const auto after = std::upper_bound(inserts.begin(), inserts.end(), i,
                                        [](std::uint32_t index, const NodeRun::Insert& in) { return index < in.at; });
    const auto k = static_cast<std::size_t>(after - inserts.begin());
    return base + (i - skip) + (k > 0u ? inserted_before[k - 1u] : 0u);
  }
  // Node i of this run as placed: an interior node's children made global.
  BvhNode placed(std::uint32_t i) const {
    BvhNode node = run->nodes[i];
    if (node.count == 0u) node.left_or_first = static_cast<std::uint32_t>(position(node.left_or_first));
    return node;
  }
};

// Lays out `run` and, depth first, its inserts.
void lay_out(const NodeRun& run, std::size_t base, std::uint32_t skip, std::vector<RunPlace>& places) {
  const std::size_t index = places.size();
  places.push_back(RunPlace{&run, base, skip, {}, {}});
  std::size_t inserted = 0;
  for (const NodeRun::Insert& insert : run.inserts) {
    places[index].insert_places.push_back(places.size());
    lay_out(*insert.run, base + (insert.at - skip) + inserted, 1u, places);
    inserted += insert.run->total - 1u;
    places[index].inserted_before.push_back(inserted);
  }
}

// A part of one run's nodes to copy.
struct CopyJob {
  const RunPlace* place;
  std::uint32_t first, last;
};

// A run's placeholders (each insert's `right`) are copied too, with a child
// index that means nothing; assemble_node_runs overwrites them afterwards.
void copy_jobs(const CopyJob* jobs, std::size_t count, BvhNode* out, BuildWorkers& workers) {
  if (count == 0u) return;
  if (count == 1u) {
    const RunPlace& place = *jobs->place;
    for (std::uint32_t i = jobs->first; i < jobs->last; ++i) out[place.position(i)] = place.placed(i);
    return;
  }
  const std::size_t half = count / 2u;
  workers.run_both([&] { copy_jobs(jobs + half, count - half, out, workers); },
                   [&] { copy_jobs(jobs, half, out, workers); });
}

}  // namespace

LargeArray<BvhNode> assemble_node_runs(NodeRun& root, BuildWorkers& workers) {
  if (root.inserts.empty()) return std::move(root.nodes);
  std::vector<RunPlace> places;
  lay_out(root, 0u, 0u, places);
  // Parts of at most this many nodes (1 MiB), so that the threads share
  // the copying evenly.
  constexpr std::uint32_t kJobNodes = 32768;
  std::vector<CopyJob> jobs;
  for (const RunPlace& place : places) {
    const auto size = static_cast<std::uint32_t>(place.run->nodes.size());
    for (std::uint32_t first = place.skip; first < size; first += kJobNodes)
      jobs.push_back(CopyJob{&place, first, std::min(size, first + kJobNodes)});
  }
  LargeArray<BvhNode> out(root.total);
  copy_jobs(jobs.data(), jobs.size(), out.data(), workers);
  // Each insert's root over its placeholder, which the copies above wrote.
  for (const RunPlace& place : places) {
    for (std::size_t k = 0; k < place.run->inserts.size(); ++k) {
      const RunPlace& inserted = places[place.insert_places[k]];
      out[place.position(place.run->inserts[k].right)] = inserted.placed(0u);
    }
  }
  return out;
}

}  // namespace sp
