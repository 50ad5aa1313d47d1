// What the C API's translation units share: the handle structs, the live
// handle registry, and the guard that turns every C++ error into an
// sp_result plus the thread's last error message.
#pragma once

#include <atomic>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "capi/context.h"
#include "soundpaint/config.h"
#include "soundpaint/result.h"
#include "soundpaint/scene.h"
#include "sim/sound_scene_backend.h"
#include "soundpaint/simulation.h"
#include "soundpaint/soundpaint.h"
#include "sp_types.h"

namespace sp::capi {

// The calls on one simulation or visualizer that must come from one thread
// at a time (stepping, reading indicators and stats, recording, destroying):
// a thread that enters while another is inside gets an InvalidArgument
// error naming both rules instead of a data race. Nobody waits: it is a
// detector, not a lock. Entering and leaving order the calls as a mutex
// would, so a host may move these calls from thread to thread between them.
class OneThreadAtATime {
 public:
  // Leaves on destruction.
  class Scope {
   public:
    explicit Scope(const OneThreadAtATime& owner) : owner_(owner) {}
    ~Scope() { owner_.busy_.store(false, std::memory_order_release); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    const OneThreadAtATime& owner_;
  };

  // Throws InvalidArgument (naming `function`) when another thread is inside.
  [[nodiscard]] Scope enter(const char* function) const {
    claim(function);
    return Scope(*this);
  }
  // Enters, and makes the calling thread the one that steps `scene`
  // (SoundScene's debug thread check), which it is until it leaves.
  [[nodiscard]] Scope enter(const char* function, sp::SoundScene& scene) const {
    claim(function);
    sp::detail::SoundSceneBackend::hand_over_to_calling_thread(scene);
    return Scope(*this);
  }
  // Enters without leaving: for destroy, after which there is nothing to leave.
  void claim(const char* function) const;

 private:
  mutable std::atomic<bool> busy_{false};
};

}  // namespace sp::capi

// Every handle holds its context (context.h), whose allocator gave its memory.
struct sp_scene {
  sp::capi::ContextRef context;
  sp::Scene scene;
};

// Borrowed from a simulation or visualizer, which keeps it as a member: its
// address is stable and it is registered and unregistered with its owner.
struct sp_sound_scene {
  sp::SoundScene* scene = nullptr;  // the owner's
};

struct sp_simulation {
  sp::capi::ContextRef context;
  std::unique_ptr<sp::Simulator> simulator;
  sp_sound_scene sound_scene;
  sp::capi::OneThreadAtATime stepping;  // step, live_indicators, stats, destroy
};

namespace sp::capi {

// Records `message` as the thread's last error and returns `code`; never throws.
sp_result fail(sp_result code, const char* message) noexcept;
sp_result to_result(ErrorCode code) noexcept;

[[noreturn]] inline void throw_error(const Error& error) { throw Exception(error); }

template <class T>
T unwrap(Result<T>&& result) {
  if (!result.ok()) throw_error(result.error());
  return std::move(result).value();
}

[[noreturn]] inline void throw_invalid(const char* function, const std::string& what) {
  throw Exception(ErrorCode::InvalidArgument, std::string(function) + ": " + what);
}

inline void require(bool condition, const char* function, const char* what) {
  if (!condition) throw_invalid(function, what);
}

// Runs body() and turns every exception into a result and message.
template <class Fn>
sp_result guarded(Fn&& body) noexcept {
  try {
    body();
    return SP_OK;
  } catch (const Exception& e) {
    return fail(to_result(e.error().code), e.what());
  } catch (const std::bad_alloc&) {
    return fail(SP_ERROR_OUT_OF_MEMORY, "out of memory");
  } catch (const std::exception& e) {
    return fail(SP_ERROR_INTERNAL, e.what());
  } catch (...) {
    return fail(SP_ERROR_INTERNAL, "unknown internal error");
  }
}

// guarded(), and a failure also goes to `context`'s log when the body set
// it (to the context of the call, or of the handle once found live).
template <class Fn>
sp_result guarded_in(sp_context* const& context, Fn&& body) noexcept {
  const sp_result result = guarded(std::forward<Fn>(body));
  if (result != SP_OK && context != nullptr) log(*context, SP_LOG_ERROR, sp_last_error_message());
  return result;
}

// The context a *_in call names: NULL is refused (the entry points without
// `_in` use the default context), a context not live too.
sp_context& context_of(sp_context* context, const char* function);

// --- Live handles ---
// Each kind has its own set, so a sound scene that is a simulation's member
// never collides with another kind of handle at the same address.
enum class HandleKind { Scene, Simulation, Visualizer, SoundScene, Signal, Context };
inline constexpr int kHandleKinds = 6;

// Makes `handle` live, with the sound scene it owns (if any) live with it.
// Throws std::bad_alloc, registering nothing.
void register_handle(HandleKind kind, const void* handle, const sp_sound_scene* owned = nullptr);
// Makes `handle` and its owned sound scene not live; false when `handle`
// was not live (nothing changes). Only the address is used, never read.
bool unregister_handle(HandleKind kind, const void* handle);
bool is_live(HandleKind kind, const void* handle);

// Throws InvalidArgument unless `handle` is non-NULL and live; `what` names
// the parameter ("simulation").
void require_live(HandleKind kind, const void* handle, const char* function, const char* what);

// The destroy protocol: NULL is a no-op, a handle not live an error,
// otherwise unregister, then delete.
template <class T>
void destroy_handle(HandleKind kind, T* handle, const char* function, const char* what) {
  if (handle == nullptr) return;
  if (!unregister_handle(kind, handle))
    throw_invalid(function, std::string(what) + " handle is not live (destroyed or never created)");
  delete_handle(handle);
}

// The scene behind a live handle; throws InvalidArgument otherwise.
inline SoundScene& scene_of(const sp_sound_scene* scene, const char* function) {
  require_live(HandleKind::SoundScene, scene, function, "scene");
  return *scene->scene;
}

// The destroy protocol of a handle that one thread uses at a time (a
// simulation steps, a visualizer records): not while that thread is inside
// a call on it (`guard`, claimed for good), then as destroy_handle.
template <class Owner, class Guard>
void destroy_guarded_handle(HandleKind kind, Owner* owner, Guard Owner::*guard, const char* function,
                            const char* what) {
  if (owner != nullptr && is_live(kind, owner)) (owner->*guard).claim(function);
  destroy_handle(kind, owner, function, what);
}

// *out = the sound scene a live simulation or visualizer owns (the
// `sp_*_scene` getters); `what` names the owner's parameter.
template <class Owner>
void hand_out_scene(HandleKind kind, Owner* owner, sp_sound_scene** out, const char* function, const char* what) {
  require_live(kind, owner, function, what);
  require(out != nullptr, function, "out is NULL");
  *out = &owner->sound_scene;
}

// The backend, checked (the enum comes from C and may hold anything).
BackendChoice backend_choice(sp_backend backend, const char* function);

// config_json (NULL: defaults) and scene resolved into a World, as both
// sp_simulation_create and sp_visualizer_create start.
// What a C caller's options change in the World it gets.
struct WorldOptions {
  unsigned threads = 0;          // of the BVH build; 0: one per core
  std::uint32_t ray_budget = 0;  // replaces the config's; 0: the config's
};
World world_from(const sp_scene& scene, const char* config_json, const WorldOptions& options = {});

// Threads a simulation of `context` may use: `requested` (0: as many as
// the context allows) capped by the context's max_threads; 0: one per core.
unsigned thread_count(const sp_context& context, std::uint32_t requested);

}  // namespace sp::capi
