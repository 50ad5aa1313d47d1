// The probe behind `soundpaint check` and the warnings of `info` and
// `simulate`: a short CPU simulation that asks, layer by layer, whether a
// ray that penetrates a surface finds a way out of matter at all.
#include <algorithm>
#include <cstdio>
#include <limits>

#include <glm/glm.hpp>

#include "check/penetration_probe.h"

#include "soundpaint/check.h"
#include "sim/world_builder.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {

// Probe sources reach this far (metres): across any room, not across a level.
constexpr float kProbeRange = 200.0f;
// The probe reads counters, never indicators: a small ring of its own, so
// that the config's max_indicators (up to 2^24, gigabytes) costs the probe
// nothing and cannot push it over a memory budget. check_scene reports the
// config's own needs against the user's budget instead (memory_budget).
constexpr std::uint32_t kProbeMaxIndicators = 1024;

glm::vec3 bounds_centre(const Scene& scene) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3 v : scene.vertices) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  return lo * 0.5f + hi * 0.5f;  // lo + hi would overflow in a level reaching past +-1.7e38
}

// Where the probe's rays start: the sources, else the listener, else the
// middle of the level.
std::vector<glm::vec3> probe_origins(const Scene& scene, const Config& config) {
  std::vector<glm::vec3> origins;
  for (const SourceDesc& s : scene.sources) origins.push_back(s.position);
  for (const SourceDesc& s : config.sources) origins.push_back(s.position);
  if (origins.empty() && config.listener_position) origins.push_back(*config.listener_position);
  if (origins.empty() && scene.camera) origins.push_back(scene.camera->position());
  if (origins.empty()) origins.push_back(bounds_centre(scene));
  return origins;
}

// The config as the probe runs it: the geometry and the layers' sheets
// as given, acoustics chosen so that every layer is penetrated often and
// energy never ends a ray before it has found its way out, rays and
// indicators counted by the probe's settings, not the config's.
Config probe_config(const Scene& scene, const Config& config, const CheckSettings& settings) {
  Config probe = config;
  probe.ray_budget = settings.probe_rays_per_step;
  probe.max_indicators = kProbeMaxIndicators;
  probe.max_wall_thickness = std::max(config.max_wall_thickness, settings.probe_reach);
  probe.max_bounces = 8;
  probe.min_energy = 0.001f;
  probe.air_attenuation = 0.0f;
  probe.bounce_energy_loss = 0.0f;
  probe.scan_radius = 2.0f * kProbeRange;
  probe.budget_weighting = BudgetWeighting::Even;
  // The probe counts penetrations: rays go out uniformly, and no spot is
  // cast to a listener.
  probe.cues.listen = false;
  probe.cues.guide_share = 0.0f;
  probe.sources.clear();
  for (const std::string& name : scene.layer_names) {
    LayerProperties layer = resolve_layer(config, name);
    layer.reflect_probability = 0.5f;
    layer.attenuation = 0.0f;
    probe.layers[name] = layer;
  }
  return probe;
}

}  // namespace

namespace detail {

PenetrationProbe probe_penetration_on(const Scene& scene, const Config& config, const CheckSettings& settings,
                                      const WorldGeometryHandle& geometry) {
  Scene probe_scene;
  probe_scene.path = scene.path;
  probe_scene.triangle_layers = scene.triangle_layers;
  probe_scene.layer_names = scene.layer_names;
  const std::vector<glm::vec3> origins = probe_origins(scene, config);
  for (const glm::vec3& at : origins) {
    SourceDesc source;
    source.position = at;
    source.max_distance = kProbeRange;
    probe_scene.sources.push_back(source);
  }
  Config probe = probe_config(scene, config, settings);
  probe.listener_position = origins.front();
  // Sources out of the listener's scan radius would stay silent: one
  // listener cannot be near all of them, so each gets a turn.
  PenetrationProbe result;
  result.layer_penetrations.assign(scene.layer_names.size(), 0);
  result.layer_no_way_out.assign(scene.layer_names.size(), 0);
  // The level as the command built it, copied: the probe's own acoustics
  // change the layers, never the geometry.
  World world = make_world_around(probe_scene, probe, geometry);
  std::vector<bool> sheet(world.layer_properties.size());
  for (std::size_t l = 0; l < sheet.size(); ++l) sheet[l] = world.layer_properties[l].sheet_thickness > 0.0f;
  auto simulator = create_cpu_simulator(std::move(world), CpuSettings{settings.threads}).value();
  const std::uint32_t steps = std::max<std::uint32_t>(settings.probe_steps, 1u);
  for (std::uint32_t n = 0; n < steps; ++n) {
    simulator->set_listener(origins[n % origins.size()]).value();
    simulator->step().value();
  }
  const SimulationStats stats = simulator->stats().value();
  result.casts_cut_short = stats.casts_cut_short;
  for (std::size_t l = 0; l < stats.layers.size() && l < sheet.size(); ++l) {
    const LayerCounters& c = stats.layers[l];
    result.hits += c.hits;
    result.back_face_hits += c.back_face_hits;
    if (sheet[l]) continue;  // sheets are crossed on the spot, never searched
    result.layer_penetrations[l] = c.penetrations;
    result.layer_no_way_out[l] = c.no_way_out;
    result.penetrations += c.penetrations;
    result.no_way_out += c.no_way_out;
  }
  return result;
}

}  // namespace detail

Result<PenetrationProbe> probe_penetration(const Scene& scene, const Config& config, const CheckSettings& settings) {
  return capture_errors(
      [&]() -> PenetrationProbe {
        return detail::probe_penetration_on(scene, config, settings,
                                            detail::build_world_geometry(scene, BvhBuildSettings{}, nullptr));
      },
      ErrorCode::InvalidScene);
}

Result<PenetrationProbe> probe_penetration(const Scene& scene, const Config& config, const CheckSettings& settings,
                                           const WorldGeometryHandle& geometry) {
  return capture_errors([&] { return detail::probe_penetration_on(scene, config, settings, geometry); },
                        ErrorCode::InvalidScene);
}

std::string work_bound_warning(const PenetrationProbe& probe) {
  if (probe.casts_cut_short == 0) return {};
  return std::to_string(probe.casts_cut_short) +
         " probe casts reached the per-cast work bound and ended there: the level stacks coincident or overlapping "
         "triangles that no bounding box can separate, so sound through them is cut short; 'soundpaint check' "
         "says more";
}

std::string penetration_warning(const PenetrationProbe& probe) {
  // "Mostly fails": more than half (the level of check's wall_thickness).
  if (probe.penetrations == 0 || probe.miss_share() <= 0.5) return {};
  char line[256];
  std::snprintf(line, sizeof line,
                "%.0f%% of probe penetrations find no way out of matter, so little sound passes through "
                "walls; run 'soundpaint check' for why",
                100.0 * probe.miss_share());
  return line;
}

}  // namespace sp
