// sp::check_scene: the findings of `soundpaint check`, from the mesh's
// topology, its bounds, the penetration probe and the config's memory
// estimate.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/mesh_topology.h"
#include "check/penetration_probe.h"
#include "check/tree_cost.h"
#include "core/glm_interop.h"
#include "core/printable_text.h"
#include "sim/memory_estimate.h"
#include "sim/world_builder.h"
#include "sim/world_geometry.h"
#include "soundpaint/check.h"

namespace sp {
namespace {

// A level wider than this, or with no extent above the lower bound, is
// probably not in metres: Quake maps are ~3,000 units across (1/32 m), a
// centimetre export of a 30 m level is 3,000.
constexpr float kLargestPlausibleExtent = 1000.0f;
constexpr float kSmallestPlausibleExtent = 0.5f;
// Findings of the probe: share of penetrations with no way out (at the
// probe's reach; at the config's W_max), and of hits on the back of a face,
// above which the level is reported.
constexpr double kMissShareReported = 0.25;
constexpr double kMissShareWarned = 0.5;
constexpr double kBackFaceShareReported = 0.01;

// The largest count a finding reports: every JSON reader holds integers up
// to 2^53 exactly (JavaScript's Number.MAX_SAFE_INTEGER + 1), not beyond.
constexpr double kLargestExactCount = 9007199254740992.0;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// The layers with a non-zero count, the most first.
std::vector<CheckLayerCount> layer_counts(const std::vector<std::string>& names,
                                          const std::vector<std::uint64_t>& counts) {
  std::vector<CheckLayerCount> layers;
  for (std::size_t l = 0; l < counts.size() && l < names.size(); ++l)
    if (counts[l] > 0) layers.push_back({names[l], counts[l]});
  std::stable_sort(layers.begin(), layers.end(),
                   [](const CheckLayerCount& a, const CheckLayerCount& b) { return a.count > b.count; });
  return layers;
}

// " (concrete 1200, wood 30)": the layers with the most, at most four. The
// names are the level's: escaped, so that none can break the line or steer
// the terminal that shows it.
std::string by_layer(const std::vector<CheckLayerCount>& layers) {
  std::string text;
  for (std::size_t k = 0; k < layers.size() && k < 4; ++k)
    text += (k ? ", " : " (") + printable_text(layers[k].name) + " " + std::to_string(layers[k].count);
  if (layers.size() > 4) text += ", ...";
  return text.empty() ? text : text + ")";
}

void add_topology_findings(const Scene& scene, const MeshTopology& topology, std::vector<CheckFinding>& findings) {
  if (topology.open_edges > 0) {
    std::vector<CheckLayerCount> layers = layer_counts(scene.layer_names, topology.open_edges_by_layer);
    findings.push_back({"open_edges", topology.open_edges,
                        std::to_string(topology.open_edges) + " edges have surface on one side only" +
                            by_layer(layers) +
                            ": the mesh is not closed, so a ray that penetrates it there finds no back face and is "
                            "absorbed. Export closed solids (collision geometry), or give one-surface layers a "
                            "sheet_thickness.",
                        std::move(layers)});
  }
  if (topology.inconsistent_edges > 0) {
    std::vector<CheckLayerCount> layers = layer_counts(scene.layer_names, topology.inconsistent_edges_by_layer);
    findings.push_back({"inconsistent_winding", topology.inconsistent_edges,
                        std::to_string(topology.inconsistent_edges) +
                            " edges are run the same way by both triangles that share them" + by_layer(layers) +
                            ": some faces are flipped, and a ray that strikes the back of a face is absorbed. Make "
                            "the normals face out of every solid (counter-clockwise seen from outside).",
                        std::move(layers)});
  }
  if (topology.degenerate_triangles > 0)
    findings.push_back({"degenerate_triangles",
                        topology.degenerate_triangles,
                        std::to_string(topology.degenerate_triangles) +
                            " triangles have zero area and are never hit. Remove them (merge vertices by distance, "
                            "delete degenerate faces).",
                        {}});
}

void add_scale_finding(const Scene& scene, std::vector<CheckFinding>& findings) {
  // In double: a level from -3e38 to 3e38 is 6e38 across, beyond any float.
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::vec3 v : scene.vertices) {
    lo = glm::min(lo, glm::dvec3(v));
    hi = glm::max(hi, glm::dvec3(v));
  }
  const glm::dvec3 extent = hi - lo;
  const double largest = std::max({extent.x, extent.y, extent.z});
  const auto across = static_cast<std::uint64_t>(std::min(std::round(largest), kLargestExactCount));
  if (largest > kLargestPlausibleExtent)
    findings.push_back({"scale",
                        across,
                        "the level is " + format(largest < 1e9 ? "%.0f" : "%.3g", largest) +
                            " units across, more than a level in metres would be: if its units are not metres, "
                            "scale it on export (Quake units: 1/32, centimetres: 1/100), or every distance and "
                            "attenuation is off by that factor",
                        {}});
  else if (largest < kSmallestPlausibleExtent)
    findings.push_back({"scale",
                        across,
                        format("the level is %.2f units across, less than a room in metres: if its units are not "
                               "metres (kilometres? a scale of 0.01 applied twice?), scale it on export",
                               largest),
                        {}});
}

void add_probe_findings(const Scene& scene, const Config& config, const CheckReport& report, float reach,
                        std::vector<CheckFinding>& findings) {
  const PenetrationProbe& probe = report.probe;
  const PenetrationProbe& at_config = report.probe_at_config;
  if (probe.penetrations > 0 && probe.miss_share() > kMissShareReported) {
    std::vector<CheckLayerCount> layers = layer_counts(scene.layer_names, probe.layer_no_way_out);
    findings.push_back({"penetration_misses", probe.no_way_out,
                        format("%.0f%% of %.0f probe penetrations found no way out of matter within %.1f m",
                               100.0 * probe.miss_share(), double(probe.penetrations), double(reach)) +
                            by_layer(layers) +
                            ": sound will rarely pass through those surfaces. Where the mesh is open (see "
                            "open_edges), export closed solids or give one-surface layers a sheet_thickness; solids "
                            "thicker than that stop sound anyway.",
                        std::move(layers)});
  } else if (at_config.penetrations > 0 && at_config.miss_share() > kMissShareWarned) {
    std::vector<CheckLayerCount> layers = layer_counts(scene.layer_names, at_config.layer_no_way_out);
    findings.push_back({"wall_thickness", at_config.no_way_out,
                        format("%.0f%% of probe penetrations need more than max_wall_thickness (%.2f m) of matter",
                               100.0 * at_config.miss_share(), double(config.max_wall_thickness)) +
                            by_layer(layers) +
                            ", though ways out exist: raise max_wall_thickness if sound should pass walls that "
                            "thick.",
                        std::move(layers)});
  }
  if (probe.hits > 0 && double(probe.back_face_hits) > kBackFaceShareReported * double(probe.hits))
    findings.push_back({"back_faces",
                        probe.back_face_hits,
                        format("%.1f%% of probe hits struck the back of a face: rays there are inside matter or the "
                               "faces are flipped, and are absorbed. Check the winding (see inconsistent_winding) "
                               "and close cracks between solids.",
                               100.0 * double(probe.back_face_hits) / double(probe.hits)),
                        {}});
}

// "4G", "768M": the smallest whole --memory-budget that holds `bytes`.
std::string budget_option_value(std::uint64_t bytes) {
  constexpr std::uint64_t kMiB = std::uint64_t{1} << 20, kGiB = std::uint64_t{1} << 30;
  const auto rounded_up = [&](std::uint64_t unit) { return bytes / unit + (bytes % unit != 0); };
  return bytes > kGiB ? std::to_string(rounded_up(kGiB)) + "G" : std::to_string(rounded_up(kMiB)) + "M";
}

// The user's config against the budget its simulations will have: the
// config's own keys and the estimates simulators check at creation
// (sim/memory_estimate.h), never the probe's.
void add_memory_finding(const Config& config, std::uint64_t budget_bytes, std::vector<CheckFinding>& findings) {
  const MemoryEstimate cpu = estimate_memory(config, Backend::Cpu);
  const MemoryEstimate gpu = estimate_memory(config, Backend::Gpu);
  const std::uint64_t needed = std::max(cpu.total(), gpu.total());
  if (needed <= budget_bytes) return;
  // The backend a simulation runs on decides: say which refuse.
  const char* refused = cpu.total() <= budget_bytes   ? " on the GPU backend"
                        : gpu.total() <= budget_bytes ? " on the CPU backend"
                                                      : "";
  findings.push_back({"memory_budget",
                      needed,
                      "the config needs up to " + describe_bytes(cpu.total()) + " on the CPU backend and " +
                          describe_bytes(gpu.total()) + " on the GPU backend (" + describe_bytes(cpu.ring_bytes) +
                          " for max_indicators " + std::to_string(config.max_indicators) + "; " +
                          describe_bytes(cpu.step_bytes) + " on the CPU, " + describe_bytes(gpu.step_bytes) +
                          " on the GPU, for a step of ray_budget " + std::to_string(config.ray_budget) +
                          " with max_bounces " + std::to_string(config.max_bounces) + "), over the memory budget of " +
                          describe_bytes(budget_bytes) + ", so simulate, render and view will refuse it" + refused +
                          ". Lower those keys, or raise the budget: --memory-budget " + budget_option_value(needed) +
                          " (memory_budget_bytes in the API).",
                      {}});
}

}  // namespace

Result<CheckReport> check_scene(const Scene& scene, const Config& config, const CheckSettings& settings) {
  return capture_errors(
      [&]() -> CheckReport {
        CheckReport report;
        report.triangles = scene.triangle_count();
        // The level is welded and built once; both probes share it.
        MeshTopology topology;
        const WorldGeometryHandle geometry = detail::build_world_geometry(scene, BvhBuildSettings{}, &topology);
        add_topology_findings(scene, topology, report.findings);
        add_scale_finding(scene, report.findings);
        report.probe = detail::probe_penetration_on(scene, config, settings, geometry);
        CheckSettings at_config = settings;
        at_config.probe_reach = 0.0f;
        report.probe_at_config = detail::probe_penetration_on(scene, config, at_config, geometry);
        const float reach = std::max(settings.probe_reach, config.max_wall_thickness);
        add_probe_findings(scene, config, report, reach, report.findings);
        add_work_findings(geometry->bvh, geometry->edges_left_out, report.probe, report.findings);
        add_memory_finding(config, settings.memory_budget_bytes, report.findings);
        return report;
      },
      ErrorCode::InvalidScene);
}

}  // namespace sp
