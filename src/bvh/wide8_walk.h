// The 8-wide tree (WideNode8) and its walk, for x86-64 CPUs with AVX-512:
// internal to the bvh module, called by wide_bvh.cpp's build and dispatch.
#pragma once

#include <cstdint>
#include <span>

#include "bvh/wide_bvh.h"

namespace sp::wide8 {

// Whether this build has the 8-wide walk and this CPU runs it.
bool cpu_runs();

// Collapses `bvh` three binary levels per node into wide.nodes8 and sets
// wide.depth8. `leaf_packets[n]` is the first packet of binary leaf n in
// wide.packets; `nodes` is how many 8-wide nodes that makes (one per binary
// interior node at a depth divisible by three). Precondition: cpu_runs().
void collapse(const Bvh& bvh, std::span<const std::uint32_t> leaf_packets, std::uint32_t nodes, WideBvh& wide);

// wide_closest_hit and wide_nearest_hits on wide.nodes8 (not empty).
HitInfo closest_hit(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);
shader::HitList nearest_hits(const WideBvh& wide, const Bvh& bvh, glm::vec3 origin, glm::vec3 dir, float tmin,
                             float tmax);
// wide_segment_blocked on wide.nodes8 (not empty).
bool segment_blocked(const WideBvh& wide, glm::vec3 origin, glm::vec3 dir, float tmin, float tmax);

}  // namespace sp::wide8
