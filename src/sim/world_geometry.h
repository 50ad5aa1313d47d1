// What a World holds behind its opaque WorldGeometryHandle: the BVH the
// backends trace and, for scenes with moving parts, what refitting and
// rebuilding it needs.
#pragma once

#include <cstdint>
#include <mutex>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "soundpaint/math.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

struct WorldGeometry {
  WorldGeometry() = default;
  // A copy for a scene whose moving parts move (WorldGeometryHandle::mutate).
  WorldGeometry(const WorldGeometry& other);
  WorldGeometry& operator=(const WorldGeometry&) = delete;

  Bvh bvh;
  // Moving parts only (empty when the scene has none):
  std::vector<glm::vec3> rest_vertices;           // scene's vertices, 3 per triangle
  std::vector<std::uint32_t> triangle_instances;  // per triangle, or kStaticInstance
  std::vector<std::uint32_t> triangle_layers;     // per triangle (scene order), for rebuilds
  std::vector<std::uint32_t> triangle_solids;     // per triangle (scene order), for rebuilds
  // Edges whose burial query reached its work bound and were left out
  // (find_exposed_edges; docs/model.md#work-bounds), at the last build.
  std::uint64_t edges_left_out = 0;
  double build_sah_cost = 0.0;  // the BVH's absolute SAH cost after its last build (set by SoundScene)

  // Fills bvh.edges (and edges_left_out) the first time a world with
  // diffraction on asks, for every holder of this geometry at once; a
  // world without diffraction never reads them. Safe from several threads.
  void ensure_exposed_edges() const;

 private:
  mutable std::mutex edges_mutex_;
  mutable bool edges_found_ = false;
};

}  // namespace sp::detail
