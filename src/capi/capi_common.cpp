// The C API's shared machinery: the thread's last error, and the registry
// of live handles that turns use-after-destroy into an error code.
#include <array>
#include <mutex>
#include <unordered_map>

#include "capi/capi_internal.h"
#include "sp_types.h"

namespace sp::capi {
namespace {

thread_local std::string g_last_error;

// handle -> the sound scene it owns (nullptr for none), per kind.
struct Registry {
  std::mutex mutex;
  std::array<std::unordered_map<const void*, const sp_sound_scene*>, kHandleKinds> live;

  auto& of(HandleKind kind) { return live[static_cast<std::size_t>(kind)]; }
};

// Never destroyed: a host may destroy handles from its own static
// destructors, which can run after ours.
Registry& registry() {
  static Registry* instance = new Registry;
  return *instance;
}

}  // namespace

sp_result fail(sp_result code, const char* message) noexcept {
  try {
    g_last_error = message;
  } catch (...) {
    g_last_error.clear();  // no allocation: keeps the capacity
  }
  return code;
}

sp_result to_result(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::InvalidArgument:
      return SP_ERROR_INVALID_ARGUMENT;
    case ErrorCode::InvalidScene:
      return SP_ERROR_INVALID_SCENE;
    case ErrorCode::InvalidConfig:
      return SP_ERROR_INVALID_CONFIG;
    case ErrorCode::Io:
      return SP_ERROR_IO;
    case ErrorCode::Vulkan:
      return SP_ERROR_VULKAN;
    case ErrorCode::LimitExceeded:
      return SP_ERROR_LIMIT_EXCEEDED;
  }
  return SP_ERROR_INTERNAL;
}

void register_handle(HandleKind kind, const void* handle, const sp_sound_scene* owned) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  r.of(kind).emplace(handle, owned);
  if (owned == nullptr) return;
  try {
    r.of(HandleKind::SoundScene).emplace(owned, nullptr);
  } catch (...) {
    r.of(kind).erase(handle);  // all or nothing
    throw;
  }
}

bool unregister_handle(HandleKind kind, const void* handle) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  auto& handles = r.of(kind);
  const auto found = handles.find(handle);
  if (found == handles.end()) return false;
  // The owned sound scene's address comes from the registry, not from
  // `handle`, which is only trusted once found.
  if (found->second != nullptr) r.of(HandleKind::SoundScene).erase(found->second);
  handles.erase(found);
  return true;
}

bool is_live(HandleKind kind, const void* handle) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  return r.of(kind).contains(handle);
}

void require_live(HandleKind kind, const void* handle, const char* function, const char* what) {
  if (handle == nullptr) throw_invalid(function, std::string(what) + " is NULL");
  if (!is_live(kind, handle))
    throw_invalid(function, std::string(what) + " handle is not live (destroyed or never created)");
}

void OneThreadAtATime::claim(const char* function) const {
  if (busy_.exchange(true, std::memory_order_acquire))
    throw_invalid(function,
                  "another thread is inside a call on this handle; stepping, reading indicators and stats, "
                  "recording and destroying must come from one thread at a time (soundpaint.h, Thread-safety)");
}

BackendChoice backend_choice(sp_backend backend, const char* function) {
  switch (backend) {
    case SP_BACKEND_CPU:
      return BackendChoice::Cpu;
    case SP_BACKEND_GPU:
      return BackendChoice::Gpu;
    case SP_BACKEND_AUTO:
      return BackendChoice::Auto;
  }
  throw_invalid(function, "backend must be SP_BACKEND_CPU, SP_BACKEND_GPU or SP_BACKEND_AUTO");
}

World world_from(const sp_scene& scene, const char* config_json, const WorldOptions& options) {
  Config config;
  if (config_json != nullptr) config = unwrap(parse_config(config_json, "config_json"));
  if (options.ray_budget != 0) config.ray_budget = options.ray_budget;
  BvhBuildSettings bvh;
  bvh.threads = options.threads;
  return unwrap(sp::make_world(scene.scene, config, bvh));
}

unsigned thread_count(const sp_context& context, std::uint32_t requested) {
  if (context.max_threads == 0) return requested;
  if (requested == 0) return context.max_threads;
  return requested < context.max_threads ? requested : context.max_threads;
}

sp_context& context_of(sp_context* context, const char* function) {
  require_live(HandleKind::Context, context, function, "context");
  return *context;
}

}  // namespace sp::capi

extern "C" const char* sp_last_error_message(void) noexcept { return sp::capi::g_last_error.c_str(); }
