// Valid scenes shaped to be slow (issue 38, docs/model.md#work-bounds):
// smaller instances of scripts/make-hostile-scenes.py's shapes, built in
// memory. Each used to cost far more than its size suggests: a cast
// through a stack of coincident triangles tested all of them, a burial
// query among overlapping boxes visited every one. Now every stage is
// bounded, and the tests read the bounds through counters, never clocks:
// casts cut short at SP_MAX_CAST_PACKETS, edges left out of diffraction,
// check's degenerate_bvh / casts_cut_short / edges_left_out findings, and
// the memory budget a scene load is refused by.
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "bvh/diffraction_edges.h"
#include "sim/world_geometry.h"
#include "soundpaint/check.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "sp_types.h"
#include "support/check_findings.h"
#include "support/exposed_edges.h"
#include "support/gltf_builder.h"
#include "support/gpu_environment.h"
#include "support/run_steps.h"
#include "support/scene_builder.h"
#include "support/test_directory.h"

namespace sp {
namespace {

using test::add_triangle;

// The shapes, at sizes where the code before the bounds spent 15 to 180
// times as long on each hostile stage tested here (0.4 to 9 s each on 2
// cores: the comb's check the longest); the whole file now runs in about
// 2 s.

// `triangles` coincident copies of one 4 x 4 m quad's two triangles at
// y = 0, facing +y, a source 1 m above its centre.
Scene coincident_quads(std::uint32_t triangles) {
  Scene scene;
  for (std::uint32_t i = 0; i < triangles / 2; ++i)
    test::add_quad(scene, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, "concrete");
  scene.sources.push_back(test::source_at({0, 1, 0}));
  return scene;
}

// Long thin triangles through a 2 m cube at the origin, in every direction:
// 20 m long, 1 cm wide at one end, so nearly every box overlaps every other.
Scene slivers(std::uint32_t count) {
  Scene scene;
  std::mt19937 rng(38);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (std::uint32_t i = 0; i < count; ++i) {
    glm::vec3 d(unit(rng), unit(rng), unit(rng));
    if (glm::length(d) < 0.1f) d = glm::vec3(0, 1, 0);
    d = glm::normalize(d);
    const glm::vec3 c(unit(rng), unit(rng), unit(rng));
    const glm::vec3 a = c - 10.0f * d, b = c + 10.0f * d;
    add_triangle(scene, a, b, a + glm::vec3(0.01f, 0.01f, 0.0f), "concrete");
  }
  scene.sources.push_back(test::source_at({0, 0, 3}));
  return scene;
}

// A comb of thin teeth 1 mm apart in the plane z = 0, each slanted 45
// degrees to a tip 20 m along: every tooth's box overlaps its neighbours'
// along 20 m, though no two teeth touch.
Scene comb(std::uint32_t teeth) {
  Scene scene;
  for (std::uint32_t i = 0; i < teeth; ++i) {
    const float x = 0.001f * float(i);
    add_triangle(scene, {x, 0, 0}, {x + 0.0005f, 0, 0}, {x + 20.0f, 20.0f, 0}, "concrete");
  }
  scene.sources.push_back(test::source_at({0.5f * 0.001f * float(teeth), 5, 1}));  // 1 m in front of it
  return scene;
}

// Near 1e15, where floats are 2^26 apart: `count` / 2 metre-sized triangles
// collapse onto one point (degenerate), and `count` / 2 triangles 1e9 wide
// spread over 1e12. The weld once numbered their grid cells past int64
// (undefined behaviour, found by the fuzzer).
Scene far_away(std::uint32_t count) {
  constexpr double kBase = 1.0e15;
  Scene scene;
  std::mt19937 rng(39);
  std::uniform_real_distribution<double> near(0.0, 1.0e3), spread(0.0, 1.0e12);
  auto at = [](double x, double y, double z) { return glm::vec3(glm::dvec3(x, y, z)); };
  for (std::uint32_t i = 0; i < count / 2; ++i) {
    const double x = kBase + near(rng), y = kBase + near(rng), z = kBase + near(rng);
    add_triangle(scene, at(x, y, z), at(x + 1, y, z), at(x, y + 1, z), "concrete");
  }
  for (std::uint32_t i = 0; i < count / 2; ++i) {
    const double x = kBase + spread(rng), y = kBase + spread(rng), z = kBase + spread(rng);
    add_triangle(scene, at(x, y, z), at(x + 1e9, y, z), at(x, y + 1e9, z), "concrete");
  }
  scene.sources.push_back(test::source_at(at(kBase + 500, kBase + 500, kBase + 500)));
  return scene;
}

// Tiny triangles scattered through a 100 m cube: many, but a BVH
// separates them, so nothing is cut short.
Scene scattered(std::uint32_t count) {
  Scene scene;
  std::mt19937 rng(40);
  std::uniform_real_distribution<float> coordinate(-50.0f, 50.0f);
  for (std::uint32_t i = 0; i < count; ++i) {
    const glm::vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
    add_triangle(scene, p, p + glm::vec3(0.02f, 0, 0), p + glm::vec3(0, 0.02f, 0), "concrete");
  }
  scene.sources.push_back(test::source_at({0, 0, 0}));
  return scene;
}

Config config_for(const Scene& scene, bool diffraction) {
  Config config;
  config.listener_position = scene.sources.at(0).position;
  config.diffraction.enabled = diffraction;
  return config;
}

// Three CPU steps of `rays` rays each; every one must complete.
SimulationStats cpu_steps(const Scene& scene, bool diffraction, std::uint32_t rays = 500) {
  Config config = config_for(scene, diffraction);
  config.ray_budget = rays;
  auto sim = create_cpu_simulator(make_world(scene, config).value(), CpuSettings{2}).value();
  return test::run_steps(*sim, 3).stats;
}

// Edges find_exposed_edges left undecided in the level's own BVH (as
// make_world numbers its solids), and its exposed edge bits.
struct EdgeCount {
  std::uint64_t left_out = 0;
  std::uint64_t exposed_bits = 0;
};

EdgeCount find_edges(const Scene& scene) {
  const World world = test::level_world(scene);
  EdgeCount count;
  const auto table = find_exposed_edges(world.geometry->bvh, &count.left_out);
  EXPECT_EQ(count.left_out, world.geometry->edges_left_out) << "make_world's search and this one differ";
  for (const auto& entry : table) count.exposed_bits += static_cast<std::uint64_t>(std::popcount(entry.exposed));
  return count;
}

CheckReport check(const Scene& scene) {
  CheckSettings settings;
  settings.probe_steps = 4;
  settings.probe_rays_per_step = 500;
  settings.threads = 2;
  return check_scene(scene, config_for(scene, true), settings).value();
}

std::string codes(const CheckReport& report) {
  std::string all;
  for (const CheckFinding& f : report.findings) all += "\n  " + f.code + ": " + f.message;
  return all;
}

// --- A cast has a work bound ---

// The source sees the quad (half-width 2 m, 1 m below) under a solid angle
// of 4 asin(2 * 2 / sqrt((2^2 + 1)(2^2 + 1))) = 4 asin(0.8) = 3.709 sr,
// 29.5% of the sphere of uniform emission directions. Every ray that way
// meets 20,000 triangles no box separates (5,000 packets, more than
// SP_MAX_CAST_PACKETS) and is cut short; every other ray meets nothing.
TEST(HostileScenes, CoincidentStackCutsEveryCastThroughIt) {
  const Scene scene = coincident_quads(20000);
  for (const bool diffraction : {false, true}) {
    SCOPED_TRACE(diffraction ? "diffraction on" : "diffraction off");
    const SimulationStats stats = cpu_steps(scene, diffraction, 4000);
    EXPECT_EQ(stats.steps, 3u);
    ASSERT_EQ(stats.rays_emitted, 12000u);
    EXPECT_EQ(stats.casts, stats.rays_emitted) << "a cut or missing ray ends after its first cast";
    const double share = double(stats.casts_cut_short) / double(stats.rays_emitted);
    EXPECT_NEAR(share, 3.709 / (4.0 * std::numbers::pi), 0.02) << stats.casts_cut_short << " cut short";
    EXPECT_EQ(stats.layers.at(0).hits, 0u) << "a cast through the stack cannot find its nearest hit";
  }
}

// The source sits among the slivers' crossings, and over teeth whose boxes
// overlap by the thousand: casts there meet far more than
// SP_MAX_CAST_PACKETS packets.
TEST(HostileScenes, OverlappingSliversAndTeethCutCastsShort) {
  for (const Scene& scene : {slivers(10000), comb(20000)}) {
    for (const bool diffraction : {false, true}) {
      SCOPED_TRACE(std::to_string(scene.triangle_count()) +
                   (diffraction ? " triangles, diffraction on" : " triangles"));
      const SimulationStats stats = cpu_steps(scene, diffraction);
      EXPECT_EQ(stats.steps, 3u);
      EXPECT_GT(stats.casts_cut_short, 0u);
      EXPECT_LE(stats.casts_cut_short, stats.casts);
    }
  }
}

// The ordinary shapes: a room, and many tiny triangles a BVH separates.
TEST(HostileScenes, OrdinaryLevelsCutNoCast) {
  for (const Scene& scene : {test::closed_room(), scattered(20000)}) {
    for (const bool diffraction : {false, true}) {
      const SimulationStats stats = cpu_steps(scene, diffraction);
      EXPECT_EQ(stats.steps, 3u);
      EXPECT_GT(stats.casts, stats.rays_emitted / 2);
      EXPECT_EQ(stats.casts_cut_short, 0u) << scene.triangle_count() << " triangles";
    }
  }
}

// The source rounds onto the float point the 10,000 collapsed triangles
// share, so every cast starts inside their box, which no hit can prune:
// every one is cut short.
TEST(HostileScenes, FarCoordinatesCutEveryCastAtTheCollapsedPoint) {
  const Scene scene = far_away(20000);
  for (const bool diffraction : {false, true}) {
    SCOPED_TRACE(diffraction ? "diffraction on" : "diffraction off");
    const SimulationStats stats = cpu_steps(scene, diffraction);
    EXPECT_EQ(stats.steps, 3u);
    EXPECT_GT(stats.casts, 1000u);
    EXPECT_EQ(stats.casts_cut_short, stats.casts);
  }
}

// Both backends walk the same leaves in the same order, so they cut the
// same casts: the counts agree exactly, step by step.
class HostileScenesGpu : public test::GpuTest {};

TEST_F(HostileScenesGpu, BothBackendsCutTheSameCasts) {
  for (const Scene& scene : {coincident_quads(20000), comb(20000)}) {
    const Config config = config_for(scene, false);
    auto cpu = make_simulator(make_world(scene, config).value(), Backend::Cpu);
    auto gpu = make_simulator(make_world(scene, config).value(), Backend::Gpu);
    for (int step = 0; step < 2; ++step) {
      SCOPED_TRACE(std::to_string(scene.triangle_count()) + " triangles, after step " + std::to_string(step));
      ASSERT_TRUE(cpu->step().ok());
      ASSERT_TRUE(gpu->step().ok());
      const SimulationStats c = cpu->stats().value(), g = gpu->stats().value();
      EXPECT_GT(c.casts_cut_short, 0u);
      EXPECT_EQ(g.casts_cut_short, c.casts_cut_short);
      EXPECT_EQ(g.casts, c.casts);
    }
  }
}

// --- Edge finding has a work bound ---

// The quad's edges are each shared by 10,000 or 20,000 triangles: never a
// candidate, so no burial query runs and none is left out.
TEST(HostileScenes, CoincidentEdgesAreNeverCandidates) {
  const EdgeCount edges = find_edges(coincident_quads(20000));
  EXPECT_EQ(edges.exposed_bits, 0u);
  EXPECT_EQ(edges.left_out, 0u);
}

// Every sliver and tooth edge is free (its own triangle only), so each is
// a candidate whose burial query searches boxes that overlap by the
// thousand: the query's bound leaves some undecided, and those are not
// exposed.
TEST(HostileScenes, OverlappingEdgesAreLeftOutAndCounted) {
  for (const Scene& scene : {slivers(10000), comb(20000)}) {
    const EdgeCount edges = find_edges(scene);
    EXPECT_GT(edges.left_out, 0u) << scene.triangle_count() << " triangles";
    EXPECT_LE(edges.left_out + edges.exposed_bits, 3u * scene.triangle_count());
  }
}

// A box's 12 edges are convex, each exposed on both its faces (24 bits);
// its 6 face diagonals are flat. Every edge decided.
TEST(HostileScenes, OrdinaryBoxDecidesEveryEdge) {
  Scene scene;
  test::add_box(scene, {0, 0, 0}, {1, 2, 3}, "concrete");
  const EdgeCount edges = find_edges(scene);
  EXPECT_EQ(edges.left_out, 0u);
  EXPECT_EQ(edges.exposed_bits, 24u);
  EXPECT_EQ(find_edges(test::closed_room()).left_out, 0u);
}

// --- check names what a level costs ---

// Every node of the stack's tree has the root's box, so its SAH cost
// (relative to the root) is at least the 20,000 triangles its leaves hold.
TEST(HostileScenes, CheckNamesTheCoincidentStack) {
  const CheckReport report = check(coincident_quads(20000));
  const CheckFinding* tree = test::find_finding(report, "degenerate_bvh");
  ASSERT_NE(tree, nullptr) << codes(report);
  EXPECT_GE(tree->count, 20000u);
  EXPECT_NE(tree->message.find("20000 triangles"), std::string::npos) << tree->message;
  EXPECT_NE(tree->message.find("Remove duplicated geometry"), std::string::npos) << tree->message;
  const CheckFinding* cut = test::find_finding(report, "casts_cut_short");
  ASSERT_NE(cut, nullptr) << codes(report);
  EXPECT_EQ(cut->count, report.probe.casts_cut_short);
  EXPECT_GT(cut->count, 0u);
  EXPECT_EQ(test::find_finding(report, "edges_left_out"), nullptr) << codes(report);
}

TEST(HostileScenes, CheckNamesSliversAndTheirEdges) {
  const CheckReport report = check(slivers(10000));
  EXPECT_NE(test::find_finding(report, "degenerate_bvh"), nullptr) << codes(report);
  EXPECT_NE(test::find_finding(report, "casts_cut_short"), nullptr) << codes(report);
  const CheckFinding* edges = test::find_finding(report, "edges_left_out");
  ASSERT_NE(edges, nullptr) << codes(report);
  EXPECT_EQ(edges->count, find_edges(slivers(10000)).left_out);
}

TEST(HostileScenes, CheckFindsNoWorkProblemInOrdinaryLevels) {
  for (const Scene& scene : {test::closed_room(), scattered(20000)}) {
    const CheckReport report = check(scene);
    for (const char* code : {"degenerate_bvh", "casts_cut_short", "edges_left_out"})
      EXPECT_EQ(test::find_finding(report, code), nullptr) << scene.triangle_count() << " triangles:" << codes(report);
    EXPECT_EQ(report.probe.casts_cut_short, 0u);
  }
}

// Half the triangles collapse onto one float point (zero area); the other
// half span about 1e12 units, so the level is reported as not in metres.
TEST(HostileScenes, CheckCompletesAtFarCoordinates) {
  const CheckReport report = check(far_away(20000));
  EXPECT_EQ(report.triangles, 20000u);
  const CheckFinding* scale = test::find_finding(report, "scale");
  ASSERT_NE(scale, nullptr) << codes(report);
  EXPECT_GT(scale->count, 900'000'000'000u);
  EXPECT_LE(scale->count, 1'100'000'000'000u);
  const CheckFinding* degenerate = test::find_finding(report, "degenerate_triangles");
  ASSERT_NE(degenerate, nullptr) << codes(report);
  EXPECT_EQ(degenerate->count, 10000u);
  EXPECT_NE(test::find_finding(report, "casts_cut_short"), nullptr) << codes(report);
}

TEST(HostileScenes, CheckCompletesOnTheComb) {
  const CheckReport report = check(comb(20000));
  EXPECT_EQ(report.triangles, 20000u);
  for (const char* code : {"degenerate_bvh", "casts_cut_short", "edges_left_out"})
    EXPECT_NE(test::find_finding(report, code), nullptr) << code << ":" << codes(report);
}

// --- A scene load has a memory budget ---

using HostileSceneLoad = test::TestDirectory;

// 375 unit boxes: 4,500 triangles, 4,500 * 700 = 3,150,000 bytes to load
// and build, just over 3 MiB (3,145,728).
TEST_F(HostileSceneLoad, RefusesAScenePastTheMemoryBudgetNamingIt) {
  const std::filesystem::path path = write("boxes.glb", test::instanced_unit_boxes(375).glb());
  ASSERT_EQ(kSceneBytesPerTriangle, 700u);
  SceneLoadOptions options;
  options.memory_budget_bytes = std::uint64_t{3} << 20;
  const Result<Scene> refused = load_scene(path, options);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::LimitExceeded);
  const std::string& message = refused.error().message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("4500 triangles"), std::string::npos) << message;
  EXPECT_NE(message.find("memory budget of 3 MiB"), std::string::npos) << message;
  EXPECT_NE(message.find("--memory-budget"), std::string::npos) << message;

  options.memory_budget_bytes = 4500 * kSceneBytesPerTriangle - 1;
  const Result<Scene> one_byte_short = load_scene(path, options);
  ASSERT_FALSE(one_byte_short.ok());
  EXPECT_EQ(one_byte_short.error().code, ErrorCode::LimitExceeded);
  options.memory_budget_bytes = 4500 * kSceneBytesPerTriangle;
  const Result<Scene> loaded = load_scene(path, options);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded.value().triangle_count(), 4500u);
  ASSERT_TRUE(load_scene(path).ok()) << "the default budget, 2 GiB, holds it";
}

}  // namespace
}  // namespace sp
