// Tests of sp::load_scene. Small glTF files are built in code (GltfBuilder)
// so that every input sits next to the expectation derived from it by hand.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/vec3.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/glm_interop.h"
#include "soundpaint/scene.h"
#include "sp_types.h"
#include "support/gltf_builder.h"
#include "support/test_directory.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sp::test::GltfBuilder;
using sp::test::kFloat;
using sp::test::kU16;
using sp::test::kU32;
using sp::test::kU8;

constexpr float kTol = 1e-5f;

// Each test writes its files into its own directory, removed afterwards.
class SceneFile : public sp::test::TestDirectory {
 protected:
  sp::Scene load_ok(const fs::path& path) const {
    sp::Result<sp::Scene> scene = sp::load_scene(path);
    if (!scene) ADD_FAILURE() << scene.error().message;
    return scene ? std::move(scene).value() : sp::Scene{};
  }
};

void expect_vec3(const glm::vec3& actual, const glm::vec3& expected, const std::string& what) {
  EXPECT_NEAR(actual.x, expected.x, kTol) << what;
  EXPECT_NEAR(actual.y, expected.y, kTol) << what;
  EXPECT_NEAR(actual.z, expected.z, kTol) << what;
}

void expect_triangle(const sp::Scene& scene, std::size_t t, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  ASSERT_LT(3 * t + 2, scene.vertices.size());
  const std::string at = "triangle " + std::to_string(t);
  expect_vec3(scene.vertices[3 * t], a, at + " corner 0");
  expect_vec3(scene.vertices[3 * t + 1], b, at + " corner 1");
  expect_vec3(scene.vertices[3 * t + 2], c, at + " corner 2");
}

const double kHalfSqrt2 = std::sqrt(0.5);

// --- transforms -----------------------------------------------------------

// The unit triangle A=(1,0,0), B=(0,1,0), C=(0,0,1) under four nodes.
// Parent P: T(10,0,0) * Ry(90 deg) * S(2,1,1); Ry(90) maps (x,y,z) to (z,y,-x).
//   A: S->(2,0,0)  R->(0,0,-2)  T->(10,0,-2)
//   B: (0,1,0) -> (10,1,0);  C: (0,0,1) -> R (1,0,0) -> (11,0,0)
// Child Q of P: T(0,0,5), so world = P * T(0,0,5):
//   A: (1,0,5) S->(2,0,5) R->(5,0,-2) T->(15,0,-2);  B -> (15,1,0);  C: (0,0,6) -> (16,0,0)
// M (matrix, columns x->(0,2,0), y->(-1,0,0), z->(0,0,1), t=(3,4,5)):
//   A -> (3,6,5);  B -> (2,4,5);  C -> (3,4,6)
// N: S(-1,1,1) mirrors, so the corners are emitted A, C, B to keep the winding:
//   (-1,0,0), (0,0,1), (0,1,0)
TEST_F(SceneFile, ComposesNodeTransformsDepthFirst) {
  GltfBuilder b;
  const int mesh = b.unit_triangle_mesh();
  const int q = b.node({{"name", "Q"}, {"mesh", mesh}, {"translation", {0, 0, 5}}});
  const int p = b.node({{"name", "P"},
                        {"mesh", mesh},
                        {"children", {q}},
                        {"translation", {10, 0, 0}},
                        {"rotation", {0, kHalfSqrt2, 0, kHalfSqrt2}},
                        {"scale", {2, 1, 1}}});
  const int m = b.node({{"mesh", mesh}, {"matrix", {0, 2, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 3, 4, 5, 1}}});
  const int n = b.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
  b.root(p);
  b.root(m);
  b.root(n);
  const sp::Scene scene = load_ok(write("transforms.gltf", b.gltf()));
  ASSERT_EQ(scene.triangle_count(), 4u);
  ASSERT_EQ(scene.vertices.size(), 12u);
  expect_triangle(scene, 0, {10, 0, -2}, {10, 1, 0}, {11, 0, 0});
  expect_triangle(scene, 1, {15, 0, -2}, {15, 1, 0}, {16, 0, 0});
  expect_triangle(scene, 2, {3, 6, 5}, {2, 4, 5}, {3, 4, 6});
  expect_triangle(scene, 3, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0});
  EXPECT_EQ(scene.path, dir_ / "transforms.gltf");
  EXPECT_FALSE(scene.camera.has_value());
  EXPECT_TRUE(scene.sources.empty());
}

// --- primitives -------------------------------------------------------------

// Quad corners v0=(0,0,0) v1=(1,0,0) v2=(1,1,0) v3=(0,1,0), v4=(2,0,0).
TEST_F(SceneFile, ReadsEveryIndexTypeAndTriangleMode) {
  GltfBuilder b;
  const int pos = b.positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}});
  const int six = b.positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}});
  json prims = json::array();
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.indices<std::uint8_t>({0, 1, 2, 0, 2, 3}, kU8)}});
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.indices<std::uint16_t>({0, 1, 2}, kU16)}});
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"indices", b.indices<std::uint32_t>({2, 3, 0}, kU32)}});
  prims.push_back({{"attributes", {{"POSITION", six}}}});               // 2 triangles
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 5}});  // strip: 3
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 6}});  // fan: 3
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 0}});  // points: none
  prims.push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 1}});  // lines: none
  prims.push_back({{"attributes", {{"POSITION", pos}}},
                   {"mode", 5},
                   {"indices", b.indices<std::uint16_t>({3, 0, 2, 1}, kU16)}});  // strip: 2
  b.root(b.node({{"mesh", b.mesh(prims)}}));
  const sp::Scene scene = load_ok(write("modes.gltf", b.gltf()));
  ASSERT_EQ(scene.triangle_count(), 2u + 1 + 1 + 2 + 3 + 3 + 2);
  expect_triangle(scene, 1, {0, 0, 0}, {1, 1, 0}, {0, 1, 0});  // u8, second triangle
  expect_triangle(scene, 2, {0, 0, 0}, {1, 0, 0}, {1, 1, 0});  // u16
  expect_triangle(scene, 3, {1, 1, 0}, {0, 1, 0}, {0, 0, 0});  // u32
  expect_triangle(scene, 5, {0, 0, 1}, {1, 0, 1}, {1, 1, 1});  // unindexed, second
  // Strip triangle i = (v_i, v_{i+1+i%2}, v_{i+2-i%2}): i=1 -> v1, v3, v2.
  expect_triangle(scene, 7, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
  // Fan triangle i = (v_{i+1}, v_{i+2}, v_0): i=2 -> v3, v4, v0.
  expect_triangle(scene, 11, {0, 1, 0}, {2, 0, 0}, {0, 0, 0});
  // Indexed strip of indices (3,0,2,1): i=1 -> (idx[1], idx[3], idx[2]) = v0, v1, v2.
  expect_triangle(scene, 13, {0, 0, 0}, {1, 0, 0}, {1, 1, 0});
}

// --- layers -----------------------------------------------------------------

TEST_F(SceneFile, ResolvesLayersFromExtrasThenMaterialThenDefault) {
  GltfBuilder b;
  b.doc["materials"] = {{{"name", "brick"}}, {{"name", ""}}, {{"name", "glass"}}};
  const int brick_mesh = b.unit_triangle_mesh({{"material", 0}});
  const int mixed =
      b.mesh({{{"attributes", {{"POSITION", b.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}}}},
              {{"attributes", {{"POSITION", b.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}}}, {"material", 1}},
              {{"attributes", {{"POSITION", b.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}}}, {"material", 0}}});
  const int glass_mesh = b.unit_triangle_mesh({{"material", 2}});
  // The override names the node's own triangles only, not its children's.
  const int child = b.node({{"mesh", brick_mesh}});
  b.root(b.node({{"mesh", brick_mesh}, {"children", {child}}, {"extras", {{"acoustic_layer", "wood"}}}}));
  b.root(b.node({{"mesh", mixed}, {"extras", {{"unrelated", 1}}}}));
  b.root(b.node({{"mesh", glass_mesh}}));
  const sp::Scene scene = load_ok(write("layers.gltf", b.gltf()));
  const std::vector<std::string> names = {"wood", "brick", "default", "glass"};
  EXPECT_EQ(scene.layer_names, names);
  // wood (override), brick (child), default (no material), default (empty
  // name), brick (material 0), glass.
  const std::vector<std::uint32_t> layers = {0, 1, 2, 2, 1, 3};
  EXPECT_EQ(scene.triangle_layers, layers);
}

// --- sources and camera -------------------------------------------------------

// Node indices differ from traversal order on purpose: roots are [2, 0], and
// node 2 ("R1", at (1,2,3)) has children [1, 4].
TEST_F(SceneFile, ReadsSourcesAndFirstCameraInTraversalOrder) {
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_audio_emitter"};
  b.doc["extensions"]["KHR_audio_emitter"]["emitters"] = {
      {{"type", "global"}, {"gain", 0.2}},
      {{"type", "positional"}, {"name", "engine"}, {"gain", 0.75}, {"positional", {{"maxDistance", 40}}}}};
  b.doc["cameras"] = {
      {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}, {"zfar", 50}, {"aspectRatio", 1.5}}}},
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.2}}}}};
  const int mesh = b.unit_triangle_mesh();
  b.node({{"name", "R2"},
          {"mesh", mesh},
          {"translation", {-4, 0, 0}},
          {"extensions", {{"KHR_audio_emitter", {{"emitter", 1}}}}}});
  b.node({{"name", "C1"},
          {"translation", {0, 0, 1}},
          {"extras",
           {{"sound_source",
             {{"color", {1, 0, 0.5}},
              {"category", "voice"},
              {"max_distance", 12},
              {"loudness", 0.5},
              {"duration", 0.1},
              {"interval", 0.25},
              {"phase", 0.05}}}}}});
  b.node({{"name", "R1"},
          {"translation", {1, 2, 3}},
          {"children", {1, 4}},
          {"extras", {{"sound_source", json::object()}}}});
  b.node({{"name", "CamLate"}, {"camera", 1}});
  b.node({{"name", "CamFirst"},
          {"camera", 0},
          {"translation", {0, 1, 0}},
          {"rotation", {0, kHalfSqrt2, 0, kHalfSqrt2}},
          {"scale", {3, 3, 3}}});
  b.root(2);
  b.root(0);
  b.root(3);
  const sp::Scene scene = load_ok(write("sources.gltf", b.gltf()));

  ASSERT_EQ(scene.sources.size(), 3u);
  const sp::SourceDesc defaults;
  const sp::SourceDesc& r1 = scene.sources[0];
  EXPECT_EQ(r1.name, "R1");
  expect_vec3(r1.position, {1, 2, 3}, "R1 position");
  EXPECT_EQ(r1.category, defaults.category);
  EXPECT_EQ(r1.max_distance, defaults.max_distance);
  EXPECT_EQ(r1.interval, defaults.interval);

  const sp::SourceDesc& c1 = scene.sources[1];
  EXPECT_EQ(c1.name, "C1");
  expect_vec3(c1.position, {1, 2, 4}, "C1 position");
  ASSERT_TRUE(c1.color.has_value());
  expect_vec3(*c1.color, {1, 0, 0.5f}, "C1 color");
  EXPECT_FALSE(r1.color.has_value()) << "without a color, the category's palette colour";
  EXPECT_EQ(c1.category, "voice");
  EXPECT_FLOAT_EQ(c1.max_distance, 12.0f);
  EXPECT_FLOAT_EQ(c1.loudness, 0.5f);
  EXPECT_DOUBLE_EQ(c1.duration, 0.1);
  EXPECT_DOUBLE_EQ(c1.interval, 0.25);
  EXPECT_DOUBLE_EQ(c1.phase, 0.05);

  const sp::SourceDesc& r2 = scene.sources[2];
  EXPECT_EQ(r2.name, "R2");
  expect_vec3(r2.position, {-4, 0, 0}, "R2 position");
  EXPECT_EQ(r2.category, "engine");
  EXPECT_FLOAT_EQ(r2.loudness, 0.75f);
  EXPECT_FLOAT_EQ(r2.max_distance, 40.0f);

  // CamFirst: world = T(1,2,3) * T(0,1,0) * Ry(90) * S(3); the scale is dropped,
  // so the camera's +Z axis is Ry(90) * (0,0,1) = (1,0,0).
  ASSERT_TRUE(scene.camera.has_value());
  expect_vec3(scene.camera->position(), {1, 3, 3}, "camera position");
  expect_vec3(glm::vec3(sp::to_glm(scene.camera->world)[2]), {1, 0, 0}, "camera z axis");
  expect_vec3(glm::vec3(sp::to_glm(scene.camera->world)[0]), {0, 0, -1}, "camera x axis");
  EXPECT_FLOAT_EQ(scene.camera->yfov, 1.0f);
  EXPECT_FLOAT_EQ(scene.camera->znear, 0.1f);
  EXPECT_FLOAT_EQ(scene.camera->zfar, 50.0f);
  EXPECT_FLOAT_EQ(scene.camera->aspect_ratio, 1.5f);
}

// --- binary glTF ---------------------------------------------------------------

TEST_F(SceneFile, LoadsBinaryGltfByExtensionOrMagic) {
  GltfBuilder b;
  b.doc["materials"] = {{{"name", "metal"}}};
  b.root(b.node({{"mesh", b.unit_triangle_mesh({{"material", 0}})}, {"translation", {0, 0, -1}}}));
  for (const char* name : {"triangle.glb", "glb_named.gltf"}) {
    const sp::Scene scene = load_ok(write(name, b.glb()));
    ASSERT_EQ(scene.triangle_count(), 1u) << name;
    expect_triangle(scene, 0, {1, 0, -1}, {0, 1, -1}, {0, 0, 0});
    EXPECT_EQ(scene.layer_names, std::vector<std::string>{"metal"});
  }
}

// Geometry is all soundpaint needs: a texture that is missing must not fail.
TEST_F(SceneFile, IgnoresMissingTextures) {
  GltfBuilder b;
  b.doc["images"] = {{{"uri", "missing.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = {{{"name", "carpet"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.root(b.node({{"mesh", b.unit_triangle_mesh({{"material", 0}})}}));
  const sp::Scene scene = load_ok(write("textured.gltf", b.gltf()));
  EXPECT_EQ(scene.triangle_count(), 1u);
  EXPECT_EQ(scene.layer_names, std::vector<std::string>{"carpet"});
}

// Without a scene list every parentless node is a root, in index order: node
// 1 (at x=5) comes first, then its child node 0 (x=5+1), then node 2 (x=-7).
TEST_F(SceneFile, WithoutScenesVisitsParentlessNodes) {
  GltfBuilder b;
  const int mesh = b.unit_triangle_mesh();
  b.node({{"mesh", mesh}, {"translation", {1, 0, 0}}});
  b.node({{"mesh", mesh}, {"translation", {5, 0, 0}}, {"children", {0}}});
  b.node({{"mesh", mesh}, {"translation", {-7, 0, 0}}});
  b.doc.erase("scene");
  b.doc.erase("scenes");
  const sp::Scene scene = load_ok(write("no_scenes.gltf", b.gltf()));
  ASSERT_EQ(scene.triangle_count(), 3u);
  expect_vec3(scene.vertices[0], {6, 0, 0}, "node 1");
  expect_vec3(scene.vertices[3], {7, 0, 0}, "node 0");
  expect_vec3(scene.vertices[6], {-6, 0, 0}, "node 2");
}

// --- malformed files -------------------------------------------------------------

// A valid one-triangle file; each case below breaks one thing.
GltfBuilder valid_triangle() {
  GltfBuilder b;
  b.root(b.node({{"name", "Tri"}, {"mesh", b.unit_triangle_mesh()}}));
  return b;
}

struct BrokenCase {
  const char* name;
  std::function<std::vector<std::uint8_t>()> make;  // the file's bytes
  const char* expected;                             // part of the message
};

std::vector<std::uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

std::vector<std::uint8_t> gltf_with(const std::function<void(GltfBuilder&)>& edit) {
  GltfBuilder b = valid_triangle();
  edit(b);
  return bytes_of(b.gltf());
}

std::vector<std::uint8_t> with_source(json source) {
  return gltf_with([&](GltfBuilder& b) { b.doc["nodes"][0]["extras"]["sound_source"] = source; });
}

TEST_F(SceneFile, RejectsMalformedFilesWithTheirNameAndProblem) {
  const std::vector<BrokenCase> cases = {
      {"bad_json.gltf", [] { return bytes_of("{ \"asset\": { \"version\": \"2.0\" "); },
       "cannot load glTF: parse error at line 1"},
      {"truncated.glb",
       [] {
         std::vector<std::uint8_t> glb = valid_triangle().glb();
         glb.resize(glb.size() / 2);
         return glb;
       },
       "cannot load binary glTF"},
      {"missing_bin.gltf",
       [] {
         json d = valid_triangle().doc;
         d["buffers"] = {{{"byteLength", 36}, {"uri", "does_not_exist.bin"}}};
         return bytes_of(d.dump());
       },
       "does_not_exist.bin"},
      {"index_out_of_range.gltf",
       [] {
         return gltf_with([](GltfBuilder& b) {
           b.doc["meshes"][0]["primitives"][0]["indices"] = b.indices<std::uint16_t>({0, 1, 3}, kU16);
         });
       },
       "index 3 (element 2) is out of range for 3 vertices"},
      {"accessor_beyond_buffer.gltf",
       [] { return gltf_with([](GltfBuilder& b) { b.doc["accessors"][0]["count"] = 4; }); },
       "reaches beyond bufferView 0"},
      {"view_beyond_buffer.gltf",
       [] { return gltf_with([](GltfBuilder& b) { b.doc["bufferViews"][0]["byteLength"] = 400; }); },
       "lies outside buffer 0"},
      {"nan_vertex.gltf",
       [] {
         return gltf_with([](GltfBuilder& b) {
           const float nan = std::numeric_limits<float>::quiet_NaN();
           std::memcpy(b.bin.data() + 16, &nan, sizeof nan);  // vertex 1, y
         });
       },
       "vertex 1 is not finite"},
      {"no_triangles.gltf", [] { return gltf_with([](GltfBuilder& b) { b.doc["nodes"][0].erase("mesh"); }); },
       "no triangles"},
      {"only_points.gltf",
       [] { return gltf_with([](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 0; }); },
       "no triangles"},
      {"cycle.gltf",
       [] {
         return gltf_with([](GltfBuilder& b) {
           b.node({{"children", {0}}});
           b.doc["nodes"][0]["children"] = {1};
         });
       },
       "reached twice"},
      {"position_u16.gltf",
       [] { return gltf_with([](GltfBuilder& b) { b.doc["accessors"][0]["componentType"] = kU16; }); },
       "POSITION must be VEC3 of FLOAT"},
      {"sparse.gltf",
       [] {
         return gltf_with([](GltfBuilder& b) {
           b.doc["accessors"][0]["sparse"] = {
               {"count", 1}, {"indices", {{"bufferView", 0}, {"componentType", kU8}}}, {"values", {{"bufferView", 0}}}};
         });
       },
       "sparse accessors are not supported"},
      {"source_type.gltf",
       [] {
         return with_source({{"loudness", "loud"}});
       },
       "node 0 \"Tri\": key \"extras.sound_source.loudness\": must be a number >= 0"},
      {"source_color.gltf",
       [] {
         return with_source({{"color", {1, 2, 0}}});
       },
       "sound_source.color[1]"},
      {"source_interval.gltf",
       [] {
         return with_source({{"interval", 0}});
       },
       "sound_source.interval"},
      {"source_unknown.gltf",
       [] {
         return with_source({{"loudnes", 1}});
       },
       "unknown key"},
      {"source_position.gltf",
       [] {
         return with_source({{"position", {0, 0, 0}}});
       },
       "sound_source.position"},
      {"emitter_index.gltf",
       [] {
         return gltf_with([](GltfBuilder& b) {
           b.doc["extensions"]["KHR_audio_emitter"]["emitters"] = {{{"type", "positional"}}};
           b.doc["nodes"][0]["extensions"]["KHR_audio_emitter"]["emitter"] = 1;
         });
       },
       "extensions.KHR_audio_emitter.emitter"},
      {"bad_node_index.gltf", [] { return gltf_with([](GltfBuilder& b) { b.root(7); }); },
       "scene 0 lists node 7, which does not exist"},
  };
  for (const BrokenCase& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path path = write(c.name, c.make());
    const sp::Result<sp::Scene> scene = sp::load_scene(path);
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().code, sp::ErrorCode::InvalidScene);
    const std::string& message = scene.error().message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A small deterministic corpus (most useful under SOUNDPAINT_SANITIZE):
// every 8th truncation of a valid GLB and seeded byte overwrites must load
// or fail with a one-line message naming the file, never crash.
TEST_F(SceneFile, SurvivesTruncatedAndCorruptedBinaries) {
  const std::vector<std::uint8_t> glb = valid_triangle().glb();
  std::uint32_t state = 12345;
  auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  std::vector<std::vector<std::uint8_t>> corpus;
  for (std::size_t n = 0; n < glb.size(); n += 8) corpus.emplace_back(glb.begin(), glb.begin() + std::ptrdiff_t(n));
  for (int i = 0; i < 200; ++i) {
    std::vector<std::uint8_t> bytes = glb;
    for (int k = 0; k < 1 + i % 4; ++k) bytes[next() % bytes.size()] = static_cast<std::uint8_t>(next() >> 24);
    corpus.push_back(std::move(bytes));
  }
  for (std::size_t i = 0; i < corpus.size(); ++i) {
    // A new file per case: overwriting one file in place is slow on some filesystems.
    const fs::path path = write("corrupt_" + std::to_string(i) + ".glb", corpus[i]);
    const sp::Result<sp::Scene> scene = sp::load_scene(path);
    if (scene.ok()) continue;
    EXPECT_EQ(scene.error().message.rfind(path.string() + ": ", 0), 0u) << "case " << i;
    EXPECT_EQ(scene.error().message.find('\n'), std::string::npos) << "case " << i;
  }
}

TEST_F(SceneFile, RejectsMissingFilesAndEmptyFiles) {
  const fs::path missing = dir_ / "nowhere.gltf";
  const sp::Result<sp::Scene> scene = sp::load_scene(missing);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().message, missing.string() + ": file not found");
  const sp::Result<sp::Scene> empty = sp::load_scene(write("empty.glb", std::string()));
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().message.find("empty.glb: empty file"), std::string::npos);
}

// A level in another format gets "not a glTF 2.0 file", not a JSON parse
// position: a Quake 3 map (its "IBSP" header), an OBJ, a JSON array; a
// .gltf that is a JSON object still gets the parser's own message.
TEST_F(SceneFile, OtherFormatsAreNotGltf) {
  const std::string bsp = std::string("IBSP\x2e\0\0\0", 8) + std::string(64, '\0');
  for (const auto& [name, bytes] : {std::pair<std::string, std::string>{"oa_dm1.bsp", bsp},
                                    {"level.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
                                    {"array.gltf", "\xEF\xBB\xBF [1, 2]"}}) {
    const sp::Result<sp::Scene> scene = sp::load_scene(write(name, bytes));
    ASSERT_FALSE(scene.ok()) << name;
    EXPECT_NE(scene.error().message.find(name + ": not a glTF 2.0 file"), std::string::npos) << scene.error().message;
  }
  const sp::Result<sp::Scene> broken = sp::load_scene(write("broken.gltf", " {\"asset\": "));
  ASSERT_FALSE(broken.ok());
  EXPECT_EQ(broken.error().message.find("not a glTF 2.0 file"), std::string::npos) << broken.error().message;
}

// --- bundled scenes ----------------------------------------------------------------

bool has_layer(const sp::Scene& scene, const std::string& name) {
  return std::find(scene.layer_names.begin(), scene.layer_names.end(), name) != scene.layer_names.end();
}

// Facts fixed by scenes/generate_scenes.py.
TEST(BundledScenes, LoadWithTheirGeneratedContent) {
  struct Expected {
    const char* file;
    std::size_t min_triangles, max_triangles, sources;
    std::vector<std::string> layers;
  };
  const std::vector<Expected> scenes = {
      {"closed_room.gltf", 72, 200, 1, {"concrete"}},
      {"two_rooms.gltf", 100, 400, 1, {"concrete", "brick", "wood"}},
      {"level.gltf", 5000, 50000, 15, {"concrete", "brick", "wood", "glass", "metal", "carpet"}},
  };
  for (const Expected& e : scenes) {
    SCOPED_TRACE(e.file);
    sp::Result<sp::Scene> scene = sp::load_scene(fs::path(SP_SCENES_DIR) / e.file);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_GE(scene->triangle_count(), e.min_triangles);
    EXPECT_LE(scene->triangle_count(), e.max_triangles);
    EXPECT_EQ(scene->vertices.size(), 3 * scene->triangle_count());
    EXPECT_EQ(scene->sources.size(), e.sources);
    EXPECT_TRUE(scene->camera.has_value());
    for (const std::string& layer : e.layers) EXPECT_TRUE(has_layer(*scene, layer)) << layer;
    EXPECT_FALSE(has_layer(*scene, "default"));
  }
}

TEST(BundledScenes, PlaceSourcesAndListenersAsGenerated) {
  sp::Result<sp::Scene> two = sp::load_scene(fs::path(SP_SCENES_DIR) / "two_rooms.gltf");
  ASSERT_TRUE(two.ok()) << two.error().message;
  ASSERT_EQ(two->sources.size(), 1u);
  EXPECT_GT(two->sources[0].position.x, 0.05f);  // room B, beyond the divider at |x| <= 0.05
  ASSERT_TRUE(two->camera.has_value());
  EXPECT_LT(two->camera->position().x, -0.05f);  // room A
  EXPECT_GT(-two->camera->world[2][0], 0.5f);    // looking towards +x, the divider
  EXPECT_NEAR(glm::length(glm::vec3(sp::to_glm(two->camera->world)[0])), 1.0f, 1e-5f);

  // The paper's benchmark: 15 sources, each sounding 0.1 s every 0.25 s.
  sp::Result<sp::Scene> level = sp::load_scene(fs::path(SP_SCENES_DIR) / "level.gltf");
  ASSERT_TRUE(level.ok()) << level.error().message;
  for (const sp::SourceDesc& source : level->sources) {
    SCOPED_TRACE(source.name);
    EXPECT_DOUBLE_EQ(source.interval, 0.25);
    EXPECT_DOUBLE_EQ(source.duration, 0.1);
    EXPECT_FLOAT_EQ(source.max_distance, 25.0f);
    EXPECT_TRUE(source.position.x > 0 && source.position.x < 36 && source.position.z > 0 && source.position.z < 24);
    EXPECT_TRUE(source.position.y > 0 && source.position.y < 3.2f);
  }
}

// The generator writes the closed room twice; its GLB writer is independent
// of the test's, so this checks the binary path against another encoder.
TEST(BundledScenes, BinaryAndJsonClosedRoomsMatch) {
  sp::Result<sp::Scene> json_room = sp::load_scene(fs::path(SP_SCENES_DIR) / "closed_room.gltf");
  sp::Result<sp::Scene> glb_room = sp::load_scene(fs::path(SP_SCENES_DIR) / "closed_room.glb");
  ASSERT_TRUE(json_room.ok()) << json_room.error().message;
  ASSERT_TRUE(glb_room.ok()) << glb_room.error().message;
  EXPECT_EQ(glb_room->vertices, json_room->vertices);
  EXPECT_EQ(glb_room->triangle_layers, json_room->triangle_layers);
  EXPECT_EQ(glb_room->layer_names, json_room->layer_names);
  ASSERT_EQ(glb_room->sources.size(), 1u);
  EXPECT_EQ(glb_room->sources[0].position, json_room->sources[0].position);
}

}  // namespace
