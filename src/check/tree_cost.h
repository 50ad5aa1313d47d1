// Whether a level's BVH is degenerate: triangles stacked so that no box
// separates them (coincident copies, slivers whose boxes all overlap), which
// `info` and `check` name with what to fix (docs/model.md#work-bounds).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "soundpaint/check.h"

namespace sp {

// The tree's SAH cost (bvh_sah_cost: triangle tests and node visits a ray
// through the level's box expects) from which it is degenerate: what one
// cast may test (SP_MAX_CAST_PACKETS packets of four), so that casts on such
// a level are cut short. OpenArena levels cost 90 to 160; 10,000 copies of
// one quad cost 21,000.
double degenerate_tree_cost();

bool is_degenerate_tree(double sah_cost);

// One sentence: what makes a tree degenerate, and what to do about it.
std::string degenerate_tree_advice();

// check's findings on what the level costs to trace: degenerate_bvh (count:
// the SAH cost, rounded), casts_cut_short (the probe's casts that reached
// the per-cast bound) and edges_left_out (edges whose burial test reached
// its bound; only found with diffraction on).
void add_work_findings(const Bvh& bvh, std::uint64_t edges_left_out, const PenetrationProbe& probe,
                       std::vector<CheckFinding>& findings);

}  // namespace sp
