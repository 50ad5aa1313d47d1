// The C API (include/soundpaint/soundpaint.h) over the C++ library: scenes
// and simulations. Every entry point is noexcept: C++ errors become an
// sp_result plus the calling thread's last error message, and every handle
// is checked against the live-handle registry before it is touched.
#include "soundpaint/soundpaint.h"

#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "capi/capi_internal.h"
#include "capi/validation_relay.h"
#include "sp_types.h"

// sp_indicator is fixed forever (soundpaint.h): these pin its layout, and
// the consumer test checks the same numbers from the installed header.
static_assert(sizeof(sp_indicator) == 108, "sp_indicator is fixed forever");
static_assert(offsetof(sp_indicator, position) == 0 && offsetof(sp_indicator, normal) == 12 &&
                  offsetof(sp_indicator, energy) == 24 && offsetof(sp_indicator, size) == 28 &&
                  offsetof(sp_indicator, color) == 32 && offsetof(sp_indicator, intensity) == 44 &&
                  offsetof(sp_indicator, kind) == 48 && offsetof(sp_indicator, source_id) == 52 &&
                  offsetof(sp_indicator, bounces) == 56 && offsetof(sp_indicator, penetrations) == 60 &&
                  offsetof(sp_indicator, path_length) == 64 && offsetof(sp_indicator, step) == 68 &&
                  offsetof(sp_indicator, direction) == 72 && offsetof(sp_indicator, diffractions) == 84 &&
                  offsetof(sp_indicator, heard_energy) == 88 && offsetof(sp_indicator, arrival) == 92 &&
                  offsetof(sp_indicator, toward) == 104,
              "sp_indicator is fixed forever");
static_assert(sizeof(sp_stats) == 32 && sizeof(sp_layer_stats) == 48, "fixed forever");

namespace {

using sp::capi::guarded;
using sp::capi::guarded_in;
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

void create_scene(sp_context& context, const SceneArrays& in, sp_scene** out, const char* fn) {
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
  auto scene = sp::capi::make_handle<sp_scene>(context);
  copy_geometry(in, fn, scene->scene);
  copy_instances(in, fn, scene->scene);
  sp::capi::register_handle(HandleKind::Scene, scene.get());
  *out = scene.release();
}


void load_scene_into(sp_context& context, const char* path, const sp::SceneLoadOptions& options, sp_scene** out,
                     const char* fn) {
  require(path != nullptr, fn, "path is NULL");
  require(out != nullptr, fn, "out is NULL");
  sp::Scene loaded = unwrap(sp::load_scene(path, options));
  auto scene = sp::capi::make_handle<sp_scene>(context);
  scene->scene = std::move(loaded);
  sp::capi::register_handle(HandleKind::Scene, scene.get());
  *out = scene.release();
}

// The C options, checked, as the C++ ones.
sp::SceneLoadOptions to_cpp(const sp_scene_load_options& options, const char* fn) {
  sp::capi::require_struct_size(options.struct_size, sizeof(sp_scene_load_options), fn, "options");
  if ((options.flags & ~SP_SCENE_LOAD_ALLOW_EXTERNAL_URIS) != 0)
    throw_invalid(fn, "options->flags has unknown bits " + std::to_string(options.flags));
  require(options.max_triangles > 0, fn, "options->max_triangles is 0");
  sp::SceneLoadOptions converted;
  converted.allow_external_uris = (options.flags & SP_SCENE_LOAD_ALLOW_EXTERNAL_URIS) != 0;
  converted.max_triangles = options.max_triangles;
  return converted;
}

}  // namespace

extern "C" {

sp_result sp_scene_load(const char* path, sp_scene** out) noexcept {
  return guarded(
      [&] { load_scene_into(sp::capi::default_context(), path, sp::SceneLoadOptions{}, out, "sp_scene_load"); });
}

void sp_scene_load_options_init(sp_scene_load_options* options) noexcept {
  if (options == nullptr) return;
  *options = sp_scene_load_options{};
  options->struct_size = sizeof(sp_scene_load_options);
  options->max_triangles = sp::SceneLoadOptions{}.max_triangles;
}

sp_result sp_scene_load_with_options(const char* path, const sp_scene_load_options* options, sp_scene** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_scene_load_with_options";
    require(options != nullptr, fn, "options is NULL");
    load_scene_into(sp::capi::default_context(), path, to_cpp(*options, fn), out, fn);
  });
}

sp_result sp_scene_load_in(sp_context* context, const char* path, const sp_scene_load_options* options,
                           sp_scene** out) noexcept {
  sp_context* log_to = nullptr;
  return guarded_in(log_to, [&] {
    const char* fn = "sp_scene_load_in";
    log_to = &sp::capi::context_of(context, fn);
    const sp::SceneLoadOptions converted = options != nullptr ? to_cpp(*options, fn) : sp::SceneLoadOptions{};
    load_scene_into(*log_to, path, converted, out, fn);
  });
}

sp_result sp_scene_create(const float* vertices, uint32_t triangle_count, const uint32_t* triangle_layers,
                          const char* const* layer_names, uint32_t layer_count, sp_scene** out) noexcept {
  const SceneArrays in{vertices, triangle_count, triangle_layers, layer_names, layer_count, nullptr, nullptr, 0};
  return guarded([&] { create_scene(sp::capi::default_context(), in, out, "sp_scene_create"); });
}

sp_result sp_scene_create_in(sp_context* context, const float* vertices, uint32_t triangle_count,
                             const uint32_t* triangle_layers, const char* const* layer_names, uint32_t layer_count,
                             const uint32_t* triangle_instances, const char* const* instance_names,
                             uint32_t instance_count, sp_scene** out) noexcept {
  const SceneArrays in{vertices,    triangle_count,     triangle_layers, layer_names,
                       layer_count, triangle_instances, instance_names,  instance_count};
  sp_context* log_to = nullptr;
  return guarded_in(log_to, [&] {
    const char* fn = "sp_scene_create_in";
    log_to = &sp::capi::context_of(context, fn);
    create_scene(*log_to, in, out, fn);
  });
}

sp_result sp_scene_create_with_instances(const float* vertices, uint32_t triangle_count,
                                         const uint32_t* triangle_layers, const char* const* layer_names,
                                         uint32_t layer_count, const uint32_t* triangle_instances,
                                         const char* const* instance_names, uint32_t instance_count,
                                         sp_scene** out) noexcept {
  const SceneArrays in{vertices,    triangle_count,     triangle_layers, layer_names,
                       layer_count, triangle_instances, instance_names,  instance_count};
  return guarded([&] { create_scene(sp::capi::default_context(), in, out, "sp_scene_create_with_instances"); });
}

sp_result sp_scene_destroy(sp_scene* scene) noexcept {
  return guarded([&] { sp::capi::destroy_handle(HandleKind::Scene, scene, "sp_scene_destroy", "scene"); });
}

namespace {

// A memory budget, a ray budget and a device flag, checked.
void check_options(const sp_simulation_options& options, const char* fn) {
  sp::capi::require_struct_size(options.struct_size, sizeof(sp_simulation_options), fn, "options");
  require(options.memory_budget_bytes > 0, fn, "options->memory_budget_bytes is 0");
  if (options.ray_budget > sp::kMaxRayBudget)
    throw_invalid(fn, "options->ray_budget is " + std::to_string(options.ray_budget) + ", more than 2^24");
  require(options.allow_cpu_device == 0 || options.allow_cpu_device == 1, fn,
          "options->allow_cpu_device must be 0 or 1");
}

void create_simulation(sp_context& context, const sp_scene* scene, const char* config_json,
                       const sp_simulation_options& options, sp_simulation** out, const char* fn) {
  require_live(HandleKind::Scene, scene, fn, "scene");
  require(out != nullptr, fn, "out is NULL");
  check_options(options, fn);
  const sp::capi::ValidationRelay relay(&context);
  sp::SimulatorSettings settings;
  settings.backend = sp::capi::backend_choice(options.backend, fn);
  const unsigned threads = sp::capi::thread_count(context, options.threads);
  settings.cpu.threads = threads;
  settings.cpu.memory_budget_bytes = options.memory_budget_bytes;
  settings.gpu.memory_budget_bytes = options.memory_budget_bytes;
  settings.gpu.validation = (context.flags & SP_CONTEXT_VULKAN_VALIDATION) != 0;
  if (options.device_name != nullptr) settings.gpu.device_name = options.device_name;
  settings.gpu.allow_cpu_device = options.allow_cpu_device != 0;
  settings.gpu.workgroup_size = options.workgroup_size;
  sp::capi::WorldOptions world_options;
  world_options.threads = threads;
  world_options.ray_budget = options.ray_budget;
  auto simulation = sp::capi::make_handle<sp_simulation>(context);
  simulation->simulator =
      unwrap(sp::create_simulator(sp::capi::world_from(*scene, config_json, world_options), settings));
  simulation->sound_scene.scene = &simulation->simulator->scene();
  sp::capi::register_handle(HandleKind::Simulation, simulation.get(), &simulation->sound_scene);
  *out = simulation.release();
}

// The context of a live simulation, for guarded_in (null otherwise: the
// handle is not trusted until found live).
sp_context* context_of(const sp_simulation* simulation) {
  if (simulation == nullptr || !sp::capi::is_live(HandleKind::Simulation, simulation)) return nullptr;
  return &*simulation->context;
}

}  // namespace

sp_result sp_simulation_create(const sp_scene* scene, const char* config_json, sp_backend backend,
                               sp_simulation** out) noexcept {
  return guarded([&] {
    sp_simulation_options options;
    sp_simulation_options_init(&options);
    options.backend = backend;
    create_simulation(sp::capi::default_context(), scene, config_json, options, out, "sp_simulation_create");
  });
}

void sp_simulation_options_init(sp_simulation_options* options) noexcept {
  if (options == nullptr) return;
  *options = sp_simulation_options{};
  options->struct_size = sizeof(sp_simulation_options);
  options->backend = SP_BACKEND_AUTO;
  options->memory_budget_bytes = sp::kDefaultMemoryBudgetBytes;
  options->allow_cpu_device = sp::GpuSettings{}.allow_cpu_device ? 1 : 0;
  options->workgroup_size = sp::GpuSettings{}.workgroup_size;
}

sp_result sp_simulation_create_with_options(const sp_scene* scene, const char* config_json,
                                            const sp_simulation_options* options, sp_simulation** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_create_with_options";
    require(options != nullptr, fn, "options is NULL");
    create_simulation(sp::capi::default_context(), scene, config_json, *options, out, fn);
  });
}

sp_result sp_simulation_create_in(sp_context* context, const sp_scene* scene, const char* config_json,
                                  const sp_simulation_options* options, sp_simulation** out) noexcept {
  sp_context* log_to = nullptr;
  return guarded_in(log_to, [&] {
    const char* fn = "sp_simulation_create_in";
    log_to = &sp::capi::context_of(context, fn);
    sp_simulation_options defaults;
    sp_simulation_options_init(&defaults);
    create_simulation(*log_to, scene, config_json, options != nullptr ? *options : defaults, out, fn);
  });
}

sp_result sp_simulation_destroy(sp_simulation* simulation) noexcept {
  // Kept alive past the handle, for the log and the validation layer's
  // messages of the teardown.
  const sp::capi::ContextRef context = simulation != nullptr && context_of(simulation) != nullptr
                                           ? simulation->context
                                           : sp::capi::ContextRef(sp::capi::default_context());
  const sp::capi::ValidationRelay relay(&*context);
  sp_context* log_to = &*context;
  return guarded_in(log_to, [&] {
    // Not while this handle's other thread steps or reads it (a call on its
    // sound scene meanwhile is the host's to prevent: soundpaint.h).
    sp::capi::destroy_guarded_handle(HandleKind::Simulation, simulation, &sp_simulation::stepping,
                                     "sp_simulation_destroy", "simulation");
  });
}

sp_result sp_simulation_scene(sp_simulation* simulation, sp_sound_scene** out) noexcept {
  return guarded(
      [&] { sp::capi::hand_out_scene(HandleKind::Simulation, simulation, out, "sp_simulation_scene", "simulation"); });
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
  sp_context* log_to = context_of(simulation);
  const sp::capi::ValidationRelay relay(log_to);
  return guarded_in(log_to, [&] {
    const char* fn = "sp_simulation_step";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    unwrap(simulation->simulator->step());
  });
}

sp_result sp_simulation_set_config(sp_simulation* simulation, const char* config_json) noexcept {
  sp_context* log_to = context_of(simulation);
  const sp::capi::ValidationRelay relay(log_to);
  return guarded_in(log_to, [&] {
    const char* fn = "sp_simulation_set_config";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    // The whole configuration, as sp_simulation_create reads it.
    sp::Config config;
    if (config_json != nullptr) config = unwrap(sp::parse_config(config_json, "config_json"));
    unwrap(simulation->simulator->set_config(config));
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
  sp_context* log_to = context_of(simulation);
  const sp::capi::ValidationRelay relay(log_to);
  return guarded_in(log_to, [&] {
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
  sp_context* log_to = context_of(simulation);
  return guarded_in(log_to, [&] {
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

sp_result sp_simulation_layer_stats(sp_simulation* simulation, sp_layer_stats* out, uint32_t capacity,
                                    uint32_t* count) noexcept {
  sp_context* log_to = context_of(simulation);
  return guarded_in(log_to, [&] {
    const char* fn = "sp_simulation_layer_stats";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    require(count != nullptr, fn, "count is NULL");
    require(out != nullptr || capacity == 0, fn, "out is NULL but capacity > 0");
    const sp::SimulationStats stats = unwrap(simulation->simulator->stats());
    // One entry per layer of the scene: a uint32_t layer id.
    const auto n = static_cast<uint32_t>(stats.layers.size());
    const uint32_t written = n < capacity ? n : capacity;
    for (uint32_t i = 0; i < written; ++i) {
      const sp::LayerCounters& in = stats.layers[i];
      out[i] =
          sp_layer_stats{in.hits, in.reflections, in.penetrations, in.no_way_out, in.back_face_hits, in.diffractions};
    }
    *count = n;
  });
}

sp_result sp_simulation_thread_count(sp_simulation* simulation, uint32_t* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_thread_count";
    require_live(HandleKind::Simulation, simulation, fn, "simulation");
    const auto one_thread = simulation->stepping.enter(fn, simulation->simulator->scene());
    require(out != nullptr, fn, "out is NULL");
    *out = simulation->simulator->thread_count();
  });
}

}  // extern "C"
