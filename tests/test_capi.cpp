// The C API: every misuse returns an error code and a message instead of
// crashing (NULL and destroyed handles included), hand-derived scenes built
// from arrays give the expected indicators, and sources added, moved,
// removed and emitted at run time show up (or stop) where derived.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "soundpaint/soundpaint.h"
#include "soundpaint/soundpaint_vulkan.h"
#include "sp_random.h"

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::string last_error() { return sp_last_error_message(); }

// A big quad on the plane z = 1: |x|, |y| <= kHalf, its front (counter-
// clockwise side) towards the source at the origin, as a wall's is.
constexpr float kHalf = 10.0f;
const std::vector<float> kQuad = {
    -kHalf, -kHalf, 1.0f, -kHalf, kHalf, 1.0f, kHalf, kHalf,  1.0f,  //
    -kHalf, -kHalf, 1.0f, kHalf,  kHalf, 1.0f, kHalf, -kHalf, 1.0f,  //
};
const std::vector<std::uint32_t> kQuadLayers = {0, 0};
const char* const kLayerNames[] = {"concrete"};

// A source at the origin, the listener on it, the quad 1 m in front (+z).
const char* const kQuadConfig = R"({
  "ray_budget": 64, "max_bounces": 0, "air_attenuation": 0, "seed": 3,
  "listener": { "position": [0, 0, 0] },
  "sources": [ { "position": [0, 0, 0], "loudness": 1.0 } ]
})";

sp_scene* make_quad_scene() {
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, &scene), SP_OK) << last_error();
  return scene;
}

// A CPU simulation of the quad scene, destroyed with the fixture.
class CapiSimulation : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = make_quad_scene();
    ASSERT_NE(scene_, nullptr);
    ASSERT_EQ(sp_simulation_create(scene_, kQuadConfig, SP_BACKEND_CPU, &sim_), SP_OK) << last_error();
  }
  void TearDown() override {
    sp_simulation_destroy(sim_);
    sp_scene_destroy(scene_);
  }
  sp_scene* scene_ = nullptr;
  sp_simulation* sim_ = nullptr;
};

TEST(CapiScene, LoadRejectsNullArguments) {
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_load(nullptr, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("path"), std::string::npos) << last_error();
  EXPECT_EQ(sp_scene_load(SP_SCENES_DIR "/closed_room.gltf", nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(scene, nullptr);
}

TEST(CapiScene, MissingFileNamesThePath) {
  sp_scene* scene = nullptr;
  const char* path = SP_SCENES_DIR "/does_not_exist.gltf";
  sp_result r = sp_scene_load(path, &scene);
  EXPECT_TRUE(r == SP_ERROR_INVALID_SCENE || r == SP_ERROR_IO) << r;
  EXPECT_NE(last_error().find("does_not_exist.gltf"), std::string::npos) << last_error();
  EXPECT_EQ(scene, nullptr);
}

TEST(CapiScene, LoadsTheBundledRoom) {
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_load(SP_SCENES_DIR "/closed_room.gltf", &scene), SP_OK) << last_error();
  EXPECT_NE(scene, nullptr);
  sp_scene_destroy(scene);
}

TEST(CapiScene, CreateRejectsNullPointersAndZeroCounts) {
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_create(nullptr, 2, kQuadLayers.data(), kLayerNames, 1, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, nullptr, kLayerNames, 1, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers.data(), nullptr, 1, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_scene_create(kQuad.data(), 0, kQuadLayers.data(), kLayerNames, 1, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("triangle_count"), std::string::npos) << last_error();
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 0, &scene), SP_ERROR_INVALID_ARGUMENT);
  const char* const null_name[] = {nullptr};
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers.data(), null_name, 1, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("layer_names[0]"), std::string::npos) << last_error();
  EXPECT_EQ(scene, nullptr);
}

TEST(CapiScene, CreateRejectsNonFiniteVertices) {
  for (float bad : {kNan, kInf, -kInf}) {
    std::vector<float> vertices = kQuad;
    vertices[13] = bad;  // triangle 1, vertex 4, y
    sp_scene* scene = nullptr;
    EXPECT_EQ(sp_scene_create(vertices.data(), 2, kQuadLayers.data(), kLayerNames, 1, &scene), SP_ERROR_INVALID_SCENE);
    EXPECT_NE(last_error().find("vertex 4"), std::string::npos) << last_error();
    EXPECT_EQ(scene, nullptr);
  }
}

TEST(CapiScene, CreateRejectsLayerIdsOutOfRange) {
  const std::vector<std::uint32_t> layers = {0, 1};
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, layers.data(), kLayerNames, 1, &scene), SP_ERROR_INVALID_SCENE);
  EXPECT_NE(last_error().find("triangle 1 has layer id 1"), std::string::npos) << last_error();
  EXPECT_EQ(scene, nullptr);
}

TEST(CapiScene, DestroyNullIsANoOp) {
  EXPECT_EQ(sp_scene_destroy(nullptr), SP_OK);
  EXPECT_EQ(sp_simulation_destroy(nullptr), SP_OK);
  EXPECT_EQ(sp_visualizer_destroy(nullptr), SP_OK);
}

TEST(CapiSimulationCreate, RejectsNullArgumentsAndUnknownBackends) {
  sp_scene* scene = make_quad_scene();
  ASSERT_NE(scene, nullptr);
  sp_simulation* sim = nullptr;
  EXPECT_EQ(sp_simulation_create(nullptr, kQuadConfig, SP_BACKEND_CPU, &sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_create(scene, kQuadConfig, SP_BACKEND_CPU, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_create(scene, kQuadConfig, static_cast<sp_backend>(3), &sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("backend"), std::string::npos) << last_error();
  EXPECT_EQ(sim, nullptr);
  sp_scene_destroy(scene);
}

TEST(CapiSimulationCreate, BadConfigNamesTheKey) {
  sp_scene* scene = make_quad_scene();
  ASSERT_NE(scene, nullptr);
  sp_simulation* sim = nullptr;
  EXPECT_EQ(sp_simulation_create(scene, R"({ "listener": { "position": [0, 0, 0] }, "ray_budget": -5 })",
                                 SP_BACKEND_CPU, &sim),
            SP_ERROR_INVALID_CONFIG);
  EXPECT_NE(last_error().find("ray_budget"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_create(scene, "{ not json", SP_BACKEND_CPU, &sim), SP_ERROR_INVALID_CONFIG);
  EXPECT_EQ(sim, nullptr);
  sp_scene_destroy(scene);
}

TEST(CapiSimulationCreate, NoListenerIsAnError) {
  sp_scene* scene = make_quad_scene();  // no camera
  ASSERT_NE(scene, nullptr);
  sp_simulation* sim = nullptr;
  EXPECT_EQ(sp_simulation_create(scene, nullptr, SP_BACKEND_CPU, &sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("listener"), std::string::npos) << last_error();
  EXPECT_EQ(sim, nullptr);
  sp_scene_destroy(scene);
}

TEST(CapiNullHandles, EveryFunctionRejectsThem) {
  std::uint32_t count = 0;
  sp_stats stats{};
  sp_indicator indicator{};
  EXPECT_EQ(sp_simulation_set_listener(nullptr, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(nullptr, 0, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_step(nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_source_count(nullptr, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_live_indicators(nullptr, &indicator, 1, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_stats(nullptr, &stats), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_simulation_stats"), std::string::npos) << last_error();
}

TEST_F(CapiSimulation, RejectsNullOutPointers) {
  sp_indicator indicator{};
  EXPECT_EQ(sp_simulation_source_count(sim_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_stats(sim_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_live_indicators(sim_, &indicator, 1, nullptr), SP_ERROR_INVALID_ARGUMENT);
  std::uint32_t count = 99;
  EXPECT_EQ(sp_simulation_live_indicators(sim_, nullptr, 1, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(count, 99u);
  EXPECT_EQ(sp_simulation_live_indicators(sim_, nullptr, 0, &count), SP_OK) << last_error();
  EXPECT_EQ(count, 0u);
}

TEST_F(CapiSimulation, RejectsNonFiniteListener) {
  EXPECT_EQ(sp_simulation_set_listener(sim_, kNan, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_set_listener(sim_, 0, kInf, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_set_listener(sim_, 0, 0, -kInf), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("not finite"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_set_listener(sim_, 1, 2, 3), SP_OK) << last_error();
}

TEST_F(CapiSimulation, PlayChecksSourceAndDuration) {
  std::uint32_t sources = 0;
  ASSERT_EQ(sp_simulation_source_count(sim_, &sources), SP_OK);
  EXPECT_EQ(sources, 1u);
  EXPECT_EQ(sp_simulation_play(sim_, 1, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("unknown source id 1"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_play(sim_, 0xFFFFFFFFu, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(sim_, 0, -1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(sim_, 0, std::numeric_limits<double>::quiet_NaN()), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(sim_, 0, std::numeric_limits<double>::infinity()), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(sim_, 0, 0.5), SP_OK) << last_error();
}

// Hand-derived: with no bounces and no air loss, one step's indicators are
// exactly the emitted rays whose direction reaches the quad (z = 1, |x|, |y|
// <= 10) within the source's max_distance (30 m), each on the plane with the
// source's full loudness.
TEST_F(CapiSimulation, QuadInFrontOfTheSourceCatchesTheRaysHeadingToIt) {
  ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error();

  std::uint32_t expected = 0;
  for (std::uint32_t ray = 0; ray < 64; ++ray) {
    const glm::vec3 dir = sp::shader::sp_emission_direction(3u, 0u, ray);
    if (!(dir.z > 0.0f)) continue;
    const float t = 1.0f / dir.z;
    if (t <= 30.0f && std::fabs(dir.x * t) <= kHalf && std::fabs(dir.y * t) <= kHalf) ++expected;
  }
  ASSERT_GT(expected, 0u);
  ASSERT_LT(expected, 64u);

  std::uint32_t count = 0;
  ASSERT_EQ(sp_simulation_live_indicators(sim_, nullptr, 0, &count), SP_OK) << last_error();
  EXPECT_EQ(count, expected);
  std::vector<sp_indicator> live(count + 1);
  std::uint32_t again = 0;
  ASSERT_EQ(sp_simulation_live_indicators(sim_, live.data(), count + 1, &again), SP_OK) << last_error();
  EXPECT_EQ(again, count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const sp_indicator& ind = live[i];
    EXPECT_NEAR(ind.position[2], 1.0f, 1e-5f) << i;
    EXPECT_LE(std::fabs(ind.position[0]), kHalf + 1e-4f) << i;
    EXPECT_LE(std::fabs(ind.position[1]), kHalf + 1e-4f) << i;
    EXPECT_EQ(ind.energy, 1.0f) << i;
    EXPECT_EQ(ind.normal[2], -1.0f) << i;  // facing the source
    EXPECT_EQ(ind.kind, SP_INDICATOR_KIND_HIT) << i;
    EXPECT_EQ(ind.source_id, 0u) << i;
    EXPECT_EQ(ind.bounces, 0u) << i;
    EXPECT_EQ(ind.step, 0u) << i;
    // A ray from the origin: its direction is its hit point, normalised.
    const float len = std::sqrt(ind.position[0] * ind.position[0] + ind.position[1] * ind.position[1] + 1.0f);
    EXPECT_NEAR(ind.direction[0], ind.position[0] / len, 1e-5f) << i;
    EXPECT_NEAR(ind.direction[2], 1.0f / len, 1e-5f) << i;
    EXPECT_EQ(ind.diffractions, 0u) << i;
    EXPECT_EQ(ind.intensity, 1.0f) << i;  // listener on the source
  }
  // A smaller capacity writes a prefix and still reports the full count.
  std::vector<sp_indicator> prefix(1);
  ASSERT_EQ(sp_simulation_live_indicators(sim_, prefix.data(), 1, &again), SP_OK);
  EXPECT_EQ(again, count);
  EXPECT_EQ(prefix[0].position[0], live[0].position[0]);

  sp_stats stats{};
  ASSERT_EQ(sp_simulation_stats(sim_, &stats), SP_OK) << last_error();
  EXPECT_EQ(stats.steps, 1u);
  EXPECT_EQ(stats.rays_emitted, 64u);
  EXPECT_EQ(stats.casts, 64u);  // one forward cast per ray, no bounces
  EXPECT_EQ(stats.indicators, count);
}

// --- Run-time scene controls -------------------------------------------

// A closed box room |x| <= 4, 0 <= y <= 3, |z| <= 5 from host arrays: every
// ray from inside first hits a wall, at the box exit point along its
// direction (all metres).
constexpr float kRoomMin[3] = {-4.0f, 0.0f, -5.0f};
constexpr float kRoomMax[3] = {4.0f, 3.0f, 5.0f};
const float kRoomDiagonal = std::sqrt(8.0f * 8.0f + 3.0f * 3.0f + 10.0f * 10.0f);
constexpr std::uint32_t kRoomRays = 48;
constexpr std::uint32_t kRoomSeed = 11;

// No sources: the tests add them. dt 0.1 s keeps step times readable; with
// no bounces and no air loss each ray makes exactly one hit indicator.
// Every ray goes out uniformly (no guide), so that the hits of every step
// are those the emission function predicts.
const char* const kRoomConfig = R"({
  "ray_budget": 48, "max_bounces": 0, "air_attenuation": 0, "seed": 11, "dt": 0.1,
  "listener": { "position": [0, 1.5, 0] }, "cues": { "guide_share": 0 }
})";

// Two triangles per face, six faces, one layer; every face's front towards
// the inside of the room, where the air is.
std::vector<float> room_vertices() {
  std::vector<float> v;
  auto corner = [](int ix, int iy, int iz) {
    return std::vector<float>{ix ? kRoomMax[0] : kRoomMin[0], iy ? kRoomMax[1] : kRoomMin[1],
                              iz ? kRoomMax[2] : kRoomMin[2]};
  };
  auto quad = [&](std::vector<float> a, std::vector<float> b, std::vector<float> c, std::vector<float> d) {
    for (const auto* p : {&a, &b, &c, &a, &c, &d}) v.insert(v.end(), p->begin(), p->end());
  };
  quad(corner(0, 0, 0), corner(0, 1, 0), corner(0, 1, 1), corner(0, 0, 1));  // x = min
  quad(corner(1, 0, 0), corner(1, 0, 1), corner(1, 1, 1), corner(1, 1, 0));  // x = max
  quad(corner(0, 0, 0), corner(0, 0, 1), corner(1, 0, 1), corner(1, 0, 0));  // y = min
  quad(corner(0, 1, 0), corner(1, 1, 0), corner(1, 1, 1), corner(0, 1, 1));  // y = max
  quad(corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(0, 1, 0));  // z = min
  quad(corner(0, 0, 1), corner(0, 1, 1), corner(1, 1, 1), corner(1, 0, 1));  // z = max
  return v;
}

// Where the ray from `p` (inside the room) along `dir` leaves the box.
glm::vec3 room_exit(glm::vec3 p, glm::vec3 dir) {
  float t = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] > 0.0f) t = std::min(t, (kRoomMax[a] - p[a]) / dir[a]);
    if (dir[a] < 0.0f) t = std::min(t, (kRoomMin[a] - p[a]) / dir[a]);
  }
  return p + t * dir;
}

// The first hits of step `step`'s rays from a lone source at `p`.
std::vector<glm::vec3> expected_hits(glm::vec3 p, std::uint32_t step) {
  std::vector<glm::vec3> hits;
  for (std::uint32_t ray = 0; ray < kRoomRays; ++ray)
    hits.push_back(room_exit(p, sp::shader::sp_emission_direction(kRoomSeed, step, ray)));
  return hits;
}

glm::vec3 position_of(const sp_indicator& ind) { return {ind.position[0], ind.position[1], ind.position[2]}; }

// On one of the six wall planes, inside the box's bounds.
bool on_room_wall(glm::vec3 q) {
  constexpr float kTol = 1e-3f;
  bool on_plane = false;
  for (int a = 0; a < 3; ++a) {
    if (q[a] < kRoomMin[a] - kTol || q[a] > kRoomMax[a] + kTol) return false;
    on_plane = on_plane || std::fabs(q[a] - kRoomMin[a]) < kTol || std::fabs(q[a] - kRoomMax[a]) < kTol;
  }
  return on_plane;
}

bool near_any(glm::vec3 q, const std::vector<glm::vec3>& points) {
  for (const glm::vec3& p : points)
    if (glm::distance(p, q) < 2e-3f) return true;
  return false;
}

std::vector<sp_indicator> live_indicators(sp_simulation* sim) {
  std::uint32_t count = 0;
  EXPECT_EQ(sp_simulation_live_indicators(sim, nullptr, 0, &count), SP_OK) << last_error();
  std::vector<sp_indicator> live(count);
  EXPECT_EQ(sp_simulation_live_indicators(sim, live.data(), count, &count), SP_OK) << last_error();
  live.resize(count);
  return live;
}

// The live indicators of one step (and, when given, one source).
std::vector<sp_indicator> of_step(sp_simulation* sim, std::uint32_t step,
                                  std::uint32_t source = std::numeric_limits<std::uint32_t>::max()) {
  std::vector<sp_indicator> out;
  for (const sp_indicator& ind : live_indicators(sim))
    if (ind.step == step && (source == std::numeric_limits<std::uint32_t>::max() || ind.source_id == source))
      out.push_back(ind);
  return out;
}

sp_source_desc source_at(float x, float y, float z, float r = 1.0f, float g = 1.0f, float b = 1.0f) {
  sp_source_desc desc;
  sp_source_desc_init(&desc);
  desc.position[0] = x;
  desc.position[1] = y;
  desc.position[2] = z;
  desc.color[0] = r;
  desc.color[1] = g;
  desc.color[2] = b;
  return desc;
}

// A CPU simulation of the room with no sources, and its sound scene.
class CapiRoom : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::vector<float> vertices = room_vertices();
    const std::vector<std::uint32_t> layers(12, 0);
    ASSERT_EQ(sp_scene_create(vertices.data(), 12, layers.data(), kLayerNames, 1, &scene_), SP_OK) << last_error();
    ASSERT_EQ(sp_simulation_create(scene_, kRoomConfig, SP_BACKEND_CPU, &sim_), SP_OK) << last_error();
    ASSERT_EQ(sp_simulation_scene(sim_, &sound_), SP_OK) << last_error();
  }
  void TearDown() override {
    EXPECT_EQ(sp_simulation_destroy(sim_), SP_OK);
    EXPECT_EQ(sp_scene_destroy(scene_), SP_OK);
  }
  void step() { ASSERT_EQ(sp_simulation_step(sim_), SP_OK) << last_error(); }
  std::uint32_t add(const sp_source_desc& desc) {
    std::uint32_t id = 12345;
    EXPECT_EQ(sp_sound_scene_add_source(sound_, &desc, &id), SP_OK) << last_error();
    return id;
  }
  bool has(std::uint32_t id) {
    int out = -1;
    EXPECT_EQ(sp_sound_scene_has_source(sound_, id, &out), SP_OK) << last_error();
    return out == 1;
  }

  sp_scene* scene_ = nullptr;
  sp_simulation* sim_ = nullptr;
  sp_sound_scene* sound_ = nullptr;
};

TEST(CapiSourceDesc, InitGivesTheLibraryDefaults) {
  sp_source_desc desc;
  std::memset(&desc, 0x7f, sizeof desc);
  sp_source_desc_init(&desc);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(desc.position[k], 0.0f);
    EXPECT_EQ(desc.color[k], -1.0f);  // no colour of its own: its category's palette colour
  }
  EXPECT_EQ(desc.category, nullptr);  // "sound"
  EXPECT_EQ(desc.max_distance, 30.0f);
  EXPECT_EQ(desc.loudness, 1.0f);
  EXPECT_EQ(desc.duration, 1.0);
  EXPECT_EQ(desc.interval, 1.0);
  EXPECT_EQ(desc.phase, 0.0);
  sp_source_desc_init(nullptr);  // no-op
}

TEST_F(CapiRoom, TheSceneHandleIsStableAndStartsEmpty) {
  sp_sound_scene* again = nullptr;
  ASSERT_EQ(sp_simulation_scene(sim_, &again), SP_OK);
  EXPECT_EQ(again, sound_);
  std::uint32_t value = 99;
  ASSERT_EQ(sp_simulation_source_count(sim_, &value), SP_OK);
  EXPECT_EQ(value, 0u);
  ASSERT_EQ(sp_sound_scene_instance_count(sound_, &value), SP_OK);
  EXPECT_EQ(value, 0u);
  ASSERT_EQ(sp_sound_scene_source_capacity(sound_, &value), SP_OK);
  EXPECT_EQ(value, 1024u);
  EXPECT_FALSE(has(0));
  step();
  EXPECT_TRUE(live_indicators(sim_).empty());
}

// Hand-derived: the added source is the only one, so it gets every ray of
// the step, and each ray's one indicator is where its direction leaves the
// box, in the source's colour and id.
TEST_F(CapiRoom, AddedSourceLightsTheWallsWhereItsRaysLeaveTheRoom) {
  const glm::vec3 p(1.0f, 1.0f, 2.0f);
  std::string category = "footsteps";
  sp_source_desc desc = source_at(p.x, p.y, p.z, 0.2f, 0.4f, 0.6f);
  desc.category = category.c_str();
  const std::uint32_t id = add(desc);
  EXPECT_EQ(id, 0u);
  category.assign(64, 'x');  // the library copied the text
  EXPECT_TRUE(has(id));
  step();

  const std::vector<sp_indicator> hits = of_step(sim_, 0);
  ASSERT_EQ(hits.size(), kRoomRays);
  const std::vector<glm::vec3> expected = expected_hits(p, 0);
  const float intensity = 1.0f - glm::distance(glm::vec3(0.0f, 1.5f, 0.0f), p) / 30.0f;
  for (const sp_indicator& ind : hits) {
    const glm::vec3 q = position_of(ind);
    EXPECT_EQ(ind.source_id, id);
    EXPECT_EQ(ind.color[0], 0.2f);
    EXPECT_EQ(ind.color[1], 0.4f);
    EXPECT_EQ(ind.color[2], 0.6f);
    EXPECT_EQ(ind.kind, SP_INDICATOR_KIND_HIT);
    EXPECT_NEAR(ind.intensity, intensity, 1e-5f);
    EXPECT_TRUE(on_room_wall(q)) << q.x << " " << q.y << " " << q.z;
    EXPECT_LT(glm::distance(p, q), kRoomDiagonal);
    EXPECT_NEAR(ind.path_length, glm::distance(p, q), 1e-3f);
    EXPECT_TRUE(near_any(q, expected)) << q.x << " " << q.y << " " << q.z;
  }
}

TEST_F(CapiRoom, MovedSourceHitsTheWallsFromItsNewPlace) {
  const glm::vec3 p(1.0f, 1.0f, 2.0f);
  const glm::vec3 q(-3.0f, 2.5f, -4.0f);
  const std::uint32_t id = add(source_at(p.x, p.y, p.z));
  step();
  ASSERT_EQ(sp_sound_scene_move_source(sound_, id, q.x, q.y, q.z), SP_OK) << last_error();
  step();

  const std::vector<glm::vec3> from_p = expected_hits(p, 1);
  const std::vector<glm::vec3> from_q = expected_hits(q, 1);
  const std::vector<sp_indicator> hits = of_step(sim_, 1);
  ASSERT_EQ(hits.size(), kRoomRays);
  std::uint32_t also_from_p = 0;
  for (const sp_indicator& ind : hits) {
    const glm::vec3 hit = position_of(ind);
    EXPECT_TRUE(on_room_wall(hit));
    EXPECT_NEAR(ind.path_length, glm::distance(q, hit), 1e-3f);
    EXPECT_TRUE(near_any(hit, from_q)) << hit.x << " " << hit.y << " " << hit.z;
    if (near_any(hit, from_p)) ++also_from_p;
  }
  EXPECT_LT(also_from_p, kRoomRays / 4);  // the hits really moved
  // Step 0's indicators stay where the source was then.
  for (const sp_indicator& ind : of_step(sim_, 0)) EXPECT_TRUE(near_any(position_of(ind), expected_hits(p, 0)));
}

TEST_F(CapiRoom, RemovedSourceMakesNoMoreIndicators) {
  const std::uint32_t a = add(source_at(1.0f, 1.0f, 2.0f, 1.0f, 0.0f, 0.0f));
  const std::uint32_t b = add(source_at(-1.0f, 2.0f, -2.0f, 0.0f, 0.0f, 1.0f));
  EXPECT_EQ(a, 0u);
  EXPECT_EQ(b, 1u);
  step();
  EXPECT_EQ(of_step(sim_, 0, a).size(), kRoomRays / 2);
  EXPECT_EQ(of_step(sim_, 0, b).size(), kRoomRays / 2);

  ASSERT_EQ(sp_sound_scene_remove_source(sound_, a), SP_OK) << last_error();
  EXPECT_FALSE(has(a));
  EXPECT_TRUE(has(b));
  for (int k = 0; k < 3; ++k) step();
  for (std::uint32_t s = 1; s <= 3; ++s) {
    EXPECT_TRUE(of_step(sim_, s, a).empty()) << s;
    EXPECT_EQ(of_step(sim_, s, b).size(), kRoomRays) << s;  // b now has the whole budget
  }
  EXPECT_EQ(of_step(sim_, 0, a).size(), kRoomRays / 2);  // drawn ones fade as usual

  // The freed slot is reused by the next add; removing twice is an error.
  EXPECT_EQ(sp_sound_scene_remove_source(sound_, a), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("source 0 was removed"), std::string::npos) << last_error();
  EXPECT_EQ(add(source_at(0.0f, 1.0f, 0.0f)), a);
}

// emit plays for its duration from the next step, then frees its id. With
// dt = 0.1 s a 0.25 s one-shot emitted after step 1 sounds at steps 1, 2, 3.
TEST_F(CapiRoom, EmittedOneShotStopsAfterItsDuration) {
  step();  // step 0, nothing plays
  sp_source_desc desc = source_at(2.0f, 1.0f, -1.0f, 0.0f, 1.0f, 0.0f);
  desc.duration = 0.0;  // ignored by emit, like interval and phase
  desc.interval = 1e-3;
  desc.phase = 100.0;
  std::uint32_t id = 99;
  ASSERT_EQ(sp_sound_scene_emit(sound_, &desc, 0.25, &id), SP_OK) << last_error();
  EXPECT_EQ(id, 0u);
  EXPECT_TRUE(has(id));
  for (int k = 0; k < 5; ++k) step();  // steps 1 .. 5
  EXPECT_TRUE(of_step(sim_, 0).empty());
  for (std::uint32_t s = 1; s <= 3; ++s) {
    const std::vector<sp_indicator> hits = of_step(sim_, s, id);
    EXPECT_EQ(hits.size(), kRoomRays) << s;
    for (const sp_indicator& ind : hits) EXPECT_EQ(ind.color[1], 1.0f);
  }
  EXPECT_TRUE(of_step(sim_, 4).empty());
  EXPECT_TRUE(of_step(sim_, 5).empty());
  EXPECT_FALSE(has(id));
  EXPECT_EQ(sp_sound_scene_move_source(sound_, id, 0, 1, 0), SP_ERROR_INVALID_ARGUMENT);
}

TEST_F(CapiRoom, PlayMakesASilentSourceSoundForItsWindow) {
  sp_source_desc desc = source_at(0.0f, 1.0f, 1.0f);
  desc.duration = 0.0;  // silent by pattern
  const std::uint32_t id = add(desc);
  step();                                                                   // step 0: silent
  ASSERT_EQ(sp_sound_scene_play(sound_, id, 0.15), SP_OK) << last_error();  // [0.1, 0.25)
  for (int k = 0; k < 3; ++k) step();
  EXPECT_TRUE(of_step(sim_, 0).empty());
  EXPECT_EQ(of_step(sim_, 1).size(), kRoomRays);
  EXPECT_EQ(of_step(sim_, 2).size(), kRoomRays);
  EXPECT_TRUE(of_step(sim_, 3).empty());
  // The simulation's shorthand reaches sources added at run time too.
  ASSERT_EQ(sp_simulation_play(sim_, id, 0.05), SP_OK) << last_error();
  step();
  EXPECT_EQ(of_step(sim_, 4).size(), kRoomRays);
}

TEST_F(CapiRoom, UpdateSourceReplacesColourAndPlace) {
  const std::uint32_t id = add(source_at(1.0f, 1.0f, 1.0f, 1.0f, 0.0f, 0.0f));
  const glm::vec3 p(-2.0f, 0.5f, 3.0f);
  const sp_source_desc changed = source_at(p.x, p.y, p.z, 0.0f, 0.5f, 1.0f);
  ASSERT_EQ(sp_sound_scene_update_source(sound_, id, &changed), SP_OK) << last_error();
  step();
  const std::vector<sp_indicator> hits = of_step(sim_, 0, id);
  ASSERT_EQ(hits.size(), kRoomRays);
  const std::vector<glm::vec3> expected = expected_hits(p, 0);
  for (const sp_indicator& ind : hits) {
    EXPECT_EQ(ind.color[0], 0.0f);
    EXPECT_EQ(ind.color[1], 0.5f);
    EXPECT_TRUE(near_any(position_of(ind), expected));
  }
}

// max_distance is both the listener's range and the rays' reach.
TEST_F(CapiRoom, ListenerOutOfRangeSilencesTheSource) {
  const glm::vec3 p(3.0f, 1.0f, 4.0f);
  sp_source_desc desc = source_at(p.x, p.y, p.z);
  desc.max_distance = 5.0f;
  add(desc);
  ASSERT_EQ(sp_sound_scene_set_listener(sound_, -3.0f, 1.0f, -4.0f), SP_OK) << last_error();  // 10 m away
  step();
  EXPECT_TRUE(of_step(sim_, 0).empty());
  ASSERT_EQ(sp_simulation_set_listener(sim_, 3.0f, 1.0f, 3.0f), SP_OK) << last_error();  // the old entry point
  step();
  std::size_t reachable = 0;
  for (const glm::vec3& hit : expected_hits(p, 1)) reachable += glm::distance(p, hit) <= 5.0f ? 1 : 0;
  ASSERT_GT(reachable, 0u);
  ASSERT_LT(reachable, kRoomRays);
  const std::vector<sp_indicator> hits = of_step(sim_, 1);
  EXPECT_EQ(hits.size(), reachable);
  for (const sp_indicator& ind : hits) EXPECT_LE(glm::distance(p, position_of(ind)), 5.0f + 1e-4f);
}

TEST_F(CapiRoom, AddingBeyondCapacityIsALimitError) {
  std::uint32_t capacity = 0;
  ASSERT_EQ(sp_sound_scene_source_capacity(sound_, &capacity), SP_OK);
  const sp_source_desc desc = source_at(0.0f, 1.0f, 0.0f);
  std::uint32_t id = 0;
  for (std::uint32_t k = 0; k < capacity; ++k) ASSERT_EQ(sp_sound_scene_add_source(sound_, &desc, &id), SP_OK);
  EXPECT_EQ(id, capacity - 1);
  EXPECT_EQ(sp_sound_scene_add_source(sound_, &desc, &id), SP_ERROR_LIMIT_EXCEEDED);
  EXPECT_EQ(sp_sound_scene_emit(sound_, &desc, 1.0, &id), SP_ERROR_LIMIT_EXCEEDED);
  EXPECT_NE(last_error().find("remove one first"), std::string::npos) << last_error();
  EXPECT_EQ(id, capacity - 1);
}

TEST_F(CapiRoom, SceneControlsRejectBadArguments) {
  const std::uint32_t id = add(source_at(0.0f, 1.0f, 0.0f));
  const sp_source_desc good = source_at(0.0f, 1.0f, 0.0f);
  std::uint32_t out_id = 77;
  // NULL pointers.
  EXPECT_EQ(sp_sound_scene_add_source(sound_, nullptr, &out_id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_add_source(sound_, &good, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("out_id"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_update_source(sound_, id, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_emit(sound_, nullptr, 1.0, &out_id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_emit(sound_, &good, 1.0, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound_, 0, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_instance_count(sound_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_has_source(sound_, id, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_source_capacity(sound_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_scene(sim_, nullptr), SP_ERROR_INVALID_ARGUMENT);

  // Non-finite scalars and fields (the C++ layer names the field).
  EXPECT_EQ(sp_sound_scene_set_listener(sound_, kNan, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_move_source(sound_, id, 0, kInf, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("not finite"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_play(sound_, id, std::numeric_limits<double>::quiet_NaN()), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_play(sound_, id, -1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_emit(sound_, &good, std::numeric_limits<double>::infinity(), &out_id),
            SP_ERROR_INVALID_ARGUMENT);
  sp_source_desc bad = good;
  bad.position[2] = kNan;
  EXPECT_EQ(sp_sound_scene_add_source(sound_, &bad, &out_id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("position is not finite"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_emit(sound_, &bad, 1.0, &out_id), SP_ERROR_INVALID_ARGUMENT);
  bad = good;
  bad.color[1] = kInf;
  EXPECT_EQ(sp_sound_scene_update_source(sound_, id, &bad), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("color"), std::string::npos) << last_error();
  bad = good;
  bad.interval = 0.0;
  EXPECT_EQ(sp_sound_scene_add_source(sound_, &bad, &out_id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("interval"), std::string::npos) << last_error();
  bad = good;
  bad.max_distance = -1.0f;
  EXPECT_EQ(sp_sound_scene_add_source(sound_, &bad, &out_id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(out_id, 77u);  // untouched on error

  // Unknown and removed ids: the C++ layer's message.
  EXPECT_EQ(sp_sound_scene_move_source(sound_, 5, 0, 1, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("unknown source id 5"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_update_source(sound_, 0xFFFFFFFFu, &good), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_play(sound_, 1, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_remove_source(sound_, 1), SP_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(sp_sound_scene_remove_source(sound_, id), SP_OK);
  EXPECT_EQ(sp_sound_scene_move_source(sound_, id, 0, 1, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("was removed"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_update_source(sound_, id, &good), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_play(sound_, id, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(sim_, id, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("was removed"), std::string::npos) << last_error();

  // A scene without moving parts has no instance 0.
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound_, 0, identity), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("unknown instance 0"), std::string::npos) << last_error();
  step();  // still runs
}

// --- Moving parts --------------------------------------------------------

// The quad of the first tests as a moving part "door": pushed from z = 1 to
// z = 2, it catches the rays that reach |x|, |y| <= 10 on the plane z = 2.
TEST(CapiInstances, MovedDoorCatchesTheRaysAtItsNewPlace) {
  const std::uint32_t instances[] = {0, 0};
  const char* const names[] = {"door"};
  sp_scene* scene = nullptr;
  ASSERT_EQ(
      sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, instances, names, 1, &scene),
      SP_OK)
      << last_error();
  sp_simulation* sim = nullptr;
  ASSERT_EQ(sp_simulation_create(scene, kQuadConfig, SP_BACKEND_CPU, &sim), SP_OK) << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  sp_sound_scene* sound = nullptr;
  ASSERT_EQ(sp_simulation_scene(sim, &sound), SP_OK);
  std::uint32_t count = 0;
  ASSERT_EQ(sp_sound_scene_instance_count(sound, &count), SP_OK);
  EXPECT_EQ(count, 1u);

  // Column-major: the translation is the last column.
  const float push[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
  ASSERT_EQ(sp_sound_scene_set_instance_transform(sound, 0, push), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(sim), SP_OK) << last_error();

  std::uint32_t expected = 0;
  for (std::uint32_t ray = 0; ray < 64; ++ray) {
    const glm::vec3 dir = sp::shader::sp_emission_direction(3u, 0u, ray);
    if (!(dir.z > 0.0f)) continue;
    const float t = 2.0f / dir.z;
    if (t <= 30.0f && std::fabs(dir.x * t) <= kHalf && std::fabs(dir.y * t) <= kHalf) ++expected;
  }
  ASSERT_GT(expected, 0u);
  const std::vector<sp_indicator> live = live_indicators(sim);
  EXPECT_EQ(live.size(), expected);
  for (const sp_indicator& ind : live) EXPECT_NEAR(ind.position[2], 2.0f, 1e-4f);

  float bad[16];
  std::copy(std::begin(push), std::end(push), bad);
  bad[5] = kNan;
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound, 0, bad), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("column_major_4x4[5]"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound, 1, push), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("unknown instance 1"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_destroy(sim), SP_OK);
}

// Scaled by FLT_MAX (finite) the door's corners land on +-FLT_MAX and inf,
// which the BVH refit refuses: that used to stop the simulation for good at
// the next step. Now the call is refused, naming the instance and why, and
// the steps go on with the door where it was.
TEST(CapiInstances, ExtremeTransformIsRefusedAndTheSimulationGoesOn) {
  const std::uint32_t instances[] = {0, 0};
  const char* const names[] = {"door"};
  sp_scene* scene = nullptr;
  ASSERT_EQ(
      sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, instances, names, 1, &scene),
      SP_OK)
      << last_error();
  sp_simulation* sim = nullptr;
  ASSERT_EQ(sp_simulation_create(scene, kQuadConfig, SP_BACKEND_CPU, &sim), SP_OK) << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  sp_sound_scene* sound = nullptr;
  ASSERT_EQ(sp_simulation_scene(sim, &sound), SP_OK);
  const float push[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};  // to z = 2
  ASSERT_EQ(sp_sound_scene_set_instance_transform(sound, 0, push), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(sim), SP_OK) << last_error();

  const float m = std::numeric_limits<float>::max();
  const float huge[16] = {m, 0, 0, 0, 0, m, 0, 0, 0, 0, m, 0, 0, 0, 0, 1};
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound, 0, huge), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("instance 0 (\"door\")"), std::string::npos) << last_error();
  EXPECT_NE(last_error().find("previous transform stays"), std::string::npos) << last_error();
  const float far[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1e12f, 1};
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound, 0, far), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("coordinate bound"), std::string::npos) << last_error();

  for (int step = 1; step <= 2; ++step) {
    ASSERT_EQ(sp_simulation_step(sim), SP_OK) << last_error();
    std::size_t of_step = 0;
    for (const sp_indicator& ind : live_indicators(sim)) {
      if (ind.step != std::uint32_t(step)) continue;
      ++of_step;
      EXPECT_NEAR(ind.position[2], 2.0f, 1e-4f);  // the door stayed pushed
    }
    EXPECT_GT(of_step, 0u);
  }
  EXPECT_EQ(sp_simulation_destroy(sim), SP_OK);
}

TEST(CapiInstances, CreateChecksInstanceIdsAndNames) {
  const char* const names[] = {"door"};
  sp_scene* scene = nullptr;
  const std::uint32_t out_of_range[] = {0, 1};
  EXPECT_EQ(sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, out_of_range, names, 1,
                                           &scene),
            SP_ERROR_INVALID_SCENE);
  EXPECT_NE(last_error().find("triangle 1 has instance id 1"), std::string::npos) << last_error();
  const std::uint32_t moving[] = {0, SP_STATIC_INSTANCE};
  EXPECT_EQ(
      sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, moving, names, 0, &scene),
      SP_ERROR_INVALID_SCENE);  // no instances, yet triangle 0 names one
  EXPECT_EQ(
      sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, nullptr, names, 1, &scene),
      SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(
      sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, moving, nullptr, 1, &scene),
      SP_ERROR_INVALID_ARGUMENT);
  const char* const null_name[] = {nullptr};
  EXPECT_EQ(
      sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, moving, null_name, 1, &scene),
      SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("instance_names[0]"), std::string::npos) << last_error();
  EXPECT_EQ(scene, nullptr);

  // Every triangle static, or no instance arrays at all: a plain scene.
  const std::uint32_t all_static[] = {SP_STATIC_INSTANCE, SP_STATIC_INSTANCE};
  for (const std::uint32_t* instances : {all_static, static_cast<const std::uint32_t*>(nullptr)}) {
    ASSERT_EQ(sp_scene_create_with_instances(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, instances, nullptr, 0,
                                             &scene),
              SP_OK)
        << last_error();
    EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  }
}

// --- Handle misuse -------------------------------------------------------

TEST(CapiHandles, DestroyingTwiceIsDetected) {
  sp_scene* scene = make_quad_scene();
  ASSERT_NE(scene, nullptr);
  sp_simulation* sim = nullptr;
  ASSERT_EQ(sp_simulation_create(scene, kQuadConfig, SP_BACKEND_CPU, &sim), SP_OK) << last_error();
  EXPECT_EQ(sp_simulation_destroy(sim), SP_OK);
  EXPECT_EQ(sp_simulation_destroy(sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_simulation_destroy: simulation handle is not live"), std::string::npos)
      << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  EXPECT_EQ(sp_scene_destroy(scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("not live (destroyed or never created)"), std::string::npos) << last_error();
}

TEST(CapiHandles, CallsAfterDestroyAreDetected) {
  sp_scene* scene = make_quad_scene();
  ASSERT_NE(scene, nullptr);
  sp_simulation* sim = nullptr;
  ASSERT_EQ(sp_simulation_create(scene, kQuadConfig, SP_BACKEND_CPU, &sim), SP_OK) << last_error();
  sp_sound_scene* sound = nullptr;
  ASSERT_EQ(sp_simulation_scene(sim, &sound), SP_OK);
  ASSERT_EQ(sp_simulation_destroy(sim), SP_OK);
  ASSERT_EQ(sp_scene_destroy(scene), SP_OK);

  std::uint32_t count = 0;
  sp_stats stats{};
  sp_indicator indicator{};
  sp_sound_scene* again = nullptr;
  EXPECT_EQ(sp_simulation_step(sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_simulation_step: simulation handle is not live"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_set_listener(sim, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_play(sim, 0, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_source_count(sim, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_live_indicators(sim, &indicator, 1, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_stats(sim, &stats), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_scene(sim, &again), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(again, nullptr);

  // The borrowed scene died with its owner.
  const sp_source_desc desc = source_at(0.0f, 0.0f, 0.0f);
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::uint32_t id = 0;
  int has = 0;
  EXPECT_EQ(sp_sound_scene_add_source(sound, &desc, &id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_sound_scene_add_source: scene handle is not live"), std::string::npos)
      << last_error();
  EXPECT_EQ(sp_sound_scene_set_listener(sound, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_update_source(sound, 0, &desc), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_move_source(sound, 0, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_remove_source(sound, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_play(sound, 0, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_emit(sound, &desc, 1.0, &id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_set_instance_transform(sound, 0, identity), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_instance_count(sound, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_has_source(sound, 0, &has), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_source_capacity(sound, &count), SP_ERROR_INVALID_ARGUMENT);

  // A destroyed scene cannot make a simulation.
  sp_simulation* other = nullptr;
  EXPECT_EQ(sp_simulation_create(scene, kQuadConfig, SP_BACKEND_CPU, &other), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("scene handle is not live"), std::string::npos) << last_error();
  EXPECT_EQ(other, nullptr);
}

// Pointers that never were handles (a stray cast, a handle of another
// kind) are rejected without being read.
TEST(CapiHandles, NeverCreatedHandlesAreRejected) {
  alignas(16) unsigned char junk[256] = {};
  auto* sim = reinterpret_cast<sp_simulation*>(junk);
  auto* scene = reinterpret_cast<sp_scene*>(junk);
  auto* sound = reinterpret_cast<sp_sound_scene*>(junk);
  auto* vis = reinterpret_cast<sp_visualizer*>(junk);
  EXPECT_EQ(sp_simulation_step(sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_destroy(sim), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_scene_destroy(scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_remove_source(sound, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_destroy(vis), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_wait(vis), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_visualizer_wait: visualizer handle is not live"), std::string::npos) << last_error();

  // A live simulation is not a live scene, and its sound scene is not it.
  sp_scene* real_scene = make_quad_scene();
  ASSERT_NE(real_scene, nullptr);
  sp_simulation* real_sim = nullptr;
  ASSERT_EQ(sp_simulation_create(real_scene, kQuadConfig, SP_BACKEND_CPU, &real_sim), SP_OK) << last_error();
  sp_simulation* other = nullptr;
  EXPECT_EQ(sp_simulation_create(reinterpret_cast<sp_scene*>(real_sim), kQuadConfig, SP_BACKEND_CPU, &other),
            SP_ERROR_INVALID_ARGUMENT);
  sp_sound_scene* sound_of_sim = nullptr;
  ASSERT_EQ(sp_simulation_scene(real_sim, &sound_of_sim), SP_OK);
  EXPECT_EQ(sp_simulation_step(reinterpret_cast<sp_simulation*>(sound_of_sim)), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_destroy(real_sim), SP_OK);
  EXPECT_EQ(sp_scene_destroy(real_scene), SP_OK);
}

TEST(CapiNullHandles, SceneControlsRejectThem) {
  const sp_source_desc desc = source_at(0.0f, 0.0f, 0.0f);
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::uint32_t id = 0;
  int has = 0;
  sp_sound_scene* sound = nullptr;
  EXPECT_EQ(sp_simulation_scene(nullptr, &sound), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_set_listener(nullptr, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_add_source(nullptr, &desc, &id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_sound_scene_add_source: scene is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(sp_sound_scene_update_source(nullptr, 0, &desc), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_move_source(nullptr, 0, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_remove_source(nullptr, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_play(nullptr, 0, 1.0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_emit(nullptr, &desc, 1.0, &id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_set_instance_transform(nullptr, 0, identity), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_instance_count(nullptr, &id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_has_source(nullptr, 0, &has), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_source_capacity(nullptr, &id), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sound, nullptr);
}

// The visualizer's checks that need no device (the GPU test covers the
// rest): they run here, under the sanitizers.
TEST(CapiVisualizerWithoutDevice, RejectsNullAndUnsetArguments) {
  sp_scene* scene = make_quad_scene();
  ASSERT_NE(scene, nullptr);
  sp_host_vulkan host;
  sp_host_vulkan_init(&host);
  EXPECT_EQ(host.queue_family, VK_QUEUE_FAMILY_IGNORED);
  EXPECT_EQ(host.compute_queue_family, VK_QUEUE_FAMILY_IGNORED);
  EXPECT_EQ(host.device, VK_NULL_HANDLE);
  sp_draw_target target;
  sp_draw_target_init(&target);
  EXPECT_EQ(target.color_format, VK_FORMAT_UNDEFINED);
  EXPECT_EQ(target.samples, VK_SAMPLE_COUNT_1_BIT);
  EXPECT_EQ(target.depth_compare, VK_COMPARE_OP_LESS_OR_EQUAL);
  sp_host_vulkan_init(nullptr);
  sp_draw_target_init(nullptr);

  sp_visualizer* vis = nullptr;
  EXPECT_EQ(sp_visualizer_create(nullptr, &target, scene, kQuadConfig, SP_BACKEND_GPU, &vis),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("host is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_create(&host, nullptr, scene, kQuadConfig, SP_BACKEND_GPU, &vis), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_create(&host, &target, nullptr, kQuadConfig, SP_BACKEND_GPU, &vis),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_create(&host, &target, scene, kQuadConfig, SP_BACKEND_GPU, nullptr),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_create(&host, &target, scene, kQuadConfig, static_cast<sp_backend>(3), &vis),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_create(&host, &target, scene, "{ not json", SP_BACKEND_GPU, &vis), SP_ERROR_INVALID_CONFIG);
  // Null Vulkan handles are rejected before any Vulkan call.
  EXPECT_EQ(sp_visualizer_create(&host, &target, scene, kQuadConfig, SP_BACKEND_GPU, &vis), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("VkDevice"), std::string::npos) << last_error();
  EXPECT_EQ(vis, nullptr);

  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::uint64_t steps = 0;
  std::uint32_t recorded = 0;
  sp_backend backend = SP_BACKEND_AUTO;
  sp_sound_scene* sound = nullptr;
  EXPECT_EQ(sp_visualizer_scene(nullptr, &sound), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_backend(nullptr, &backend), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_simulation(nullptr, VK_NULL_HANDLE, 0.1, &recorded), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_draw(nullptr, VK_NULL_HANDLE, identity, identity, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_wait(nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_steps_run(nullptr, &steps), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("sp_visualizer_steps_run: visualizer is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

}  // namespace
