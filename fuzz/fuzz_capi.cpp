// Fuzz target: the C API as a game host drives it (configs come from
// players; scene arrays and run-time calls from the host). The input is a
// JSON config, then bytes that pick geometry and a sequence of calls with
// their arguments (fuzz_input.h). No call may crash or throw; each returns
// a result code, with a one-line message on failure.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "soundpaint/soundpaint.h"

namespace {

// A memory budget far below the default keeps one input well under a
// second; the budget check is what refuses heavier configs.
constexpr std::uint64_t kFuzzMemoryBudget = std::uint64_t{64} << 20;
constexpr int kMaxCalls = 24;
constexpr uint32_t kMaxTriangles = 64;

void check(sp_result result) {
  if (result != SP_OK && std::strchr(sp_last_error_message(), '\n') != nullptr) __builtin_trap();
}

float small_float(sp::fuzz::ByteReader& in) {
  const float f = in.take<float>();
  return std::isfinite(f) ? std::fmod(f, 50.0f) : f;  // keep most values inside the scene
}

// Triangles from the bytes (any floats, NaN included), else a floor.
sp_scene* make_scene(sp::fuzz::ByteReader& in) {
  const uint32_t triangles = 1 + in.take<uint8_t>() % kMaxTriangles;
  std::vector<float> vertices(9 * triangles);
  for (float& v : vertices) v = small_float(in);
  std::vector<uint32_t> layers(triangles);
  for (uint32_t& l : layers) l = in.take<uint8_t>() % 3;  // 2: out of range
  const char* const names[] = {"concrete", "wood"};
  sp_scene* scene = nullptr;
  check(sp_scene_create(vertices.data(), triangles, layers.data(), names, 2, &scene));
  if (scene != nullptr) return scene;
  const float floor[9] = {-20, 0, -20, 20, 0, -20, 0, 0, 20};
  const uint32_t floor_layer = 0;
  check(sp_scene_create(floor, 1, &floor_layer, names, 1, &scene));
  return scene;
}

void call(sp::fuzz::ByteReader& in, sp_simulation* sim, sp_sound_scene* scene) {
  const uint32_t id = in.take<uint8_t>() % 8;
  switch (in.take<uint8_t>() % 9) {
    case 0:
      check(sp_simulation_step(sim));
      break;
    case 1:
      check(sp_sound_scene_set_listener(scene, small_float(in), small_float(in), small_float(in)));
      break;
    case 2: {
      sp_source_desc desc;
      sp_source_desc_init(&desc);
      for (float& p : desc.position) p = small_float(in);
      desc.max_distance = small_float(in);
      desc.interval = in.take<double>();
      uint32_t added = 0;
      check(sp_sound_scene_add_source(scene, &desc, &added));
      break;
    }
    case 3:
      check(sp_sound_scene_move_source(scene, id, small_float(in), small_float(in), small_float(in)));
      break;
    case 4:
      check(sp_sound_scene_remove_source(scene, id));
      break;
    case 5:
      check(sp_sound_scene_play(scene, id, in.take<double>()));
      break;
    case 6: {
      sp_source_desc desc;
      sp_source_desc_init(&desc);
      uint32_t emitted = 0;
      check(sp_sound_scene_emit(scene, &desc, in.take<double>(), &emitted));
      break;
    }
    case 7: {
      uint32_t count = 0;
      check(sp_simulation_live_indicators(sim, nullptr, 0, &count));
      std::vector<sp_indicator> indicators(count);
      check(sp_simulation_live_indicators(sim, indicators.data(), count, &count));
      break;
    }
    default: {
      sp_stats stats;
      check(sp_simulation_stats(sim, &stats));
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parts = sp::fuzz::split_parts(data, size);
  const std::string config(parts[0]);
  sp::fuzz::ByteReader in(parts.size() > 1 ? parts[1] : std::string_view());
  sp_scene* scene = make_scene(in);
  if (scene == nullptr) __builtin_trap();  // the floor is valid
  sp_simulation_options options;
  sp_simulation_options_init(&options);
  options.backend = SP_BACKEND_CPU;
  options.memory_budget_bytes = kFuzzMemoryBudget;
  sp_simulation* sim = nullptr;
  check(sp_simulation_create_with_options(scene, config.empty() ? nullptr : config.c_str(), &options, &sim));
  check(sp_scene_destroy(scene));
  if (sim == nullptr) return 0;
  sp_sound_scene* sound_scene = nullptr;
  check(sp_simulation_scene(sim, &sound_scene));
  for (int i = 0; i < kMaxCalls && !in.empty(); ++i) call(in, sim, sound_scene);
  check(sp_simulation_destroy(sim));
  return 0;
}
