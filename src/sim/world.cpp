#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "bvh/diffraction_edges.h"
#include "bvh/mesh_topology.h"
#include "config/build_features.h"
#include "config/config_rules.h"
#include "core/finite.h"
#include "core/glm_interop.h"
#include "core/printable_text.h"
#include "display/display_checks.h"
#include "sim/geometry_update.h"
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

namespace detail {

// Guards API users who fill Config by hand with the JSON reader's own
// table of ranges (config_rules.h): one rule per key, whichever way a
// value came.
void check_config(const Config& c) {
  auto fail = [](const std::string& what) { throw Exception(ErrorCode::InvalidConfig, what); };
  config_rules::check_numbers(c);
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

std::vector<LayerProperties> resolve_layers(const Config& config, const std::vector<std::string>& layer_names) {
  std::vector<LayerProperties> properties;
  properties.reserve(layer_names.size());
  for (const std::string& name : layer_names) properties.push_back(resolve_layer(config, name));
  return properties;
}

}  // namespace detail

WorldGeometryHandle::WorldGeometryHandle() : geometry_(std::make_shared<detail::WorldGeometry>()) {}
WorldGeometryHandle::~WorldGeometryHandle() = default;
WorldGeometryHandle::WorldGeometryHandle(const WorldGeometryHandle& other) = default;
WorldGeometryHandle& WorldGeometryHandle::operator=(const WorldGeometryHandle& other) = default;
// A moved-from handle's geometry is null: reading it gives the empty
// geometry, changing it first gives it one of its own.
const detail::WorldGeometry& WorldGeometryHandle::operator*() const {
  static const detail::WorldGeometry empty{};
  return geometry_ ? *geometry_ : empty;
}
detail::WorldGeometry& WorldGeometryHandle::mutate() {
  if (!geometry_) {
    geometry_ = std::make_shared<detail::WorldGeometry>();
  } else if (geometry_.use_count() > 1) {
    geometry_ = std::make_shared<detail::WorldGeometry>(*geometry_);
  }
  return *geometry_;
}
WorldGeometryHandle::WorldGeometryHandle(WorldGeometryHandle&& other) noexcept = default;
WorldGeometryHandle& WorldGeometryHandle::operator=(WorldGeometryHandle&& other) noexcept = default;

namespace detail {

WorldGeometry::WorldGeometry(const WorldGeometry& other)
    : bvh(other.bvh),
      rest_vertices(other.rest_vertices),
      triangle_instances(other.triangle_instances),
      triangle_layers(other.triangle_layers),
      triangle_solids(other.triangle_solids),
      edges_left_out(other.edges_left_out),
      build_sah_cost(other.build_sah_cost) {
  const std::lock_guard lock(other.edges_mutex_);
  edges_found_ = other.edges_found_;
}

void WorldGeometry::ensure_exposed_edges() const {
  const std::lock_guard lock(edges_mutex_);
  if (edges_found_ || bvh.nodes.empty()) return;
  // A cache of what the geometry already determines: filled once, under
  // the lock, before any reader of the edges (a world with diffraction on)
  // is made.
  auto& self = const_cast<WorldGeometry&>(*this);
  self.bvh.edges = find_exposed_edges(bvh, &self.edges_left_out);
  edges_found_ = true;
}

}  // namespace detail

std::size_t World::triangle_count() const { return geometry->bvh.triangle_count(); }

namespace detail {

WorldGeometryHandle build_world_geometry(const Scene& scene, const BvhBuildSettings& bvh_settings,
                                         MeshTopology* topology_out) {
  check_scene(scene);
  WorldGeometryHandle handle;
  WorldGeometry& geometry = handle.mutate();
  // Which triangles form one piece of surface: the matter rules cross a
  // piece met through a shared edge once (docs/model.md#the-rules).
  std::vector<glm::vec3> vertices = to_glm(scene.vertices);
  MeshTopology topology = analyse_mesh(vertices, scene.triangle_layers, scene.layer_names.size());
  geometry.bvh = build_bvh(vertices, scene.triangle_layers, topology.triangle_solids, bvh_settings);
  if (!scene.instance_names.empty()) {
    geometry.rest_vertices = std::move(vertices);
    geometry.triangle_instances = scene.triangle_instances;
    if (geometry.triangle_instances.empty())
      geometry.triangle_instances.assign(scene.triangle_count(), kStaticInstance);
    geometry.triangle_layers = scene.triangle_layers;
    geometry.triangle_solids = topology.triangle_solids;
    // What a refit's cost is compared with, to decide on a rebuild.
    geometry.build_sah_cost = absolute_sah_cost(geometry.bvh);
  }
  if (topology_out != nullptr) *topology_out = std::move(topology);
  return handle;
}

World make_world_around(const Scene& scene, const Config& config, WorldGeometryHandle geometry, bool check_geometry) {
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
  world.layer_properties = resolve_layers(config, scene.layer_names);
  if (check_geometry && geometry->bvh.triangle_count() != scene.triangle_count())
    throw Exception(ErrorCode::InvalidArgument, "make_world: the geometry has " +
                                                    std::to_string(geometry->bvh.triangle_count()) +
                                                    " triangles, the scene " + std::to_string(scene.triangle_count()) +
                                                    ": it was built from another scene");
  // The edges sound bends round, only when it may (docs/model.md#diffraction).
  if (config.diffraction.enabled) geometry->ensure_exposed_edges();
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
    detail::check_config(config);
    (void)detail::make_world_around(scene, config, WorldGeometryHandle{}, /*check_geometry=*/false);
    return detail::make_world_around(scene, config, detail::build_world_geometry(scene, bvh_settings, nullptr));
  });
}

Result<WorldGeometryHandle> build_geometry(const Scene& scene, const BvhBuildSettings& bvh_settings) {
  return capture_errors([&] { return detail::build_world_geometry(scene, bvh_settings, nullptr); });
}

Result<World> make_world(const Scene& scene, const Config& config, WorldGeometryHandle geometry) {
  return capture_errors([&] {
    check_scene(scene);
    return detail::make_world_around(scene, config, std::move(geometry));
  });
}

float indicator_opacity(const Indicator& indicator, double age_seconds, float lifetime_seconds) {
  if (!(lifetime_seconds > 0.0f) || !(age_seconds >= 0.0)) return 0.0f;
  return shader::sp_indicator_opacity(indicator.intensity, static_cast<float>(age_seconds), lifetime_seconds);
}

}  // namespace sp
