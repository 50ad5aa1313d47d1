// The C API (include/soundpaint/soundpaint.h) over the C++ library: scenes
// and simulations. Every entry point is noexcept: C++ errors become an
// sp_result plus the calling thread's last error message, and every handle
// is checked against the live-handle registry before it is touched.
#include "soundpaint/soundpaint.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "capi/capi_internal.h"
#include "sp_types.h"

namespace {

using sp::capi::guarded;
using sp::capi::HandleKind;
using sp::capi::require;
using sp::capi::require_live;
using sp::capi::throw_invalid;
using sp::capi::unwrap;

sp_indicator to_c(const sp::Indicator& in) {
  sp_indicator out{};
  out.position[0] = in.position.x;
  out.position[1] = in.position.y;
  out.position[2] = in.position.z;
  out.normal[0] = in.normal.x;
  out.normal[1] = in.normal.y;
  out.normal[2] = in.normal.z;
  out.energy = in.energy;
  out.size = in.size;
  out.color[0] = in.color.x;
  out.color[1] = in.color.y;
  out.color[2] = in.color.z;
  out.intensity = in.intensity;
  out.kind = in.kind;
  out.source_id = in.source_id;
  out.bounces = in.bounces;
  out.penetrations = in.penetrations;
  out.path_length = in.path_length;
  out.step = in.step;
  out.direction[0] = in.dir.x;
  out.direction[1] = in.dir.y;
  out.direction[2] = in.dir.z;
  out.diffractions = in.diffractions;
  out.heard_energy = in.heard_energy;
  out.arrival[0] = in.arrival.x;
  out.arrival[1] = in.arrival.y;
  out.arrival[2] = in.arrival.z;
  out.toward = in.toward;
  return out;
}

// The arguments of both scene-from-arrays entry points; the instance arrays
// are NULL / 0 for sp_scene_create.
struct SceneArrays {
  const float* vertices;
  uint32_t triangle_count;
  const uint32_t* triangle_layers;
  const char* const* layer_names;
  uint32_t layer_count;
  const uint32_t* triangle_instances;
  const char* const* instance_names;
  uint32_t instance_count;
};

void require_names(const char* const* names, uint32_t count, const char* fn, const char* what) {
  for (uint32_t i = 0; i < count; ++i)
    if (names[i] == nullptr) throw_invalid(fn, std::string(what) + "[" + std::to_string(i) + "] is NULL");
}

[[noreturn]] void throw_scene(const char* fn, const std::string& what) {
  throw sp::Exception(sp::ErrorCode::InvalidScene, std::string(fn) + ": " + what);
}

void copy_geometry(const SceneArrays& in, const char* fn, sp::Scene& s) {
  const std::size_t vertex_count = std::size_t{3} * in.triangle_count;
  s.vertices.reserve(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const float* p = in.vertices + 3 * v;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw_scene(fn, "vertex " + std::to_string(v) + " (triangle " + std::to_string(v / 3) + ") is not finite");
    s.vertices.emplace_back(p[0], p[1], p[2]);
  }
  s.triangle_layers.assign(in.triangle_layers, in.triangle_layers + in.triangle_count);
  for (uint32_t t = 0; t < in.triangle_count; ++t)
    if (s.triangle_layers[t] >= in.layer_count)
      throw_scene(fn, "triangle " + std::to_string(t) + " has layer id " + std::to_string(s.triangle_layers[t]) +
                          " but layer_count is " + std::to_string(in.layer_count));
  s.layer_names.assign(in.layer_names, in.layer_names + in.layer_count);
}

// Without instances (or with every triangle static) the scene has no moving
// parts, exactly as sp_scene_create makes it.
void copy_instances(const SceneArrays& in, const char* fn, sp::Scene& s) {
  if (in.triangle_instances == nullptr) return;
  s.triangle_instances.assign(in.triangle_instances, in.triangle_instances + in.triangle_count);
  for (uint32_t t = 0; t < in.triangle_count; ++t) {
    const uint32_t instance = s.triangle_instances[t];
    if (instance != SP_STATIC_INSTANCE && instance >= in.instance_count)
      throw_scene(fn, "triangle " + std::to_string(t) + " has instance id " + std::to_string(instance) +
                          " but instance_count is " + std::to_string(in.instance_count) +
                          " (SP_STATIC_INSTANCE for a static triangle)");
  }
  if (in.instance_count == 0) {
    s.triangle_instances.clear();
    return;
  }
  s.instance_names.assign(in.instance_names, in.instance_names + in.instance_count);
}

sp_result create_scene(const SceneArrays& in, sp_scene** out, const char* fn) {
  return guarded([&] {
    require(in.vertices != nullptr, fn, "vertices is NULL");
    require(in.triangle_layers != nullptr, fn, "triangle_layers is NULL");
    require(in.layer_names != nullptr, fn, "layer_names is NULL");
    require(out != nullptr, fn, "out is NULL");
    require(in.triangle_count > 0, fn, "triangle_count is 0");
    require(in.layer_count > 0, fn, "layer_count is 0");
    require_names(in.layer_names, in.layer_count, fn, "layer_names");
    if (in.instance_count > 0) {
      require(in.triangle_instances != nullptr, fn, "triangle_instances is NULL but instance_count > 0");
      require(in.instance_names != nullptr, fn, "instance_names is NULL but instance_count > 0");
      require_names(in.instance_names, in.instance_count, fn, "instance_names");
    }
    auto scene = std::make_unique<sp_scene>();
    copy_geometry(in, fn, scene->scene);
    copy_instances(in, fn, scene->scene);
    sp::capi::register_handle(HandleKind::Scene, scene.get());
    *out = scene.release();
  });
}

}  // namespace

extern "C" {

namespace {

void load_scene_into(const char* path, const sp::SceneLoadOptions& options, sp_scene** out, const char* fn) {
  require(path != nullptr, fn, "path is NULL");
  require(out != nullptr, fn, "out is NULL");
  auto scene = std::make_unique<sp_scene>(sp_scene{unwrap(sp::load_scene(path, options))});
  sp::capi::register_handle(HandleKind::Scene, scene.get());
  *out = scene.release();
}

}  // namespace

sp_result sp_scene_load(const char* path, sp_scene** out) noexcept {
  return guarded([&] { load_scene_into(path, sp::SceneLoadOptions{}, out, "sp_scene_load"); });
}

void sp_scene_load_options_init(sp_scene_load_options* options) noexcept {
  if (options == nullptr) return;
  *options = sp_scene_load_options{};
  options->max_triangles = sp::SceneLoadOptions{}.max_triangles;
}

sp_result sp_scene_load_with_options(const char* path, const sp_scene_load_options* options, sp_scene** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_scene_load_with_options";
    require(options != nullptr, fn, "options is NULL");
    if ((options->flags & ~SP_SCENE_LOAD_ALLOW_EXTERNAL_URIS) != 0)
      throw_invalid(fn, "options->flags has unknown bits " + std::to_string(options->flags));
    require(options->max_triangles > 0, fn, "options->max_triangles is 0");
    sp::SceneLoadOptions converted;
    converted.allow_external_uris = (options->flags & SP_SCENE_LOAD_ALLOW_EXTERNAL_URIS) != 0;
    converted.max_triangles = options->max_triangles;
    load_scene_into(path, converted, out, fn);
  });
}

sp_result sp_scene_create(const float* vertices, uint32_t triangle_count, const uint32_t* triangle_layers,
                          const char* const* layer_names, uint32_t layer_count, sp_scene** out) noexcept {
  const SceneArrays in{vertices, triangle_count, triangle_layers, layer_names, layer_count, nullptr, nullptr, 0};
  return create_scene(in, out, "sp_scene_create");
}

sp_result sp_scene_create_with_instances(const float* vertices, uint32_t triangle_count,
                                         const uint32_t* triangle_layers, const char* const* layer_names,
                                         uint32_t layer_count, const uint32_t* triangle_instances,
                                         const char* const* instance_names, uint32_t instance_count,
                                         sp_scene** out) noexcept {
  const SceneArrays in{vertices,    triangle_count,     triangle_layers, layer_names,
                       layer_count, triangle_instances, instance_names,  instance_count};
  return create_scene(in, out, "sp_scene_create_with_instances");
}

sp_result sp_scene_destroy(sp_scene* scene) noexcept {
  return guarded([&] { sp::capi::destroy_handle(HandleKind::Scene, scene, "sp_scene_destroy", "scene"); });
}

namespace {

void create_simulation(const sp_scene* scene, const char* config_json, const sp_simulation_options& options,
                       sp_simulation** out, const char* fn) {
  require_live(HandleKind::Scene, scene, fn, "scene");
  require(out != nullptr, fn, "out is NULL");
  require(options.memory_budget_bytes > 0, fn, "options->memory_budget_bytes is 0");
  sp::SimulatorSettings settings;
  settings.backend = sp::capi::backend_choice(options.backend, fn);
  settings.cpu.memory_budget_bytes = options.memory_budget_bytes;
  settings.gpu.memory_budget_bytes = options.memory_budget_bytes;
  auto simulation = std::make_unique<sp_simulation>();
  simulation->simulator = unwrap(sp::create_simulator(sp::capi::world_from(*scene, config_json), settings));
  simulation->sound_scene.scene = &simulation->simulator->scene();
  sp::capi::register_handle(HandleKind::Simulation, simulation.get(), &simulation->sound_scene);
  *out = simulation.release();
}

}  // namespace

sp_result sp_simulation_create(const sp_scene* scene, const char* config_json, sp_backend backend,
                               sp_simulation** out) noexcept {
  return guarded([&] {
    sp_simulation_options options;
    sp_simulation_options_init(&options);
    options.backend = backend;
    create_simulation(scene, config_json, options, out, "sp_simulation_create");
  });
}

void sp_simulation_options_init(sp_simulation_options* options) noexcept {
  if (options == nullptr) return;
  *options = sp_simulation_options{};
  options->backend = SP_BACKEND_AUTO;
  options->memory_budget_bytes = sp::kDefaultMemoryBudgetBytes;
}

sp_result sp_simulation_create_with_options(const sp_scene* scene, const char* config_json,
                                            const sp_simulation_options* options, sp_simulation** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_create_with_options";
    require(options != nullptr, fn, "options is NULL");
    create_simulation(scene, config_json, *options, out, fn);
  });
}

sp_result sp_simulation_destroy(sp_simulation* simulation) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_destroy";
    // Not while this handle's other thread steps or reads it (a call on its
    // sound scene meanwhile is the host's to prevent: soundpaint.h).
    if (simulation != nullptr && sp::capi::is_live(HandleKind::Simulation, simulation)) simulation->stepping.claim(fn);
    sp::capi::destroy_handle(HandleKind::Simulation, simulation, fn, "simulation");
  });
}

sp_result sp_simulation_scene(sp_simulation* simulation, sp_sound_scene** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_scene";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    require(out != nullptr, fn, "out is NULL");
    *out = &simulation->sound_scene;
  });
}

sp_result sp_simulation_set_listener(sp_simulation* simulation, float x, float y, float z) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_set_listener";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    require(std::isfinite(x) && std::isfinite(y) && std::isfinite(z), fn, "position is not finite");
    unwrap(simulation->simulator->set_listener(glm::vec3(x, y, z)));
  });
}

sp_result sp_simulation_play(sp_simulation* simulation, uint32_t source_id, double duration_seconds) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_play";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    require(std::isfinite(duration_seconds) && duration_seconds >= 0.0, fn, "duration_seconds must be finite and >= 0");
    // The scene checks the id (unknown, removed) from any thread; world()
    // belongs to the thread that steps.
    unwrap(simulation->simulator->play(source_id, duration_seconds));
  });
}

sp_result sp_simulation_step(sp_simulation* simulation) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_step";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    unwrap(simulation->simulator->step());
  });
}

sp_result sp_simulation_source_count(const sp_simulation* simulation, uint32_t* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_source_count";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    require(out != nullptr, fn, "out is NULL");
    *out = simulation->simulator->scene().source_slot_count();  // any thread: not world()
  });
}

sp_result sp_simulation_live_indicators(sp_simulation* simulation, sp_indicator* out, uint32_t capacity,
                                        uint32_t* count) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_live_indicators";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    require(count != nullptr, fn, "count is NULL");
    require(out != nullptr || capacity == 0, fn, "out is NULL but capacity > 0");
    const std::vector<sp::Indicator> live = unwrap(simulation->simulator->live_indicators());
    // The ring buffer holds at most max_indicators <= 2^24 entries.
    const auto n = static_cast<uint32_t>(live.size());
    const uint32_t written = n < capacity ? n : capacity;
    for (uint32_t i = 0; i < written; ++i) out[i] = to_c(live[i]);
    *count = n;
  });
}

sp_result sp_simulation_stats(sp_simulation* simulation, sp_stats* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_stats";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    require(out != nullptr, fn, "out is NULL");
    const sp::SimulationStats stats = unwrap(simulation->simulator->stats());
    sp_stats result{};
    result.steps = stats.steps;
    result.casts = stats.casts;
    result.rays_emitted = stats.rays_emitted;
    result.indicators = stats.indicators;
    *out = result;
  });
}

}  // extern "C"
