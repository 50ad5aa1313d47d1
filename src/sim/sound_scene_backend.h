// The part of a SoundScene only the backends use: planning a step, moving
// pending instance transforms into the BVH and taking a new config. Kept
// off the public class so that a host cannot race the CPU backend's worker
// with them.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bvh/bvh.h"
#include "sim/step_plan.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

struct SoundSceneBackend {
  static void plan(SoundScene& scene, std::uint64_t step, StepPlan& out) { scene.plan(step, out); }
  static BvhChanges update_geometry(SoundScene& scene) { return scene.update_geometry(); }
  static void apply_config(SoundScene& scene, Config config, std::vector<LayerProperties> layer_properties) {
    scene.apply_config(std::move(config), std::move(layer_properties));
  }
  // For a caller that serialises its render-thread calls itself (the C
  // API's one-thread-at-a-time guard): the thread now inside becomes the
  // thread that steps, so the debug thread check follows a host that moves
  // those calls from thread to thread between them, as the C API allows.
  static void hand_over_to_calling_thread(SoundScene& scene) { scene.note_stepping_thread(); }
};

}  // namespace sp::detail
