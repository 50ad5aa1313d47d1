// The C API (include/soundpaint/soundpaint.h) over the C++ library. Every
// entry point is noexcept: C++ errors become an sp_result plus the calling
// thread's last error message.
#include "soundpaint/soundpaint.h"

#include <cmath>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "soundpaint/config.h"
#include "soundpaint/result.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"

struct sp_scene {
  sp::Scene scene;
};

struct sp_simulation {
  std::unique_ptr<sp::Simulator> simulator;
};

namespace {

thread_local std::string g_last_error;

sp_result to_result(sp::ErrorCode code) {
  switch (code) {
    case sp::ErrorCode::InvalidArgument: return SP_ERROR_INVALID_ARGUMENT;
    case sp::ErrorCode::InvalidScene: return SP_ERROR_INVALID_SCENE;
    case sp::ErrorCode::InvalidConfig: return SP_ERROR_INVALID_CONFIG;
    case sp::ErrorCode::Io: return SP_ERROR_IO;
    case sp::ErrorCode::Vulkan: return SP_ERROR_VULKAN;
    case sp::ErrorCode::LimitExceeded: return SP_ERROR_LIMIT_EXCEEDED;
  }
  return SP_ERROR_INTERNAL;
}

// Records `message` as the thread's last error; never throws (a failed
// assignment leaves a shorter fixed message).
sp_result fail(sp_result code, const char* message) noexcept {
  try {
    g_last_error = message;
  } catch (...) {
    g_last_error.clear();  // no allocation: keeps the capacity
  }
  return code;
}

[[noreturn]] void throw_error(const sp::Error& error) { throw sp::Exception(error); }

template <class T>
T unwrap(sp::Result<T>&& result) {
  if (!result.ok()) throw_error(result.error());
  return std::move(result).value();
}

void require(bool condition, const char* function, const char* what) {
  if (!condition) throw sp::Exception(sp::ErrorCode::InvalidArgument, std::string(function) + ": " + what);
}

// Runs body() and turns every exception into a result and message.
template <class Fn>
sp_result guarded(Fn&& body) noexcept {
  try {
    body();
    return SP_OK;
  } catch (const sp::Exception& e) {
    return fail(to_result(e.error().code), e.what());
  } catch (const std::bad_alloc&) {
    return fail(SP_ERROR_OUT_OF_MEMORY, "out of memory");
  } catch (const std::exception& e) {
    return fail(SP_ERROR_INTERNAL, e.what());
  } catch (...) {
    return fail(SP_ERROR_INTERNAL, "unknown internal error");
  }
}

std::unique_ptr<sp::Simulator> create_simulator(sp::World world, sp_backend backend) {
  sp::SimulatorSettings settings;
  settings.backend = backend == SP_BACKEND_CPU   ? sp::BackendChoice::Cpu
                     : backend == SP_BACKEND_GPU ? sp::BackendChoice::Gpu
                                                 : sp::BackendChoice::Auto;
  return unwrap(sp::create_simulator(std::move(world), settings));
}

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
  return out;
}

}  // namespace

extern "C" {

const char* sp_last_error_message(void) noexcept { return g_last_error.c_str(); }

sp_result sp_scene_load(const char* path, sp_scene** out) noexcept {
  return guarded([&] {
    require(path != nullptr, "sp_scene_load", "path is NULL");
    require(out != nullptr, "sp_scene_load", "out is NULL");
    auto scene = std::make_unique<sp_scene>(sp_scene{unwrap(sp::load_scene(path))});
    *out = scene.release();
  });
}

sp_result sp_scene_create(const float* vertices, uint32_t triangle_count, const uint32_t* triangle_layers,
                          const char* const* layer_names, uint32_t layer_count, sp_scene** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_scene_create";
    require(vertices != nullptr, fn, "vertices is NULL");
    require(triangle_layers != nullptr, fn, "triangle_layers is NULL");
    require(layer_names != nullptr, fn, "layer_names is NULL");
    require(out != nullptr, fn, "out is NULL");
    require(triangle_count > 0, fn, "triangle_count is 0");
    require(layer_count > 0, fn, "layer_count is 0");
    for (uint32_t i = 0; i < layer_count; ++i)
      if (layer_names[i] == nullptr)
        throw sp::Exception(sp::ErrorCode::InvalidArgument,
                            std::string(fn) + ": layer_names[" + std::to_string(i) + "] is NULL");
    auto scene = std::make_unique<sp_scene>();
    sp::Scene& s = scene->scene;
    const std::size_t vertex_count = std::size_t{3} * triangle_count;
    s.vertices.reserve(vertex_count);
    for (std::size_t v = 0; v < vertex_count; ++v) {
      const float* p = vertices + 3 * v;
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw sp::Exception(sp::ErrorCode::InvalidScene, std::string(fn) + ": vertex " + std::to_string(v) +
                                                             " (triangle " + std::to_string(v / 3) +
                                                             ") is not finite");
      s.vertices.emplace_back(p[0], p[1], p[2]);
    }
    s.triangle_layers.assign(triangle_layers, triangle_layers + triangle_count);
    for (uint32_t t = 0; t < triangle_count; ++t)
      if (s.triangle_layers[t] >= layer_count)
        throw sp::Exception(sp::ErrorCode::InvalidScene,
                            std::string(fn) + ": triangle " + std::to_string(t) + " has layer id " +
                                std::to_string(s.triangle_layers[t]) + " but layer_count is " +
                                std::to_string(layer_count));
    s.layer_names.assign(layer_names, layer_names + layer_count);
    *out = scene.release();
  });
}

void sp_scene_destroy(sp_scene* scene) noexcept { delete scene; }

sp_result sp_simulation_create(const sp_scene* scene, const char* config_json, sp_backend backend,
                               sp_simulation** out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_create";
    require(scene != nullptr, fn, "scene is NULL");
    require(out != nullptr, fn, "out is NULL");
    require(backend == SP_BACKEND_CPU || backend == SP_BACKEND_GPU || backend == SP_BACKEND_AUTO, fn,
            "backend must be SP_BACKEND_CPU, SP_BACKEND_GPU or SP_BACKEND_AUTO");
    sp::Config config;
    if (config_json != nullptr) config = unwrap(sp::parse_config(config_json, "config_json"));
    sp::World world = unwrap(sp::make_world(scene->scene, config));
    auto simulation = std::make_unique<sp_simulation>();
    simulation->simulator = create_simulator(std::move(world), backend);
    *out = simulation.release();
  });
}

void sp_simulation_destroy(sp_simulation* simulation) noexcept { delete simulation; }

sp_result sp_simulation_set_listener(sp_simulation* simulation, float x, float y, float z) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_set_listener";
    require(simulation != nullptr, fn, "simulation is NULL");
    require(std::isfinite(x) && std::isfinite(y) && std::isfinite(z), fn, "position is not finite");
    unwrap(simulation->simulator->set_listener(glm::vec3(x, y, z)));
  });
}

sp_result sp_simulation_play(sp_simulation* simulation, uint32_t source_id, double duration_seconds) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_play";
    require(simulation != nullptr, fn, "simulation is NULL");
    const std::size_t count = simulation->simulator->world().sources.size();
    if (source_id >= count)
      throw sp::Exception(sp::ErrorCode::InvalidArgument, std::string(fn) + ": unknown source id " +
                                                              std::to_string(source_id) + " (there are " +
                                                              std::to_string(count) + " sources)");
    require(std::isfinite(duration_seconds) && duration_seconds >= 0.0, fn,
            "duration_seconds must be finite and >= 0");
    unwrap(simulation->simulator->play(source_id, duration_seconds));
  });
}

sp_result sp_simulation_step(sp_simulation* simulation) noexcept {
  return guarded([&] {
    require(simulation != nullptr, "sp_simulation_step", "simulation is NULL");
    unwrap(simulation->simulator->step());
  });
}

sp_result sp_simulation_source_count(const sp_simulation* simulation, uint32_t* out) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_source_count";
    require(simulation != nullptr, fn, "simulation is NULL");
    require(out != nullptr, fn, "out is NULL");
    *out = static_cast<uint32_t>(simulation->simulator->world().sources.size());
  });
}

sp_result sp_simulation_live_indicators(sp_simulation* simulation, sp_indicator* out, uint32_t capacity,
                                        uint32_t* count) noexcept {
  return guarded([&] {
    const char* fn = "sp_simulation_live_indicators";
    require(simulation != nullptr, fn, "simulation is NULL");
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
    require(simulation != nullptr, fn, "simulation is NULL");
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
