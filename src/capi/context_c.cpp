// sp_context (soundpaint.h, "Contexts"): creation from versioned settings,
// the default context of the entry points without one, the allocator and
// log routing every handle uses, and the struct_size rule of sized structs.
#include "capi/context.h"

#include <cstdlib>
#include <string>

#include "capi/capi_internal.h"

namespace sp::capi {

sp_context& default_context() noexcept {
  // Never destroyed: handles made without a context may outlive our static
  // destructors (a host's own statics destroying them at exit).
  static sp_context* instance = new sp_context;
  return *instance;
}

void* allocate(sp_context& context, std::size_t size, std::size_t alignment) {
  void* memory = nullptr;
  if (context.allocator.allocate != nullptr) {
    memory = context.allocator.allocate(context.allocator.user_data, size, alignment);
  } else {
    // malloc's alignment covers every handle (none is over-aligned).
    static_assert(alignof(std::max_align_t) >= 16);
    memory = std::malloc(size);
  }
  if (memory == nullptr) throw std::bad_alloc();
  return memory;
}

void release(sp_context& context, void* memory) noexcept {
  if (context.allocator.free != nullptr) context.allocator.free(context.allocator.user_data, memory);
  else std::free(memory);
}

void log(const sp_context& context, sp_log_level level, const char* message) noexcept {
  if (context.log != nullptr) context.log(context.log_user_data, level, message);
}

void release_reference(sp_context* context) noexcept {
  if (context->references.fetch_sub(1, std::memory_order_acq_rel) != 1) return;
  // The default context holds its own reference forever, so never gets here.
  const sp_allocator allocator = context->allocator;
  context->~sp_context();
  if (allocator.free != nullptr) allocator.free(allocator.user_data, context);
  else std::free(context);
}

void require_struct_size(std::uint32_t size, std::size_t known, const char* function, const char* what) {
  const std::string name(what);
  if (size == 0) throw_invalid(function, name + "->struct_size is 0: fill the struct with its _init function first");
  if (size != known)
    throw_invalid(function, name + "->struct_size is " + std::to_string(size) + " but this soundpaint (" +
                                std::to_string(SOUNDPAINT_VERSION_MAJOR) + "." +
                                std::to_string(SOUNDPAINT_VERSION_MINOR) + "." +
                                std::to_string(SOUNDPAINT_VERSION_PATCH) + ") knows only " + std::to_string(known) +
                                " bytes: fill it with its _init function, and compile against the headers of the "
                                "library you run");
}

}  // namespace sp::capi

namespace {

using sp::capi::guarded;
using sp::capi::require;
using sp::capi::throw_invalid;

constexpr std::uint32_t kKnownContextFlags = SP_CONTEXT_VULKAN_VALIDATION;

// What sp_context_create checks before it allocates: every problem named.
void check_settings(const sp_context_settings* settings, sp_context** out, const char* fn) {
  require(settings != nullptr, fn, "settings is NULL");
  require(out != nullptr, fn, "out is NULL");
  sp::capi::require_struct_size(settings->struct_size, sizeof(sp_context_settings), fn, "settings");
  const std::uint32_t major = settings->version >> 16;
  if (major != SOUNDPAINT_VERSION_MAJOR)
    throw_invalid(fn, "settings->version asks for soundpaint " + std::to_string(major) + "." +
                          std::to_string((settings->version >> 8) & 0xFFu) + "." +
                          std::to_string(settings->version & 0xFFu) + " but this library is " +
                          std::to_string(SOUNDPAINT_VERSION_MAJOR) + "." + std::to_string(SOUNDPAINT_VERSION_MINOR) +
                          "." + std::to_string(SOUNDPAINT_VERSION_PATCH) +
                          ": major versions differ (set version to SOUNDPAINT_VERSION)");
  // A host built against a newer minor version may use what this one lacks.
  if (settings->version > SOUNDPAINT_VERSION)
    throw_invalid(fn, "settings->version " + std::to_string(settings->version) +
                          " is newer than this library's SOUNDPAINT_VERSION " + std::to_string(SOUNDPAINT_VERSION));
  if ((settings->allocator.allocate == nullptr) != (settings->allocator.free == nullptr))
    throw_invalid(fn, "settings->allocator needs both allocate and free, or neither (malloc and free)");
  if ((settings->flags & ~kKnownContextFlags) != 0)
    throw_invalid(fn, "settings->flags has unknown bits " + std::to_string(settings->flags & ~kKnownContextFlags));
}

}  // namespace

extern "C" {

uint32_t sp_get_version(void) noexcept { return SOUNDPAINT_VERSION; }

void sp_context_settings_init(sp_context_settings* settings) noexcept {
  if (settings == nullptr) return;
  *settings = sp_context_settings{};
  settings->struct_size = sizeof(sp_context_settings);
  settings->version = SOUNDPAINT_VERSION;
}

sp_result sp_context_create(const sp_context_settings* settings, sp_context** out) noexcept {
  const sp_result result = guarded([&] {
    const char* fn = "sp_context_create";
    check_settings(settings, out, fn);
    sp_context staging;  // only to reach the allocator the context lives in
    staging.allocator = settings->allocator;
    void* memory = sp::capi::allocate(staging, sizeof(sp_context), alignof(sp_context));
    auto* context = new (memory) sp_context;
    context->log = settings->log;
    context->log_user_data = settings->log_user_data;
    context->allocator = settings->allocator;
    context->max_threads = settings->max_threads;
    context->flags = settings->flags;
    try {
      sp::capi::register_handle(sp::capi::HandleKind::Context, context);
    } catch (...) {
      sp::capi::release_reference(context);
      throw;
    }
    *out = context;
  });
  // The host's log hears why its context was refused, when it got that far.
  if (result != SP_OK && settings != nullptr && settings->log != nullptr &&
      settings->struct_size == sizeof(sp_context_settings))
    settings->log(settings->log_user_data, SP_LOG_ERROR, sp_last_error_message());
  return result;
}

sp_result sp_context_destroy(sp_context* context) noexcept {
  return guarded([&] {
    if (context == nullptr) return;
    if (!sp::capi::unregister_handle(sp::capi::HandleKind::Context, context))
      throw_invalid("sp_context_destroy", "context handle is not live (destroyed or never created)");
    sp::capi::release_reference(context);  // objects made in it keep it until they go
  });
}

}  // extern "C"
