// How soundpaint allocates, observed by replacing the global operator new
// in this test binary: loading an instanced scene allocates in proportion
// to its triangles (never a copy per instance, never a regrowth per mesh),
// and an allocation that fails on a CPU worker thread comes back as an
// error instead of terminating the process.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "support/gltf_builder.h"
#include "support/scene_builder.h"
#include "support/test_directory.h"

namespace {

std::atomic<std::uint64_t> g_bytes_allocated{0};
std::atomic<bool> g_fail_off_main_thread{false};      // every allocation on another thread throws
std::atomic<std::size_t> g_fail_from_size{SIZE_MAX};  // allocations of this size or more throw
std::atomic<int> g_refused{0};                        // allocations made to throw so far
std::thread::id g_main_thread;

}  // namespace

// Every operator new below takes its memory from malloc, so free is the
// matching release; GCC cannot see that through the replacement.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  if ((g_fail_off_main_thread.load(std::memory_order_relaxed) && std::this_thread::get_id() != g_main_thread) ||
      size >= g_fail_from_size.load(std::memory_order_relaxed)) {
    g_refused.fetch_add(1);
    throw std::bad_alloc();
  }
  g_bytes_allocated.fetch_add(size, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

namespace fs = std::filesystem;

class Allocations : public sp::test::TestDirectory {
 protected:
  void SetUp() override {
    TestDirectory::SetUp();
    g_main_thread = std::this_thread::get_id();
  }
  void TearDown() override {
    g_fail_off_main_thread = false;
    g_fail_from_size = SIZE_MAX;
    TestDirectory::TearDown();
  }
};

// Bytes allocated (never freed ones subtracted: the sum of every request)
// while loading `path`, which must load.
std::uint64_t bytes_to_load(const fs::path& path, std::size_t expected_triangles) {
  const std::uint64_t before = g_bytes_allocated.load();
  const sp::Result<sp::Scene> scene = sp::load_scene(path);
  const std::uint64_t bytes = g_bytes_allocated.load() - before;
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error().message);
  if (scene.ok()) {
    EXPECT_EQ(scene->triangle_count(), expected_triangles);
  }
  return bytes;
}

// Growing the triangle list by exactly one primitive at a time made every
// instance copy all the triangles before it: 20,000 instances of a box
// allocated ~86 GB in total. Ten times the instances must now cost about
// ten times the bytes.
TEST_F(Allocations, InstancedSceneLoadsInBytesProportionalToItsTriangles) {
  const std::uint64_t small = bytes_to_load(write("2k.glb", sp::test::instanced_unit_boxes(2000).glb()), 2000 * 12);
  const std::uint64_t large = bytes_to_load(write("20k.glb", sp::test::instanced_unit_boxes(20000).glb()), 20000 * 12);
  EXPECT_LT(large, 15 * small) << "2,000 instances: " << small << " bytes; 20,000: " << large;
}

// A mesh is decoded once, however many nodes place it: a primitive that
// uses 8 corners of a 100,000-vertex array (1.2 MB) placed 20,000 times
// would otherwise read 24 GB of vertices.
TEST_F(Allocations, InstancesDoNotDecodeTheirMeshAgain) {
  const fs::path path = write("wide.glb", sp::test::instanced_unit_boxes(20000, 100000).glb());
  const std::uint64_t bytes = bytes_to_load(path, 20000 * 12);
  EXPECT_LT(bytes, std::uint64_t{256} << 20) << bytes << " bytes to load " << fs::file_size(path) << " bytes";
}

// A 6 x 3 x 5 m room; 100,000 rays a step make 3,125 chunks of work, more
// than the calling thread can finish before the workers wake. A ring of
// 200,000 admits 3,334 indicators a step (ring_quota), 267 kB.
sp::World room_world() {
  sp::Config config;
  config.ray_budget = 100000;
  config.max_indicators = 200000;
  config.listener_position = glm::vec3(0.0f, 1.5f, 0.0f);
  return sp::make_world(sp::test::closed_room(), config).value();
}

// The first step fails while `arm` holds; the simulator must then report
// the failure on every step and keep what it had.
void expect_step_failure_stops_the_simulator(const std::function<void()>& arm) {
  sp::CpuSettings settings;
  settings.threads = 4;
  auto simulator = sp::create_cpu_simulator(room_world(), settings);
  ASSERT_TRUE(simulator.ok()) << simulator.error().message;
  g_refused = 0;
  arm();
  const sp::Result<bool> failed = (*simulator)->step();
  g_fail_off_main_thread = false;
  g_fail_from_size = SIZE_MAX;
  ASSERT_GT(g_refused.load(), 0) << "no allocation was refused: the test proves nothing";
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().code, sp::ErrorCode::LimitExceeded);
  EXPECT_EQ(failed.error().message, "step 0 failed, the simulator has stopped: out of memory");
  // Stopped for good, and says so; what it reported before stays readable.
  const sp::Result<bool> again = (*simulator)->step();
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().message, failed.error().message);
  EXPECT_FALSE((*simulator)->last_step_indicators().ok());
  ASSERT_TRUE((*simulator)->live_indicators().ok());
  EXPECT_TRUE((*simulator)->live_indicators()->empty());
  EXPECT_EQ((*simulator)->stats()->steps, 0u);
  EXPECT_EQ((*simulator)->steps_run(), 0u);
  // A new simulator on the same world works: nothing global was harmed.
  auto fresh = sp::create_cpu_simulator(room_world(), settings);
  ASSERT_TRUE(fresh.ok());
  ASSERT_TRUE((*fresh)->step().ok());
  EXPECT_GT((*fresh)->stats()->indicators, 0u);
}

// Used to reach std::terminate: the pool ran bodies on workers uncaught.
TEST_F(Allocations, WorkerOutOfMemoryBecomesAnErrorAndStopsTheSimulator) {
  expect_step_failure_stops_the_simulator([] { g_fail_off_main_thread = true; });
}

// The list of the step's indicators the ring admits (room_world: 267 kB),
// made on the caller.
TEST_F(Allocations, CallerOutOfMemoryBecomesAnErrorAndStopsTheSimulator) {
  expect_step_failure_stops_the_simulator([] { g_fail_from_size = std::size_t{128} << 10; });
}

}  // namespace
