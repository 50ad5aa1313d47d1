#include <chrono>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "bvh/diffraction_edges.h"
#include "cli/commands.h"
#include "cli/limit_options.h"
#include "cli/options.h"
#include "check/tree_cost.h"
#include "cli/world_loading.h"
#include "core/printable_text.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "soundpaint/ray_query.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"

namespace sp::cli {
namespace {

constexpr const char* kInfoHelp =
    "usage: soundpaint info SCENE [--config FILE] [--max-triangles N] [--allow-external-uris]\n"
    "                             [--memory-budget SIZE]\n"
    "\n"
    "Prints the scene's triangles, layers (with triangle counts and the acoustic\n"
    "properties they resolve to), sources, listener, the floor under each (a ray\n"
    "cast straight down), and BVH node count, depth and\n"
    "build time, and the exposed edges sound may bend round (diffraction) with the\n"
    "time it takes to find them. --config applies a configuration's layers, sources,\n"
    "listener and diffraction edge angle.\n";

void print_vec(glm::vec3 v) { std::printf("(%.3f, %.3f, %.3f)", double(v.x), double(v.y), double(v.z)); }

// What is straight below `position` (the public ray query): a source or
// listener with no floor under it is likely outside the level.
void print_floor(const World& world, const char* what, glm::vec3 position) {
  const std::optional<RayHit> hit = cast_ray(world, position, Vec3(0.0f, -1.0f, 0.0f)).value();
  if (hit)
    std::printf("  %-10s %.3f m above %s\n", what, double(hit->distance),
                printable_text(world.layer_names[hit->layer]).c_str());
  else std::printf("  %-10s nothing below: outside the level?\n", what);
}

}  // namespace

int run_info(const std::vector<std::string>& args) {
  // --memory-budget: a level whose load would pass it is refused, naming
  // the option; so info takes it too.
  ParsedArgs parsed =
      parse_args(args, with_options(with_options({"--config"}, kSceneLimitValueOptions), kMemoryLimitValueOptions),
                 with_options({"--help"}, kSceneLimitFlagOptions));
  if (printed_help(parsed, {kInfoHelp, scene_limit_help(), memory_limit_help()})) return 0;
  const std::string& scene_path = scene_argument(parsed, "info");
  Config config;
  if (auto path = parsed.value("--config")) config = load_config(*path).value();
  Scene scene = load_scene(scene_path, scene_load_options(parsed)).value();
  // info describes scenes without a listener too; simulate would reject them.
  const char* listener_from = config.listener_position ? "config" : scene.camera ? "camera" : "none; origin assumed";
  if (!config.listener_position && !scene.camera) config.listener_position = glm::vec3(0.0f);
  World world = make_world(scene, config).value();
  const std::optional<PenetrationProbe> probe = warn_if_penetration_fails(scene, world);

  // Every name below is the level's or the config's: data, printed escaped
  // (core/printable_text.h) so that none can steer the terminal.
  std::printf("scene: %s\n", printable_text(scene.path.string()).c_str());
  std::printf("triangles: %zu\n", scene.triangle_count());
  std::printf("layers: %zu\n", world.layer_names.size());
  for (std::size_t l = 0; l < world.layer_names.size(); ++l)
    std::printf("  %-16s %8u triangles  reflect_probability %.2f  attenuation %.2f/m\n",
                printable_text(world.layer_names[l]).c_str(), world.layer_triangle_counts[l],
                double(world.layer_properties[l].reflect_probability), double(world.layer_properties[l].attenuation));
  std::printf("sources: %zu\n", world.sources.size());
  for (std::size_t id = 0; id < world.sources.size(); ++id) {
    const SourceDesc& s = world.sources[id];
    std::printf("  %2zu %-16s %-12s at ", id, s.name.empty() ? "-" : printable_text(s.name).c_str(),
                printable_text(s.category).c_str());
    print_vec(s.position);
    std::printf(" color ");
    print_vec(world.source_colors[id]);
    if (!s.color) std::printf(" (palette)");
    std::printf(" max_distance %.1f m, every %.3f s for %.3f s\n", double(s.max_distance), s.interval, s.duration);
  }
  std::printf("listener: ");
  print_vec(world.listener);
  std::printf(" (%s)\n", listener_from);
  std::printf("floors (a ray cast straight down):\n");
  print_floor(world, "listener", world.listener);
  for (std::size_t id = 0; id < world.sources.size(); ++id)
    print_floor(world, ("source " + std::to_string(id)).c_str(), world.sources[id].position);
  const Bvh& bvh = world.geometry->bvh;
  const double sah = bvh_sah_cost(bvh);
  std::printf("bvh: %zu nodes, depth %u, built in %.3f ms, SAH cost %.0f (tests a ray through the level expects)\n",
              bvh.nodes.size(), bvh.depth, bvh.build_ms, sah);
  if (is_degenerate_tree(sah)) std::printf("  degenerate: %s\n", degenerate_tree_advice().c_str());
  if (probe && probe->casts_cut_short > 0)
    std::printf("  %llu of the probe's casts reached the per-cast work bound\n",
                static_cast<unsigned long long>(probe->casts_cut_short));
  // Each exposed edge is held by one triangle (a free boundary) or two:
  // the world's own when diffraction is on, else found here to show them.
  const auto started = std::chrono::steady_clock::now();
  std::uint64_t left_out = world.geometry->edges_left_out;
  const std::vector<shader::TriangleEdges> edges =
      config.diffraction.enabled ? bvh.edges : find_exposed_edges(bvh, &left_out);
  const double edges_ms =
      config.diffraction.enabled
          ? 0.0
          : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  std::size_t boundary = 0, convex = 0;
  const float cos_max = diffraction_edge_cos_max(config.diffraction);
  for (const shader::TriangleEdges& e : edges)
    for (int i = 0; i < 3; ++i) {
      if (((e.exposed >> i) & 1u) == 0u) continue;
      if (e.turn_cos[i] <= -1.0f) ++boundary;
      else if (e.turn_cos[i] <= cos_max) ++convex;
    }
  if (config.diffraction.enabled)
    std::printf(
        "diffracting edges (at %.0f degrees): %zu convex, %zu free boundaries, found with the level "
        "(diffraction on)\n",
        double(config.diffraction.edge_angle), convex / 2, boundary);
  else
    std::printf(
        "diffracting edges (at %.0f degrees): %zu convex, %zu free boundaries, found in %.3f ms (diffraction "
        "off)\n",
        double(config.diffraction.edge_angle), convex / 2, boundary, edges_ms);
  if (left_out > 0)
    std::printf("  %llu edges left out: their burial test reached its work bound (overlapping triangles)\n",
                static_cast<unsigned long long>(left_out));
  return 0;
}

}  // namespace sp::cli
