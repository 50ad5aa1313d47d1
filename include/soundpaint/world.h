// A scene and a configuration resolved into a World: the indicators a
// simulation paints, the level's shared geometry, and make_world.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/export.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/scene.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// Indicator::kind values.
inline constexpr std::uint32_t kIndicatorHit = 0;   // a ray struck a surface
inline constexpr std::uint32_t kIndicatorExit = 1;  // a ray left matter it had crossed

// An indicator (docs/model.md#indicators): a cue painted where a ray met a
// surface. Category is sources[source_id].category. 96 bytes, laid out as
// the GPU's ring buffer holds them.
struct Indicator {
  Vec3 position;
  float energy = 0.0f;
  Vec3 normal;        // facing the side the ray came from (hit) or leaves to (exit)
  float size = 0.0f;  // metres: indicator_size * E / E0
  Vec3 color;         // linear RGB
  float intensity = 0.0f;
  Vec3 dir;                  // the ray's direction of travel: incoming (hit), outgoing (exit)
  float path_length = 0.0f;  // metres from the source
  std::uint32_t kind = kIndicatorHit;
  std::uint32_t source_id = 0;
  std::uint32_t bounces = 0;
  std::uint32_t penetrations = 0;
  std::uint32_t diffractions = 0;
  std::uint32_t step = 0;
  std::uint32_t ray_index = 0;
  std::uint32_t iteration = 0;
  // What reaches the player (docs/model.md#cues-for-the-player), with
  // Config::cues.listen: the unit direction from the listener to this spot,
  // the way its sound arrives, and the energy that arrives along it, 0 when
  // the listener does not hear it (its surface faces away, the way is
  // blocked, or no more than tau_min would arrive).
  Vec3 arrival;
  float heard_energy = 0.0f;
  std::uint32_t emit_cell = 0;    // the guide cell its ray was emitted into
  std::uint32_t source_slot = 0;  // its source's entry in its step's source table
  float toward = 0.0f;            // in [0, 1]: how nearly `arrival` points at its source; 0 when not heard
  std::uint32_t reserved = 0;
};

// How make_world builds its BVH (binned SAH).
inline constexpr std::uint32_t kBvhMaxDepth = 32;  // the traversal stack's depth
struct BvhBuildSettings {
  std::uint32_t bins = 16;          // SAH bins per axis and split
  std::uint32_t max_leaf_size = 4;  // leaves never hold more unless the depth cap forces it
  // SAH cost of visiting a node, relative to one triangle test. 3 makes
  // leaves of up to four triangles, which the CPU tests as one packet:
  // casts 3-7 % faster than with 1 (leaves of two), 25 % at 1M triangles,
  // on bench/RESULTS.md section 22's machine.
  float traversal_cost = 3.0f;
  std::uint32_t max_depth = kBvhMaxDepth;  // levels including the root; <= kBvhMaxDepth
  // Threads the build may use: 0 means std::thread::hardware_concurrency(),
  // 1 builds on the calling thread only. Subtrees near the root are built
  // concurrently and spliced in a fixed order, so the result (nodes,
  // triangles, depth) is byte-identical for every value.
  unsigned threads = 0;
};

struct BvhChanges;  // src/bvh/bvh.h
namespace detail {
struct WorldGeometry;      // src/sim/world_geometry.h
struct SoundSceneBackend;  // src/sim/sound_scene_backend.h
}  // namespace detail

// The level's geometry a backend traces (the BVH, which triangles form one
// solid, the rest pose of moving parts and what rebuilding needs, and, once
// a world with diffraction asks, the edges sound bends round), opaque
// outside the library. Built once (build_geometry) and shared: copies of a
// handle, and the Worlds, simulators, visualizers and probes made from
// them, read one geometry; only a scene whose moving parts move gets a copy
// of its own, when they first move. A moved-from handle holds no geometry
// and reads as an empty one (no triangles).
class WorldGeometryHandle {
 public:
  WorldGeometryHandle();
  ~WorldGeometryHandle();
  WorldGeometryHandle(const WorldGeometryHandle& other);
  WorldGeometryHandle& operator=(const WorldGeometryHandle& other);
  WorldGeometryHandle(WorldGeometryHandle&& other) noexcept;
  WorldGeometryHandle& operator=(WorldGeometryHandle&& other) noexcept;

  const detail::WorldGeometry& operator*() const;
  const detail::WorldGeometry* operator->() const { return &**this; }
  // The geometry to change (moving parts), this handle's own: copied first
  // when it is shared, so that no other holder sees the change.
  detail::WorldGeometry& mutate();
  // Whether the two read the same geometry.
  bool shares_with(const WorldGeometryHandle& other) const { return geometry_ == other.geometry_; }

 private:
  std::shared_ptr<detail::WorldGeometry> geometry_;
};

// Everything a backend needs, resolved once: geometry, per-layer acoustics,
// sources (scene's then config's) and the listener. A running simulation
// keeps its World in a SoundScene, which changes sources and moving parts.
// Make it with make_world: the simulators refuse a World whose tables
// disagree (sources, source_active, source_colors; instance_names,
// instance_transforms) rather than repair it.
struct World {
  Config config;
  std::vector<std::string> layer_names;
  std::vector<LayerProperties> layer_properties;  // per layer id
  std::vector<std::uint32_t> layer_triangle_counts;
  std::vector<SourceDesc> sources;  // source id == index
  // Per source id: its category's index in category_names (built-in
  // categories first, then others in order of first appearance), and the
  // colour its indicators carry: its own, else its category's palette
  // colour. Kept up to date by make_world and SoundScene.
  std::vector<std::uint32_t> source_categories;
  std::vector<Vec3> source_colors;
  std::vector<std::string> category_names;
  // Per source id: false once removed (SoundScene::remove_source); the slot
  // keeps its last description and a later add_source may reuse it.
  std::vector<bool> source_active;
  Vec3 listener;

  // Moving parts (Scene::instance_names); empty when the scene has none.
  // Kept so that an instance transform can re-place its triangles.
  std::vector<std::string> instance_names;
  std::vector<Mat4> instance_transforms;  // per instance, applied to the rest pose

  // The triangles and their BVH, opaque.
  WorldGeometryHandle geometry;
  std::size_t triangle_count() const;
};

// Resolves scene + config. Errors: no listener (neither a camera in the scene
// nor config.listener), invalid source fields, a config value out of range
// (InvalidConfig naming the key, as the JSON reader does). Builds the
// level's geometry: to make several worlds of one level (other settings,
// another backend, a probe), build it once with build_geometry and use the
// overload below.
Result<World> make_world(const Scene& scene, const Config& config, const BvhBuildSettings& bvh_settings = {});

// The level's geometry, built once: weld and topology, the BVH, and what
// moving parts need (the edges diffraction needs are built when a world
// first asks). Errors: InvalidScene as make_world.
Result<WorldGeometryHandle> build_geometry(const Scene& scene, const BvhBuildSettings& bvh_settings = {});

// A World for `scene` and `config` around `geometry`, built from the same
// scene: nothing is built again (diffraction's edges once, the first time
// a world with diffraction on asks). Errors as make_world, and
// InvalidArgument when `geometry` was built from another scene (its
// triangle count differs).
Result<World> make_world(const Scene& scene, const Config& config, WorldGeometryHandle geometry);

}  // namespace sp

SP_CPP_API_END
