// The CPU backend's cast to the nearest surface through Embree, for
// cpu_traversal = "embree" (include/soundpaint/config.h). Built with
// -DSOUNDPAINT_EMBREE=ON; elsewhere constructing one is a configuration
// error. Embree stays optional: soundpaint's own traversal is the default
// and the reference the GPU backend is tested against.
#pragma once

#include <memory>

#include <glm/vec3.hpp>

#include "bvh/bvh.h"
#include "soundpaint/config.h"

namespace sp {

class EmbreeTraversal {
 public:
  // An Embree scene over `bvh`'s triangles, read in place (`bvh` must
  // outlive this): primitive i is bvh.triangles[i], so hits name triangles
  // as soundpaint's traversal does. Embree's own build threads are limited
  // to `threads` (0: all cores). Throws sp::Exception.
  EmbreeTraversal(const Bvh& bvh, unsigned threads);
  ~EmbreeTraversal();
  EmbreeTraversal(const EmbreeTraversal&) = delete;
  EmbreeTraversal& operator=(const EmbreeTraversal&) = delete;

  // After SoundScene::update_geometry changed the BVH by `changes`: builds
  // the scene again when any triangle moved (or the BVH was rebuilt). No
  // closest_hit() may run meanwhile.
  void update(const BvhChanges& changes);

  // The nearest hit in (tmin, tmax] as closest_hit() gives it, up to float
  // rounding: t, and the index into bvh.triangles (SP_INVALID and tmax when
  // nothing is hit). Thread-safe.
  HitInfo closest_hit(glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) const;

 private:
  struct Impl;
  static std::unique_ptr<Impl> build(const Bvh& bvh, unsigned threads);

  const Bvh* bvh_;
  unsigned threads_;
  std::unique_ptr<Impl> impl_;
};

// The Embree traversal `config` asks for over `bvh`, or null when it asks
// for soundpaint's own (the default).
std::unique_ptr<EmbreeTraversal> make_cpu_traversal(const Config& config, const Bvh& bvh, unsigned threads);

}  // namespace sp
