// Traces single rays placed by hand through hand-built geometry with the CPU
// backend's tracer, for tests whose expectations are derived by hand.
#pragma once

#include <vector>

#include <glm/geometric.hpp>

#include "sim/cpu_tracer.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "sp_ray_model.h"

namespace sp::test {

// A world around `scene` and `config`; one layer table entry per layer and
// one source (E0 = 1, intensity 0.5, range 100 m) that rays belong to.
struct SingleRay {
  Scene scene;
  Config config;
  World world;
  std::vector<shader::LayerAcoustics> layers;
  std::vector<shader::StepSource> sources;

  // Builds the world; call after filling scene and config.
  void finish() {
    if (!config.listener_position) config.listener_position = glm::vec3(0.0f);
    world = make_world(scene, config).value();
    layers = make_layer_table(world);
    shader::StepSource s{};
    s.position = glm::vec3(0.0f);
    s.max_distance = 100.0f;
    s.loudness = 1.0f;
    s.color = {1, 0, 0};
    s.intensity = 0.5f;
    sources = {s};
  }

  // Traces one ray from `origin` along `dir` (normalised here).
  std::vector<shader::Indicator> trace(glm::vec3 origin, glm::vec3 dir, TraceCounters& counters) {
    TraceContext context{&world.geometry->bvh, layers, sources, make_sim_params(config, 0, world.listener)};
    shader::RayState ray = shader::sp_emit_ray(sources[0], 0, 0, glm::normalize(dir), 0u);
    ray.origin = origin;
    ray.dir = glm::normalize(dir);
    counters.layers.assign(world.layer_names.size(), {});
    DefaultInitVector<shader::Indicator> out;
    trace_ray(context, ray, out, counters);
    return {out.begin(), out.end()};
  }
  std::vector<shader::Indicator> trace(glm::vec3 origin, glm::vec3 dir) {
    TraceCounters counters;
    return trace(origin, dir, counters);
  }
};

}  // namespace sp::test
