// Scenes: a glTF 2.0 level flattened into one world-space triangle soup with a
// layer per triangle, plus its sound sources and listener (contract: README.md,
// "Authoring scenes").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// A perspective camera placed by a node's world transform; looks down -Z of
// that transform, +Y up (glTF convention).
struct Camera {
  Mat4 world;                 // node's world matrix (rotation + translation)
  float yfov = 0.8f;          // vertical field of view, radians
  float znear = 0.05f;        // metres
  float zfar = 1000.0f;       // metres
  float aspect_ratio = 0.0f;  // 0: take it from the image
  Vec3 position() const { return world.translation(); }
};

// Scene::triangle_instances value of a triangle that never moves.
inline constexpr std::uint32_t kStaticInstance = 0xFFFFFFFFu;

struct Scene {
  std::filesystem::path path;                  // where it was loaded from, if from a file
  std::vector<Vec3> vertices;                  // 3 per triangle, world space, metres
  std::vector<std::uint32_t> triangle_layers;  // per triangle, index into layer_names
  std::vector<std::string> layer_names;        // distinct layer names, in first-use order
  std::vector<SourceDesc> sources;             // in node order (depth-first over the default scene)
  std::optional<Camera> camera;                // the first camera node: listener and render camera
  // Moving parts (doors, lifts): per triangle, an index into instance_names
  // or kStaticInstance; empty when nothing moves. A simulation places an
  // instance's triangles with SoundScene::set_instance_transform, relative
  // to the positions in `vertices` (the rest pose).
  std::vector<std::uint32_t> triangle_instances;
  std::vector<std::string> instance_names;

  std::size_t triangle_count() const { return triangle_layers.size(); }
};

// Triangles a scene may have by default, every mesh instance counted.
// Loading a scene and building its BVH peaks at about 0.3 KB a triangle, so
// this keeps a level under about 0.6 GB and a few seconds of loading; the
// acoustic geometry of real levels is a few hundred thousand triangles.
inline constexpr std::uint64_t kDefaultMaxTriangles = 2'000'000;

// How load_scene treats a file that may come from a stranger (a downloaded
// level, a mod): README "Security".
struct SceneLoadOptions {
  // false: buffers are read only from regular files inside the scene file's
  // folder tree (no absolute path, no ".." or symbolic link leading out;
  // a link with an absolute target is refused even when it points inside).
  // true: from any regular file the URI names, for trusted asset pipelines.
  // Either way, devices, /proc and /sys are never read and images never are.
  bool allow_external_uris = false;
  // A scene with more triangles than this (every instance of a mesh counted)
  // is refused before its triangles are built. At most 2^32 / 3.
  std::uint64_t max_triangles = kDefaultMaxTriangles;
  // A scene whose triangles would need more than this many bytes to load
  // and build (kSceneBytesPerTriangle each) is refused as soon as they are
  // counted, before they are built. The default is the simulation's own
  // (kDefaultMemoryBudgetBytes, 2 GiB), which holds max_triangles.
  std::uint64_t memory_budget_bytes = std::uint64_t{2} << 30;
};

// What one triangle costs at the peak of loading a level and building what
// a simulation traces (welding, solids, the BVH, diffraction edges, the
// probe's copy): measured at 640 bytes with 2,000,000 scattered triangles
// (bench/RESULTS.md, hostile levels), rounded up.
inline constexpr std::uint64_t kSceneBytesPerTriangle = 700;

// Loads a .gltf or .glb file: every node of the default scene (or scene 0)
// with its transform composed, every triangle primitive (indexed or not, any
// index type; mode TRIANGLES, or TRIANGLE_STRIP / TRIANGLE_FAN), layers from
// node extras.acoustic_layer, else the material name, else "default"; sources
// from node extras.sound_source and KHR_audio_emitter positional emitters.
// Errors name the file and the problem: unreadable file, malformed glTF,
// missing buffer, index out of range, non-finite position, no triangle;
// and what `options` refuse: a buffer URI outside the rules, JSON nested
// deeper than 128 levels, more than max_triangles triangles, more than
// memory_budget_bytes to load and build them (LimitExceeded).
Result<Scene> load_scene(const std::filesystem::path& path, const SceneLoadOptions& options);
// load_scene with the default SceneLoadOptions.
Result<Scene> load_scene(const std::filesystem::path& path);

}  // namespace sp

SP_CPP_API_END
