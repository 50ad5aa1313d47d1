// The C API: every misuse returns an error code and a message instead of
// crashing, and a hand-derived scene built from arrays gives the expected
// indicators.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "soundpaint/soundpaint.h"
#include "sp_random.h"

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::string last_error() { return sp_last_error_message(); }

// A big two-sided quad on the plane z = 1: |x|, |y| <= kHalf.
constexpr float kHalf = 10.0f;
const std::vector<float> kQuad = {
    -kHalf, -kHalf, 1.0f, kHalf, -kHalf, 1.0f, kHalf, kHalf, 1.0f,   //
    -kHalf, -kHalf, 1.0f, kHalf, kHalf,  1.0f, -kHalf, kHalf, 1.0f,  //
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
  EXPECT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers.data(), kLayerNames, 1, nullptr),
            SP_ERROR_INVALID_ARGUMENT);
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
    EXPECT_EQ(sp_scene_create(vertices.data(), 2, kQuadLayers.data(), kLayerNames, 1, &scene),
              SP_ERROR_INVALID_SCENE);
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
  sp_scene_destroy(nullptr);
  sp_simulation_destroy(nullptr);
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

}  // namespace
