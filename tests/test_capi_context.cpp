// Contexts through the C API (soundpaint.h, "Contexts"): the version
// handshake and struct_size rule refuse what they must and say why, the log
// hears validation messages, the allocator gives and gets back every handle,
// the thread cap reaches the CPU pool without changing a result, and each C
// option of sp_simulation_options does what its comment says, checked
// against numbers worked out by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "soundpaint/soundpaint.h"

namespace {

std::string last_error() { return sp_last_error_message(); }

// What a host's log callback saw.
struct LogRecord {
  std::vector<sp_log_level> levels;
  std::vector<std::string> messages;
};

void record_log(void* user_data, sp_log_level level, const char* message) {
  auto* record = static_cast<LogRecord*>(user_data);
  record->levels.push_back(level);
  record->messages.emplace_back(message);
}

// A host allocator that counts, and checks that what it frees it gave.
struct CountingAllocator {
  int allocations = 0;
  int frees = 0;
  std::vector<void*> live;
};

void* counting_allocate(void* user_data, size_t size, size_t alignment) {
  auto* counter = static_cast<CountingAllocator*>(user_data);
  void* memory = std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  if (memory != nullptr) {
    ++counter->allocations;
    counter->live.push_back(memory);
  }
  return memory;
}

void counting_free(void* user_data, void* memory) {
  auto* counter = static_cast<CountingAllocator*>(user_data);
  ++counter->frees;
  std::erase(counter->live, memory);
  std::free(memory);
}

sp_context* make_context(const sp_context_settings& settings) {
  sp_context* context = nullptr;
  EXPECT_EQ(sp_context_create(&settings, &context), SP_OK) << last_error();
  return context;
}

// A closed cube of "concrete" (layer 0), 10 m across round the origin, its
// faces turned inward, and one triangle of "wood" (layer 1) 1 km away:
// every ray from the origin hits the cube first, and none gets to the wood.
struct Cube {
  std::vector<float> vertices;
  std::vector<uint32_t> layers;
  const char* names[2] = {"concrete", "wood"};

  Cube() {
    const float c[8][3] = {{-5, -5, -5}, {5, -5, -5}, {5, 5, -5}, {-5, 5, -5},
                           {-5, -5, 5},  {5, -5, 5},  {5, 5, 5},  {-5, 5, 5}};
    const int quads[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
    for (const auto& q : quads) {
      for (const int corner : {q[0], q[1], q[2], q[0], q[2], q[3]})
        vertices.insert(vertices.end(), c[corner], c[corner] + 3);
      layers.insert(layers.end(), {0, 0});
    }
    vertices.insert(vertices.end(), {1000, 0, 0, 1000, 1, 0, 1000, 0, 1});
    layers.push_back(1);
  }
  uint32_t triangles() const { return static_cast<uint32_t>(layers.size()); }
};

// One source at the origin that always plays, heard from the origin; no
// reflections, so each ray makes exactly one hit.
const char* const kCubeConfig = R"({
  "ray_budget": 200, "max_bounces": 0, "seed": 7,
  "listener": { "position": [0, 0, 0] },
  "sources": [ { "position": [0, 0, 0], "max_distance": 30 } ]
})";

TEST(CapiContext, VersionIsTheHeadersAndPacksAsDocumented) {
  EXPECT_EQ(sp_get_version(), SOUNDPAINT_VERSION);
  // 0.2.0 packed as major << 16 | minor << 8 | patch.
  EXPECT_EQ(sp_get_version(), (0u << 16) | (2u << 8) | 0u);
}

TEST(CapiContext, SettingsWithAStructSizeTooSmallOrZeroAreRefused) {
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  sp_context* context = nullptr;
  settings.struct_size = 8;  // the version field and no further
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("settings->struct_size is 8"), std::string::npos) << last_error();
  settings.struct_size = 0;
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("struct_size is 0"), std::string::npos) << last_error();
  settings.struct_size = sizeof(sp_context_settings) + 8;  // a newer header's
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(context, nullptr);
}

TEST(CapiContext, AnotherMajorVersionIsRefused) {
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  sp_context* context = nullptr;
  settings.version = SOUNDPAINT_MAKE_VERSION(1, 0, 0);
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("major versions differ"), std::string::npos) << last_error();
  EXPECT_NE(last_error().find("1.0.0"), std::string::npos) << last_error();
  settings.version = SOUNDPAINT_MAKE_VERSION(0, 255, 0);  // a newer minor: may use what we lack
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(context, nullptr);
}

TEST(CapiContext, BadInputIsNamedNeverACrash) {
  sp_context* context = nullptr;
  EXPECT_EQ(sp_context_create(nullptr, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("settings is NULL"), std::string::npos) << last_error();
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  EXPECT_EQ(sp_context_create(&settings, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("out is NULL"), std::string::npos) << last_error();
  settings.flags = 0x80u;
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("flags has unknown bits 128"), std::string::npos) << last_error();
  settings.flags = 0;
  CountingAllocator counter;
  settings.allocator.allocate = counting_allocate;  // no free
  settings.allocator.user_data = &counter;
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("allocator"), std::string::npos) << last_error();
  EXPECT_EQ(counter.allocations, 0);
  sp_context_settings_init(nullptr);

  sp_simulation* simulation = nullptr;
  EXPECT_EQ(sp_simulation_create_in(nullptr, nullptr, nullptr, nullptr, &simulation), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("context is NULL"), std::string::npos) << last_error();
  sp_scene* scene = nullptr;
  EXPECT_EQ(sp_scene_load_in(nullptr, "x.gltf", nullptr, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("context is NULL"), std::string::npos) << last_error();

  sp_context_settings_init(&settings);
  context = make_context(settings);
  ASSERT_EQ(sp_context_destroy(context), SP_OK);
  EXPECT_EQ(sp_context_destroy(context), SP_ERROR_INVALID_ARGUMENT);  // twice
  EXPECT_NE(last_error().find("not live"), std::string::npos) << last_error();
  EXPECT_EQ(sp_scene_load_in(context, "x.gltf", nullptr, &scene), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_context_destroy(nullptr), SP_OK);
}

TEST(CapiContext, LogHearsConfigAndSceneValidationNamingTheProblem) {
  LogRecord log;
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  settings.log = record_log;
  settings.log_user_data = &log;
  sp_context* context = make_context(settings);
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create_in(context, cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2,
                               nullptr, nullptr, 0, &scene),
            SP_OK)
      << last_error();
  EXPECT_TRUE(log.messages.empty());

  sp_simulation* simulation = nullptr;
  EXPECT_EQ(sp_simulation_create_in(context, scene, R"({ "ray_budget": -1 })", nullptr, &simulation),
            SP_ERROR_INVALID_CONFIG);
  ASSERT_EQ(log.messages.size(), 1u);
  EXPECT_EQ(log.levels[0], SP_LOG_ERROR);
  EXPECT_NE(log.messages[0].find("ray_budget"), std::string::npos) << log.messages[0];
  EXPECT_EQ(log.messages[0], last_error());

  EXPECT_EQ(sp_simulation_create_in(context, scene, R"({ "diffraction": { "frequency": 0 } })", nullptr, &simulation),
            SP_ERROR_INVALID_CONFIG);
  ASSERT_EQ(log.messages.size(), 2u);
  EXPECT_NE(log.messages[1].find("diffraction.frequency"), std::string::npos) << log.messages[1];

  // A scene whose triangle names a layer that does not exist.
  const uint32_t bad_layers[1] = {5};
  sp_scene* bad = nullptr;
  EXPECT_EQ(sp_scene_create_in(context, cube.vertices.data(), 1, bad_layers, cube.names, 2, nullptr, nullptr, 0, &bad),
            SP_ERROR_INVALID_SCENE);
  ASSERT_EQ(log.messages.size(), 3u);
  EXPECT_NE(log.messages[2].find("triangle 0 has layer id 5"), std::string::npos) << log.messages[2];

  // The default context has no log: the same mistake reaches only the
  // last error message.
  EXPECT_EQ(sp_simulation_create(scene, R"({ "ray_budget": -1 })", SP_BACKEND_CPU, &simulation),
            SP_ERROR_INVALID_CONFIG);
  EXPECT_EQ(log.messages.size(), 3u);

  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  EXPECT_EQ(sp_context_destroy(context), SP_OK);
}

TEST(CapiContext, AllocatorGivesEveryHandleAndGetsItBack) {
  CountingAllocator counter;
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  settings.allocator.allocate = counting_allocate;
  settings.allocator.free = counting_free;
  settings.allocator.user_data = &counter;
  sp_context* context = make_context(settings);
  EXPECT_EQ(counter.allocations, 1);  // the context itself
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create_in(context, cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2,
                               nullptr, nullptr, 0, &scene),
            SP_OK)
      << last_error();
  EXPECT_EQ(counter.allocations, 2);
  sp_simulation* simulation = nullptr;
  ASSERT_EQ(sp_simulation_create_in(context, scene, kCubeConfig, nullptr, &simulation), SP_OK) << last_error();
  EXPECT_EQ(counter.allocations, 3);
  EXPECT_EQ(counter.frees, 0);

  // A failed creation gives back what it took.
  sp_simulation* refused = nullptr;
  EXPECT_EQ(sp_simulation_create_in(context, scene, R"({ "ray_budget": -1 })", nullptr, &refused),
            SP_ERROR_INVALID_CONFIG);
  EXPECT_EQ(counter.allocations - counter.frees, 3);

  // The objects keep their context: it goes with the last of them.
  EXPECT_EQ(sp_context_destroy(context), SP_OK);
  EXPECT_EQ(counter.live.size(), 3u);
  EXPECT_EQ(sp_simulation_step(simulation), SP_OK) << last_error();
  EXPECT_EQ(sp_simulation_destroy(simulation), SP_OK) << last_error();
  EXPECT_EQ(counter.live.size(), 2u);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
  EXPECT_EQ(counter.frees, counter.allocations);
  EXPECT_TRUE(counter.live.empty());
}

TEST(CapiContext, AllocatorThatFailsGivesOutOfMemory) {
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  settings.allocator.allocate = [](void*, size_t, size_t) -> void* { return nullptr; };
  settings.allocator.free = [](void*, void*) {};
  sp_context* context = nullptr;
  EXPECT_EQ(sp_context_create(&settings, &context), SP_ERROR_OUT_OF_MEMORY);
  EXPECT_EQ(context, nullptr);
}

// The live indicators after `steps` steps of the cube.
std::vector<sp_indicator> run_cube(sp_simulation* simulation, int steps) {
  for (int i = 0; i < steps; ++i) EXPECT_EQ(sp_simulation_step(simulation), SP_OK) << last_error();
  uint32_t count = 0;
  EXPECT_EQ(sp_simulation_live_indicators(simulation, nullptr, 0, &count), SP_OK) << last_error();
  std::vector<sp_indicator> live(count);
  EXPECT_EQ(sp_simulation_live_indicators(simulation, live.data(), count, &count), SP_OK) << last_error();
  return live;
}

TEST(CapiContext, ThreadCapReachesTheCpuPoolAndChangesNoResult) {
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create(cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2, &scene), SP_OK);
  sp_simulation_options options;
  sp_simulation_options_init(&options);
  options.backend = SP_BACKEND_CPU;

  sp_context_settings settings;
  sp_context_settings_init(&settings);
  settings.max_threads = 1;
  sp_context* capped = make_context(settings);
  sp_simulation* one = nullptr;
  ASSERT_EQ(sp_simulation_create_in(capped, scene, kCubeConfig, &options, &one), SP_OK) << last_error();
  uint32_t threads = 0;
  ASSERT_EQ(sp_simulation_thread_count(one, &threads), SP_OK);
  EXPECT_EQ(threads, 1u);
  // A simulation asking for more than the cap still gets the cap.
  options.threads = 3;
  sp_simulation* asks_three = nullptr;
  ASSERT_EQ(sp_simulation_create_in(capped, scene, kCubeConfig, &options, &asks_three), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_thread_count(asks_three, &threads), SP_OK);
  EXPECT_EQ(threads, 1u);
  // Without a cap, what it asks for; with neither, one per core.
  sp_simulation* three = nullptr;
  ASSERT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &three), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_thread_count(three, &threads), SP_OK);
  EXPECT_EQ(threads, 3u);
  sp_simulation* every_core = nullptr;
  ASSERT_EQ(sp_simulation_create(scene, kCubeConfig, SP_BACKEND_CPU, &every_core), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_thread_count(every_core, &threads), SP_OK);
  EXPECT_EQ(threads, std::max(1u, std::thread::hardware_concurrency()));

  // The CPU backend is deterministic whatever its threads.
  const std::vector<sp_indicator> capped_live = run_cube(one, 5);
  const std::vector<sp_indicator> three_live = run_cube(three, 5);
  const std::vector<sp_indicator> default_live = run_cube(every_core, 5);
  ASSERT_FALSE(capped_live.empty());
  ASSERT_EQ(capped_live.size(), default_live.size());
  ASSERT_EQ(capped_live.size(), three_live.size());
  EXPECT_EQ(std::memcmp(capped_live.data(), default_live.data(), capped_live.size() * sizeof(sp_indicator)), 0);
  EXPECT_EQ(std::memcmp(capped_live.data(), three_live.data(), capped_live.size() * sizeof(sp_indicator)), 0);

  for (sp_simulation* s : {one, asks_three, three, every_core}) EXPECT_EQ(sp_simulation_destroy(s), SP_OK);
  EXPECT_EQ(sp_context_destroy(capped), SP_OK);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

TEST(CapiSimulationOptions, RayBudgetReplacesTheConfigs) {
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create(cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2, &scene), SP_OK);
  sp_simulation_options options;
  sp_simulation_options_init(&options);
  options.backend = SP_BACKEND_CPU;
  options.ray_budget = 37;  // the config says 200
  sp_simulation* simulation = nullptr;
  ASSERT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(simulation), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(simulation), SP_OK) << last_error();
  sp_stats stats;
  ASSERT_EQ(sp_simulation_stats(simulation, &stats), SP_OK);
  // One source that always plays gets the whole budget, each step.
  EXPECT_EQ(stats.rays_emitted, 2u * 37u);
  EXPECT_EQ(sp_simulation_destroy(simulation), SP_OK);

  options.ray_budget = (1u << 24) + 1;
  EXPECT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("options->ray_budget"), std::string::npos) << last_error();
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

TEST(CapiSimulationOptions, StructSizeAndFieldsAreChecked) {
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create(cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2, &scene), SP_OK);
  sp_simulation* simulation = nullptr;
  sp_simulation_options options;
  std::memset(&options, 0, sizeof options);  // never initialised
  EXPECT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("options->struct_size is 0"), std::string::npos) << last_error();
  sp_simulation_options_init(&options);
  options.struct_size = 16;  // an older, smaller struct this version never had
  EXPECT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("options->struct_size is 16"), std::string::npos) << last_error();
  sp_simulation_options_init(&options);
  options.allow_cpu_device = 2;
  EXPECT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("allow_cpu_device"), std::string::npos) << last_error();

  sp_scene_load_options load;
  sp_scene_load_options_init(&load);
  EXPECT_EQ(load.struct_size, sizeof(sp_scene_load_options));
  load.struct_size = 4;
  sp_scene* loaded = nullptr;
  EXPECT_EQ(sp_scene_load_with_options(SP_SCENES_DIR "/level.gltf", &load, &loaded), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("options->struct_size is 4"), std::string::npos) << last_error();
  EXPECT_EQ(simulation, nullptr);
  EXPECT_EQ(loaded, nullptr);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

TEST(CapiSimulationOptions, DeviceNameChoosesTheGpu) {
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create(cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2, &scene), SP_OK);
  sp_simulation_options options;
  sp_simulation_options_init(&options);
  options.backend = SP_BACKEND_GPU;
  options.device_name = "no device is called this";
  sp_simulation* simulation = nullptr;
  EXPECT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_ERROR_VULKAN);
  EXPECT_NE(last_error().find("no device is called this"), std::string::npos) << last_error();
  EXPECT_EQ(simulation, nullptr);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

// The kernels' width reaches the GPU backend: 128 (a multiple of every
// subgroup width, within the limit every device has) runs; a width past any
// device's limit is refused, naming the field.
TEST(CapiSimulationOptions, WorkgroupSizeReachesTheGpuBackend) {
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create(cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2, &scene), SP_OK);
  sp_simulation_options options;
  sp_simulation_options_init(&options);
  EXPECT_EQ(options.workgroup_size, 0u);
  options.backend = SP_BACKEND_GPU;
  options.workgroup_size = 128;
  sp_simulation* simulation = nullptr;
  ASSERT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_OK) << last_error();
  ASSERT_EQ(sp_simulation_step(simulation), SP_OK) << last_error();
  sp_stats stats;
  ASSERT_EQ(sp_simulation_stats(simulation, &stats), SP_OK);
  EXPECT_EQ(stats.rays_emitted, 200u);
  EXPECT_EQ(sp_simulation_destroy(simulation), SP_OK);

  simulation = nullptr;
  options.workgroup_size = 1u << 20;
  EXPECT_EQ(sp_simulation_create_with_options(scene, kCubeConfig, &options, &simulation), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("workgroup_size"), std::string::npos) << last_error();
  EXPECT_EQ(simulation, nullptr);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

TEST(CapiLayerStats, EveryRayHitsTheEnclosingLayerAndNoneTheFarOne) {
  const Cube cube;
  sp_scene* scene = nullptr;
  ASSERT_EQ(sp_scene_create(cube.vertices.data(), cube.triangles(), cube.layers.data(), cube.names, 2, &scene), SP_OK);
  sp_simulation* simulation = nullptr;
  ASSERT_EQ(sp_simulation_create(scene, kCubeConfig, SP_BACKEND_CPU, &simulation), SP_OK) << last_error();
  for (int i = 0; i < 3; ++i) ASSERT_EQ(sp_simulation_step(simulation), SP_OK) << last_error();

  uint32_t count = 0;
  ASSERT_EQ(sp_simulation_layer_stats(simulation, nullptr, 0, &count), SP_OK) << last_error();
  ASSERT_EQ(count, 2u);
  sp_layer_stats layers[2];
  std::memset(layers, 0xAB, sizeof layers);
  ASSERT_EQ(sp_simulation_layer_stats(simulation, layers, 2, &count), SP_OK) << last_error();
  // 3 steps of 200 rays from the cube's centre, 5 m from every face, within
  // their 30 m reach: each ray hits the cube once (no reflections), from
  // the front, and the wood 1 km away never.
  EXPECT_EQ(layers[0].hits, 3u * 200u);
  EXPECT_EQ(layers[0].back_face_hits, 0u);
  EXPECT_EQ(layers[0].reflections, 0u);
  EXPECT_EQ(layers[0].diffractions, 0u);
  EXPECT_EQ(layers[1].hits, 0u);
  EXPECT_EQ(layers[1].penetrations, 0u);
  EXPECT_EQ(layers[1].no_way_out, 0u);

  // Capacity 1 writes the first layer only; out NULL with capacity refused.
  sp_layer_stats first;
  ASSERT_EQ(sp_simulation_layer_stats(simulation, &first, 1, &count), SP_OK);
  EXPECT_EQ(count, 2u);
  EXPECT_EQ(first.hits, layers[0].hits);
  EXPECT_EQ(sp_simulation_layer_stats(simulation, nullptr, 1, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("out is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(sp_simulation_layer_stats(simulation, layers, 2, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_simulation_destroy(simulation), SP_OK);
  EXPECT_EQ(sp_simulation_layer_stats(simulation, layers, 2, &count), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_scene_destroy(scene), SP_OK);
}

}  // namespace
