#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "bvh/diffraction_edges.h"
#include "bvh/mesh_topology.h"
#include "config/build_features.h"
#include "core/finite.h"
#include "core/glm_interop.h"
#include "core/printable_text.h"
#include "display/display_checks.h"
#include "sim/source_checks.h"
#include "sim/source_display.h"
#include "sim/world_builder.h"
#include "sim/world_geometry.h"
#include "sp_ring.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {

void check_scene(const Scene& scene) {
  const std::string name = scene.path.empty() ? std::string("scene") : printable_text(scene.path.string());
  auto fail = [&](const std::string& what) { throw Exception(ErrorCode::InvalidScene, name + ": " + what); };
  if (scene.triangle_count() == 0) fail("no triangles");
  if (scene.vertices.size() != 3 * scene.triangle_count())
    fail("vertices (" + std::to_string(scene.vertices.size()) + ") must be 3 per triangle (" +
         std::to_string(scene.triangle_count()) + " triangles)");
  for (std::size_t i = 0; i < scene.triangle_count(); ++i)
    if (scene.triangle_layers[i] >= scene.layer_names.size())
      fail("triangle " + std::to_string(i) + " has layer id " + std::to_string(scene.triangle_layers[i]) +
           " but there are only " + std::to_string(scene.layer_names.size()) + " layers");
  for (std::size_t i = 0; i < scene.vertices.size(); ++i)
    if (!all_finite(scene.vertices[i])) fail("vertex " + std::to_string(i) + " is not finite");
  if (!scene.triangle_instances.empty()) {
    if (scene.triangle_instances.size() != scene.triangle_count())
      fail("triangle_instances (" + std::to_string(scene.triangle_instances.size()) +
           ") must be empty or one per triangle (" + std::to_string(scene.triangle_count()) + ")");
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
      const std::uint32_t instance = scene.triangle_instances[i];
      if (instance != kStaticInstance && instance >= scene.instance_names.size())
        fail("triangle " + std::to_string(i) + " belongs to instance " + std::to_string(instance) +
             " but there are only " + std::to_string(scene.instance_names.size()) + " instances");
    }
  }
}

}  // namespace

void check_source(const SourceDesc& s, std::size_t id) {
  auto fail = [&](const std::string& what) {
    throw Exception(ErrorCode::InvalidArgument, "source " + std::to_string(id) + ": " + what);
  };
  if (!all_finite(s.position)) fail("position is not finite");
  if (s.color)
    for (int c = 0; c < 3; ++c)
      if (!((*s.color)[c] >= 0.0f && (*s.color)[c] <= 1.0f)) fail("color components must be in [0, 1]");
  if (!(s.max_distance >= 0.0f) || !std::isfinite(s.max_distance)) fail("max_distance must be finite and >= 0");
  if (!(s.loudness >= 0.0f) || !std::isfinite(s.loudness)) fail("loudness must be finite and >= 0");
  if (!(s.interval > 0.0) || !std::isfinite(s.interval)) fail("interval must be finite and > 0");
  if (!(s.duration >= 0.0) || !std::isfinite(s.duration)) fail("duration must be finite and >= 0");
  if (!(s.phase >= 0.0) || !std::isfinite(s.phase)) fail("phase must be finite and >= 0");
}

namespace {

// Guards API users who fill Config by hand; parse_config checks the same.
void check_config(const Config& c) {
  auto fail = [](const std::string& what) { throw Exception(ErrorCode::InvalidConfig, what); };
  auto non_negative = [&](float v, const char* key) {
    if (!(v >= 0.0f) || !std::isfinite(v)) fail(std::string(key) + " must be finite and >= 0");
  };
  non_negative(c.scan_radius, "scan_radius");
  non_negative(c.min_energy, "min_energy");
  non_negative(c.air_attenuation, "air_attenuation");
  non_negative(c.indicator_size, "indicator_size");
  if (!(c.max_wall_thickness > 0.0f) || !std::isfinite(c.max_wall_thickness)) fail("max_wall_thickness must be > 0");
  if (!(c.indicator_lifetime > 0.0f) || !std::isfinite(c.indicator_lifetime)) fail("indicator_lifetime must be > 0");
  if (!(c.dt > 0.0) || !std::isfinite(c.dt)) fail("dt must be > 0");
  if (!(c.bounce_energy_loss >= 0.0f && c.bounce_energy_loss <= 1.0f)) fail("bounce_energy_loss must be in [0, 1]");
  if (c.max_bounces > kMaxBouncesLimit) fail("max_bounces must be <= " + std::to_string(kMaxBouncesLimit));
  if (c.ray_budget > kMaxRayBudget) fail("ray_budget must be <= " + std::to_string(kMaxRayBudget));
  if (c.max_indicators == 0 || c.max_indicators > kMaxIndicatorsLimit)
    fail("max_indicators must be in [1, " + std::to_string(kMaxIndicatorsLimit) + "]");
  for (const auto& [name, layer] : c.layers) {
    if (!(layer.reflect_probability >= 0.0f && layer.reflect_probability <= 1.0f))
      fail("layers." + printable_text(name) + ".reflect_probability must be in [0, 1]");
    if (!(layer.attenuation >= 0.0f) || !std::isfinite(layer.attenuation))
      fail("layers." + printable_text(name) + ".attenuation must be finite and >= 0");
  }
  if (c.listener_position && !all_finite(*c.listener_position)) fail("listener.position is not finite");
  if (c.cpu_traversal == CpuTraversal::Embree && !embree_available())
    fail(std::string("cpu_traversal: Embree ") + kEmbreeBuildHint);
  if (c.cpu_traversal != CpuTraversal::Soundpaint && c.cpu_traversal != CpuTraversal::Embree)
    fail("cpu_traversal is not a CpuTraversal value");
  check_display_settings(c.display);
  const SignalSettings& signal = c.signal;
  if (signal.window && !(*signal.window >= 0.001 && *signal.window <= 1.0))
    fail("signal.window must be in [0.001, 1] seconds");
  if (!std::isfinite(signal.floor_db) || !std::isfinite(signal.reference_db) ||
      !(signal.floor_db < signal.reference_db))
    fail("signal.floor must be finite and below signal.reference");
}

}  // namespace

WorldGeometryHandle::WorldGeometryHandle() : geometry_(std::make_unique<detail::WorldGeometry>()) {}
WorldGeometryHandle::~WorldGeometryHandle() = default;
WorldGeometryHandle::WorldGeometryHandle(const WorldGeometryHandle& other)
    : geometry_(std::make_unique<detail::WorldGeometry>(*other)) {}
WorldGeometryHandle& WorldGeometryHandle::operator=(const WorldGeometryHandle& other) {
  if (this != &other) geometry_ = std::make_unique<detail::WorldGeometry>(*other);
  return *this;
}
// A moved-from handle's geometry is null: reading it gives the empty
// geometry, writing it first gives it one of its own.
detail::WorldGeometry& WorldGeometryHandle::operator*() {
  if (!geometry_) geometry_ = std::make_unique<detail::WorldGeometry>();
  return *geometry_;
}
const detail::WorldGeometry& WorldGeometryHandle::operator*() const {
  static const detail::WorldGeometry empty{};
  return geometry_ ? *geometry_ : empty;
}
WorldGeometryHandle::WorldGeometryHandle(WorldGeometryHandle&& other) noexcept = default;
WorldGeometryHandle& WorldGeometryHandle::operator=(WorldGeometryHandle&& other) noexcept = default;

std::size_t World::triangle_count() const { return geometry->bvh.triangle_count(); }

namespace detail {

WorldGeometryHandle build_world_geometry(const Scene& scene, const Config& config, const BvhBuildSettings& bvh_settings,
                                         MeshTopology* topology_out) {
  check_scene(scene);
  check_config(config);
  WorldGeometryHandle geometry;
  // Which triangles form one piece of surface: the matter rules cross a
  // piece met through a shared edge once (docs/model.md#the-rules).
  std::vector<glm::vec3> vertices = to_glm(scene.vertices);
  MeshTopology topology = analyse_mesh(vertices, scene.triangle_layers, scene.layer_names.size());
  geometry->bvh = build_bvh(vertices, scene.triangle_layers, topology.triangle_solids, bvh_settings);
  // The edges sound bends round, only when it may (docs/model.md#diffraction).
  if (config.diffraction.enabled) geometry->bvh.edges = find_exposed_edges(geometry->bvh, &geometry->edges_left_out);
  if (!scene.instance_names.empty()) {
    geometry->rest_vertices = std::move(vertices);
    geometry->triangle_instances = scene.triangle_instances;
    if (geometry->triangle_instances.empty())
      geometry->triangle_instances.assign(scene.triangle_count(), kStaticInstance);
    geometry->triangle_layers = scene.triangle_layers;
    geometry->triangle_solids = topology.triangle_solids;
  }
  if (topology_out != nullptr) *topology_out = std::move(topology);
  return geometry;
}

World make_world_around(const Scene& scene, const Config& config, WorldGeometryHandle geometry) {
  check_config(config);
  World world;
  world.config = config;
  world.sources = scene.sources;
  world.sources.insert(world.sources.end(), config.sources.begin(), config.sources.end());
  for (std::size_t id = 0; id < world.sources.size(); ++id) check_source(world.sources[id], id);
  world.source_active.assign(world.sources.size(), true);
  resolve_all_source_display(world);
  if (config.listener_position) {
    world.listener = *config.listener_position;
  } else if (scene.camera) {
    world.listener = scene.camera->position();
  } else {
    throw Exception(ErrorCode::InvalidArgument,
                    "no listener: the scene has no camera node and the config sets no listener.position");
  }
  world.layer_names = scene.layer_names;
  world.layer_triangle_counts.assign(scene.layer_names.size(), 0);
  for (std::uint32_t layer : scene.triangle_layers) world.layer_triangle_counts[layer] += 1;
  for (const std::string& name : scene.layer_names) world.layer_properties.push_back(resolve_layer(config, name));
  world.geometry = std::move(geometry);
  if (!scene.instance_names.empty()) {
    world.instance_names = scene.instance_names;
    world.instance_transforms.assign(scene.instance_names.size(), Mat4{});
  }
  return world;
}

}  // namespace detail

Result<World> make_world(const Scene& scene, const Config& config, const BvhBuildSettings& bvh_settings) {
  return capture_errors([&]() -> World {
    // The cheap checks first: a bad source or a missing listener is
    // refused before the level's geometry is built.
    check_scene(scene);
    (void)detail::make_world_around(scene, config, WorldGeometryHandle{});
    return detail::make_world_around(scene, config, detail::build_world_geometry(scene, config, bvh_settings, nullptr));
  });
}

float indicator_opacity(const Indicator& indicator, double age_seconds, float lifetime_seconds) {
  if (!(lifetime_seconds > 0.0f) || !(age_seconds >= 0.0)) return 0.0f;
  return shader::sp_indicator_opacity(indicator.intensity, static_cast<float>(age_seconds), lifetime_seconds);
}

}  // namespace sp
