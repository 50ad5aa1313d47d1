// The host's side of a SoundScene: the changes waiting for the next step,
// and the source slots as those changes will leave them. A game makes the
// changes from its audio thread while its render thread steps; each call is
// checked against these slots and queued under `mutex`, and the step takes
// the queue under the same mutex before it reads anything (sound_scene.cpp).
// So the World a step traces is only ever written by the thread that steps.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/math.h"
#include "soundpaint/simulation.h"

namespace sp::detail {

// One queued change each; applied in the order the calls were made.
struct SetListener {
  Vec3 position;
};
// add_source and emit: the slot `id` was taken when the call was made.
struct PutSource {
  std::uint32_t id = 0;
  SourceDesc source;
  bool one_shot = false;
  double duration = 0.0;  // one-shots: seconds from the step that applies it
};
struct UpdateSource {
  std::uint32_t id = 0;
  SourceDesc source;
};
struct MoveSource {
  std::uint32_t id = 0;
  Vec3 position;
};
struct RemoveSource {
  std::uint32_t id = 0;
};
struct PlaySource {
  std::uint32_t id = 0;
  double duration = 0.0;
};
struct SetSignal {
  std::uint32_t id = 0;
  std::shared_ptr<const Signal> signal;
  bool loop = false;
};
struct SetVoice {
  std::uint32_t id = 0;
  VoiceState state;
};
struct SetVoiceLevel {
  std::uint32_t id = 0;
  double level_db = 0.0;
};
struct PlaceInstance {
  std::uint32_t instance = 0;
  Mat4 transform;
};
struct SceneCommand {
  // Built in place (commands.emplace_back(MoveSource{...})): a variant
  // moved out of a temporary trips GCC 12's -Wmaybe-uninitialized at -O2.
  template <class Change>
  explicit SceneCommand(Change change_) : change(std::in_place_type<Change>, std::move(change_)) {}
  std::variant<SetListener, PutSource, UpdateSource, MoveSource, RemoveSource, PlaySource, SetSignal, SetVoice,
               SetVoiceLevel, PlaceInstance>
      change;
};

struct SceneInbox {
  mutable std::mutex mutex;
  // Guarded by `mutex`:
  std::vector<SceneCommand> commands;
  std::vector<bool> slot_taken;   // per source id, once the queue is applied
  std::uint32_t taken = 0;        // count of true in slot_taken
  Vec3 listener;                  // the latest set_listener
  bool transform_queued = false;  // a set_instance_transform waits for the next refit

  // The thread that planned or refitted last (none before the first step):
  // what debug builds compare world()'s caller with.
  std::atomic<std::thread::id> stepping_thread{};

  // The lowest free slot (may be slot_taken.size(), a new one), or nothing
  // when `capacity` are taken.
  std::optional<std::uint32_t> lowest_free(std::uint32_t capacity) const;
  void take(std::uint32_t id);
  void release(std::uint32_t id);
};

// Debug builds (NDEBUG undefined): aborts with a message naming `call` when
// a thread other than the one that steps the scene makes it. Release
// builds: nothing.
void expect_stepping_thread(const SceneInbox& inbox, const char* call);

}  // namespace sp::detail
