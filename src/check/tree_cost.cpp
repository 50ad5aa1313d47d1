#include "check/tree_cost.h"

#include <cmath>
#include <cstdio>

#include "sp_types.h"

namespace sp {

double degenerate_tree_cost() { return 4.0 * double(SP_MAX_CAST_PACKETS); }

bool is_degenerate_tree(double sah_cost) { return sah_cost >= degenerate_tree_cost(); }

std::string degenerate_tree_advice() {
  return "triangles lie on top of one another or their boxes all overlap (duplicated meshes, long thin slivers), "
         "so no bounding box separates them and casts through them end at the per-cast work bound. Remove "
         "duplicated geometry (merge by distance) and split long thin triangles.";
}

void add_work_findings(const Bvh& bvh, std::uint64_t edges_left_out, const PenetrationProbe& probe,
                       std::vector<CheckFinding>& findings) {
  const double sah = bvh_sah_cost(bvh);
  if (is_degenerate_tree(sah)) {
    char cost[64];
    std::snprintf(cost, sizeof cost, "%.0f", sah);
    findings.push_back({"degenerate_bvh",
                        static_cast<std::uint64_t>(std::llround(std::min(sah, 9.0e15))),
                        std::string("the level's BVH costs ") + cost + " tests per ray through it (OpenArena levels " +
                            "cost about 100; " + std::to_string(bvh.triangle_count()) +
                            " triangles): " + degenerate_tree_advice(),
                        {}});
  }
  if (probe.casts_cut_short > 0)
    findings.push_back({"casts_cut_short",
                        probe.casts_cut_short,
                        std::to_string(probe.casts_cut_short) +
                            " probe casts reached the per-cast work bound and ended there, so the sound they carried "
                            "stopped short: the same stacked or overlapping triangles. A simulation counts them as "
                            "casts_cut_short in its stats.",
                        {}});
  if (edges_left_out > 0)
    findings.push_back({"edges_left_out",
                        edges_left_out,
                        std::to_string(edges_left_out) +
                            " edges were left out of diffraction: deciding whether another surface buries them "
                            "reached its work bound among overlapping triangles.",
                        {}});
}

}  // namespace sp
