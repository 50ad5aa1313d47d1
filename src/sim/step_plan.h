// Source registry and ray distribution (docs/model.md#registry,
// docs/model.md#distribution): which sources emit in a step and how many rays
// each gets. Both backends use this same table.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "bvh/bvh.h"
#include "soundpaint/simulation.h"

namespace sp {

struct StepPlan {
  std::vector<shader::StepSource> sources;  // active sources, ascending id
  std::uint32_t total_rays = 0;             // sum of ray_count
  glm::vec3 listener{0.0f};                 // where the step's sound is heard
};

// Is the source playing at time t by its emission pattern?
bool source_pattern_plays(const SourceDesc& source, double t);

// Playing sources of step `step` (time step * dt) within reach of the
// listener, and their ray counts. Removed sources (World::source_active)
// never play. `play_windows` has one entry per source (end <= start: none).
StepPlan plan_step(const World& world, std::uint64_t step, glm::vec3 listener,
                   const std::vector<PlayWindow>& play_windows);

// Splits `budget` rays by weight: floor of the proportional share, then the
// remainder one each to the lowest indices. All weights zero: even split.
std::vector<std::uint32_t> split_budget(std::uint32_t budget, const std::vector<double>& weights);

// The ray model's parameters for one step, heard at `listener`.
shader::SimParams make_sim_params(const Config& config, std::uint64_t step, glm::vec3 listener);

// cos of diffraction.edge_angle: an edge whose faces turn by at least the
// angle has turn_cos <= this. One computation for the backends and `info`.
float diffraction_edge_cos_max(const DiffractionSettings& diffraction);

// Per layer id, the acoustics table the ray model reads.
std::vector<shader::LayerAcoustics> make_layer_table(const World& world);
// The same from the layers' properties (a config not yet applied).
std::vector<shader::LayerAcoustics> make_layer_table(const std::vector<LayerProperties>& layer_properties);

}  // namespace sp
