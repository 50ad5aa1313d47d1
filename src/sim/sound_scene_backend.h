// The part of a SoundScene only the backends use: planning a step and
// moving pending instance transforms into the BVH. Kept off the public
// class so that a host cannot race the CPU backend's worker with them.
#pragma once

#include <cstdint>

#include "bvh/bvh.h"
#include "sim/step_plan.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

struct SoundSceneBackend {
  static void plan(SoundScene& scene, std::uint64_t step, StepPlan& out) { scene.plan(step, out); }
  static BvhChanges update_geometry(SoundScene& scene) { return scene.update_geometry(); }
};

}  // namespace sp::detail
