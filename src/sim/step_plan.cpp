#include "core/glm_interop.h"
#include "sim/step_loudness.h"
#include "sim/step_plan.h"
#include "sp_types.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <glm/geometric.hpp>

namespace sp {

bool source_pattern_plays(const SourceDesc& source, double t) {
  if (t < source.phase) return false;
  return std::fmod(t - source.phase, source.interval) < source.duration;
}

std::vector<std::uint32_t> split_budget(std::uint32_t budget, const std::vector<double>& weights) {
  std::vector<std::uint32_t> counts(weights.size(), 0);
  if (weights.empty()) return counts;
  double total = 0.0;
  for (double w : weights) total += w;
  std::uint64_t assigned = 0;
  if (total > 0.0) {
    for (std::size_t i = 0; i < weights.size(); ++i) {
      double share = std::floor(static_cast<double>(budget) * weights[i] / total);
      counts[i] = static_cast<std::uint32_t>(std::min(share, static_cast<double>(budget)));
      assigned += counts[i];
    }
  } else {
    for (auto& c : counts) c = budget / static_cast<std::uint32_t>(weights.size());
    assigned = static_cast<std::uint64_t>(counts[0]) * weights.size();
  }
  // Rounding of budget * w / total can push a floor one over; take it back
  // from the highest indices so the split never exceeds the budget.
  for (std::size_t i = counts.size(); assigned > budget && i-- > 0;) {
    if (counts[i] > 0) {
      counts[i] -= 1;
      assigned -= 1;
      i += 1;
    }
  }
  // Floors lose less than one ray per source, so one pass over the lowest
  // indices always places the whole remainder.
  std::uint64_t remainder = budget > assigned ? budget - assigned : 0;
  for (std::size_t i = 0; remainder > 0; i = (i + 1) % counts.size(), --remainder) counts[i] += 1;
  return counts;
}

StepPlan plan_step(const World& world, std::uint64_t step, glm::vec3 listener,
                   const std::vector<PlayWindow>& play_windows) {
  const Config& config = world.config;
  const double t = static_cast<double>(step) * config.dt;
  StepPlan plan;
  plan.listener = listener;
  std::vector<double> weights;
  for (std::uint32_t id = 0; id < world.sources.size(); ++id) {
    const SourceDesc& source = world.sources[id];
    if (!world.source_active[id]) continue;
    const PlayWindow& window = play_windows[id];
    const bool in_window = t >= window.start && t < window.end;
    bool playing = source_pattern_plays(source, t) || in_window;
    if (!playing) continue;
    double d_ls = static_cast<double>(glm::distance(listener, to_glm(source.position)));
    if (d_ls > config.scan_radius || d_ls > source.max_distance) continue;
    const StepLoudness loudness = step_loudness(source, window, in_window, t, config);
    if (!loudness.emits) continue;  // below the signal's floor: silence paints nothing
    double proximity = source.max_distance > 0.0f ? std::max(0.0, 1.0 - d_ls / source.max_distance) : 0.0;

    shader::StepSource entry{};
    entry.position = source.position;
    entry.max_distance = source.max_distance;
    entry.color = world.source_colors[id];
    entry.loudness = loudness.energy;
    entry.intensity = static_cast<float>(proximity);
    entry.source_id = id;
    plan.sources.push_back(entry);
    // Rays follow energy: a source's share is weighted by its level's gain
    // (1 without a signal, so runs without signals split as before).
    const double weight = config.budget_weighting == BudgetWeighting::Proximity ? proximity : 1.0;
    weights.push_back(loudness.share == 1.0 ? weight : weight * loudness.share);
  }
  std::vector<std::uint32_t> counts = split_budget(config.ray_budget, weights);
  for (std::size_t i = 0; i < plan.sources.size(); ++i) {
    plan.sources[i].first_ray = plan.total_rays;
    plan.sources[i].ray_count = counts[i];
    plan.total_rays += counts[i];
  }
  return plan;
}

shader::SimParams make_sim_params(const Config& config, std::uint64_t step, glm::vec3 listener) {
  shader::SimParams p{};
  p.min_energy = config.min_energy;
  p.air_attenuation = config.air_attenuation;
  p.bounce_energy_loss = config.bounce_energy_loss;
  p.max_wall_thickness = config.max_wall_thickness;
  p.indicator_size = config.indicator_size;
  p.max_bounces = config.max_bounces;
  p.seed = config.seed;
  // The RNG key is 32-bit; steps beyond 2^32 (two years at 60 Hz) wrap.
  p.step = static_cast<std::uint32_t>(step);
  const DiffractionSettings& d = config.diffraction;
  if (d.enabled) {
    // Computed here once, so both backends read the same floats.
    p.diffraction = 1u;
    p.edge_cos_max = diffraction_edge_cos_max(d);
    p.diffraction_reach = diffraction_reach(d);
    // sigma(a) = 1 / (2 k a), k = 2 pi f / c: the width is c / (4 pi f).
    p.diffraction_width = static_cast<float>(double(kSpeedOfSound) / (4.0 * std::numbers::pi * double(d.frequency)));
    p.diffraction_gain = d.gain;
  }
  const CueSettings& cues = config.cues;
  p.cues = (cues.listen ? SP_CUES_LISTEN : 0u) | (cues.listen && cues.guide_share > 0.0f ? SP_CUES_GUIDE : 0u);
  p.toward_cos = static_cast<float>(std::cos(double(cues.toward_angle) * std::numbers::pi / 180.0));
  p.guide_share = cues.guide_share;
  p.listener = listener;
  return p;
}

float diffraction_edge_cos_max(const DiffractionSettings& diffraction) {
  return static_cast<float>(std::cos(double(diffraction.edge_angle) * std::numbers::pi / 180.0));
}

std::vector<shader::LayerAcoustics> make_layer_table(const World& world) {
  return make_layer_table(world.layer_properties);
}

std::vector<shader::LayerAcoustics> make_layer_table(const std::vector<LayerProperties>& layer_properties) {
  std::vector<shader::LayerAcoustics> table;
  for (const LayerProperties& props : layer_properties)
    table.push_back({props.reflect_probability, props.attenuation, props.sheet_thickness, 0u});
  return table;
}

}  // namespace sp
