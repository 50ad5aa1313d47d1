// sp::check_scene: the findings of `soundpaint check`, from the mesh's
// topology, its bounds and the penetration probe.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/glm.hpp>

#include "bvh/mesh_topology.h"
#include "core/glm_interop.h"
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

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// " (concrete 1200, wood 30)": the layers with the most, at most four.
std::string by_layer(const std::vector<std::string>& names, const std::vector<std::uint64_t>& counts) {
  std::vector<std::size_t> order;
  for (std::size_t l = 0; l < counts.size() && l < names.size(); ++l)
    if (counts[l] > 0) order.push_back(l);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return counts[a] > counts[b]; });
  std::string text;
  for (std::size_t k = 0; k < order.size() && k < 4; ++k)
    text += (k ? ", " : " (") + names[order[k]] + " " + std::to_string(counts[order[k]]);
  if (order.size() > 4) text += ", ...";
  return text.empty() ? text : text + ")";
}

void add_topology_findings(const Scene& scene, const MeshTopology& topology, std::vector<CheckFinding>& findings) {
  if (topology.open_edges > 0)
    findings.push_back({"open_edges", topology.open_edges,
                        std::to_string(topology.open_edges) + " edges have surface on one side only" +
                            by_layer(scene.layer_names, topology.open_edges_by_layer) +
                            ": the mesh is not closed, so a ray that penetrates it there finds no back face and is "
                            "absorbed. Export closed solids (collision geometry), or give one-surface layers a "
                            "sheet_thickness."});
  if (topology.inconsistent_edges > 0)
    findings.push_back({"inconsistent_winding", topology.inconsistent_edges,
                        std::to_string(topology.inconsistent_edges) +
                            " edges are run the same way by both triangles that share them" +
                            by_layer(scene.layer_names, topology.inconsistent_edges_by_layer) +
                            ": some faces are flipped, and a ray that strikes the back of a face is absorbed. Make "
                            "the normals face out of every solid (counter-clockwise seen from outside)."});
  if (topology.degenerate_triangles > 0)
    findings.push_back({"degenerate_triangles", topology.degenerate_triangles,
                        std::to_string(topology.degenerate_triangles) +
                            " triangles have zero area and are never hit. Remove them (merge vertices by distance, "
                            "delete degenerate faces)."});
}

void add_scale_finding(const Scene& scene, std::vector<CheckFinding>& findings) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3 v : scene.vertices) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  const glm::vec3 extent = hi - lo;
  const float largest = std::max({extent.x, extent.y, extent.z});
  const auto across = static_cast<std::uint64_t>(std::lround(largest));
  if (largest > kLargestPlausibleExtent)
    findings.push_back({"scale", across,
                        format("the level is %.0f units across, more than a level in metres would be: if its units "
                               "are not metres, scale it on export (Quake units: 1/32, centimetres: 1/100), or every "
                               "distance and attenuation is off by that factor",
                               double(largest))});
  else if (largest < kSmallestPlausibleExtent)
    findings.push_back({"scale", across,
                        format("the level is %.2f units across, less than a room in metres: if its units are not "
                               "metres (kilometres? a scale of 0.01 applied twice?), scale it on export",
                               double(largest))});
}

void add_probe_findings(const Scene& scene, const Config& config, const CheckReport& report, float reach,
                        std::vector<CheckFinding>& findings) {
  const PenetrationProbe& probe = report.probe;
  const PenetrationProbe& at_config = report.probe_at_config;
  if (probe.penetrations > 0 && probe.miss_share() > kMissShareReported) {
    findings.push_back({"penetration_misses", probe.no_way_out,
                        format("%.0f%% of %.0f probe penetrations found no way out of matter within %.1f m",
                               100.0 * probe.miss_share(), double(probe.penetrations), double(reach)) +
                            by_layer(scene.layer_names, probe.layer_no_way_out) +
                            ": sound will rarely pass through those surfaces. Where the mesh is open (see "
                            "open_edges), export closed solids or give one-surface layers a sheet_thickness; solids "
                            "thicker than that stop sound anyway."});
  } else if (at_config.penetrations > 0 && at_config.miss_share() > kMissShareWarned) {
    findings.push_back({"wall_thickness", at_config.no_way_out,
                        format("%.0f%% of probe penetrations need more than max_wall_thickness (%.2f m) of matter",
                               100.0 * at_config.miss_share(), double(config.max_wall_thickness)) +
                            by_layer(scene.layer_names, at_config.layer_no_way_out) +
                            ", though ways out exist: raise max_wall_thickness if sound should pass walls that "
                            "thick."});
  }
  if (probe.hits > 0 && double(probe.back_face_hits) > kBackFaceShareReported * double(probe.hits))
    findings.push_back({"back_faces", probe.back_face_hits,
                        format("%.1f%% of probe hits struck the back of a face: rays there are inside matter or the "
                               "faces are flipped, and are absorbed. Check the winding (see inconsistent_winding) "
                               "and close cracks between solids.",
                               100.0 * double(probe.back_face_hits) / double(probe.hits))});
}

}  // namespace

Result<CheckReport> check_scene(const Scene& scene, const Config& config, const CheckSettings& settings) {
  return capture_errors(
      [&]() -> CheckReport {
        CheckReport report;
        report.triangles = scene.triangle_count();
        const MeshTopology topology =
            analyse_mesh(to_glm(scene.vertices), scene.triangle_layers, scene.layer_names.size());
        add_topology_findings(scene, topology, report.findings);
        add_scale_finding(scene, report.findings);
        report.probe = probe_penetration(scene, config, settings).value();
        CheckSettings at_config = settings;
        at_config.probe_reach = 0.0f;
        report.probe_at_config = probe_penetration(scene, config, at_config).value();
        const float reach = std::max(settings.probe_reach, config.max_wall_thickness);
        add_probe_findings(scene, config, report, reach, report.findings);
        return report;
      },
      ErrorCode::InvalidScene);
}

}  // namespace sp
