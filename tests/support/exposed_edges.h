// Reading the exposed-edge table of a level (docs/model.md#edges) by hand-
// derived brush and edge: which brush's edges diffract, and whether the
// edge with a given midpoint does.
#pragma once

#include <bit>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bvh/bvh.h"
#include "sim/world_geometry.h"
#include "soundpaint/config.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"

namespace sp::test {

// The table as a level gets it: make_world numbers the solids by the
// mesh's shared edges (a bare build_bvh makes each triangle a solid of its
// own).
inline World level_world(const Scene& scene) {
  Config config;
  config.listener_position = glm::vec3(0.0f);
  config.diffraction.enabled = true;
  return make_world(scene, config).value();
}

// Exposed bits of brush `brush`: scene triangles 12 brush to 12 brush + 11,
// as add_box appends them.
inline int brush_bits(const Bvh& bvh, std::uint32_t brush) {
  int n = 0;
  for (std::size_t t = 0; t < bvh.triangles.size(); ++t)
    if (bvh.triangles[t].scene_index / 12u == brush) n += std::popcount(bvh.edges[t].exposed);
  return n;
}

// Exposed bits whose edge has its midpoint at `mid`: 2 for an exposed edge
// of a closed solid (one from each of its faces), 0 for a buried one.
inline int bits_at(const Bvh& bvh, glm::vec3 mid) {
  int n = 0;
  for (std::size_t t = 0; t < bvh.triangles.size(); ++t) {
    const BvhTriangle& tri = bvh.triangles[t];
    const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
    for (int i = 0; i < 3; ++i)
      n += ((bvh.edges[t].exposed >> i) & 1u) && glm::distance(0.5f * (v[i] + v[(i + 1) % 3]), mid) < 1e-4f;
  }
  return n;
}

}  // namespace sp::test
