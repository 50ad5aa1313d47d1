// SoundScene, the stepping thread's side: at the start of each step the
// queued changes are taken under the inbox's mutex and applied to the World
// in call order; then one-shots that are over end, and the step plans or
// refits from a World no other thread writes.
#include <algorithm>
#include <limits>
#include <mutex>
#include <thread>
#include <type_traits>
#include <variant>

#include "sim/geometry_update.h"
#include "sim/scene_inbox.h"
#include "sim/source_display.h"
#include "sim/step_plan.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"

namespace sp {

void SoundScene::note_stepping_thread() {
  inbox_->stepping_thread.store(std::this_thread::get_id(), std::memory_order_relaxed);
}

void SoundScene::take_changes() {
  for (detail::SceneCommand& command : inbox_->commands) apply(command);
  inbox_->commands.clear();
}

void SoundScene::end_source(std::uint32_t id) {
  world_.source_active[id] = false;
  play_windows_[id] = {};
  one_shot_[id] = false;
}

// A command naming a slot that is no longer live (a one-shot that ended
// after the call was checked) changes nothing: the slot keeps its last
// description, as a removed one does.
void SoundScene::apply(detail::SceneCommand& command) {
  const double t = next_step_time();
  auto live = [&](std::uint32_t id) { return id < world_.sources.size() && world_.source_active[id]; };
  std::visit(
      [&](auto& change) {
        using Change = std::decay_t<decltype(change)>;
        if constexpr (std::is_same_v<Change, detail::SetListener>) {
          world_.listener = change.position;
        } else if constexpr (std::is_same_v<Change, detail::PutSource>) {
          const std::size_t slots = std::max<std::size_t>(world_.sources.size(), std::size_t{change.id} + 1);
          world_.sources.resize(slots);
          world_.source_active.resize(slots, false);
          play_windows_.resize(slots);
          one_shot_.resize(slots, false);
          world_.sources[change.id] = std::move(change.source);
          world_.source_active[change.id] = true;
          play_windows_[change.id] = change.one_shot ? PlayWindow{t, t + change.duration, t} : PlayWindow{};
          one_shot_[change.id] = change.one_shot;
          resolve_source_display(world_, change.id);
        } else if constexpr (std::is_same_v<Change, detail::UpdateSource>) {
          if (!live(change.id)) return;
          SourceDesc& source = world_.sources[change.id];
          const SourceDesc previous = source;
          source = std::move(change.source);
          if (one_shot_[change.id]) {
            // A one-shot keeps sounding by its window only, never by a pattern.
            source.duration = previous.duration;
            source.interval = previous.interval;
            source.phase = previous.phase;
          }
          resolve_source_display(world_, change.id);
        } else if constexpr (std::is_same_v<Change, detail::MoveSource>) {
          if (live(change.id)) world_.sources[change.id].position = change.position;
        } else if constexpr (std::is_same_v<Change, detail::RemoveSource>) {
          if (live(change.id)) end_source(change.id);
        } else if constexpr (std::is_same_v<Change, detail::PlaySource>) {
          if (!live(change.id)) return;
          PlayWindow& window = play_windows_[change.id];
          window.start = t;
          window.end = t + change.duration;
          window.signal_origin = t;  // the sound starts
        } else if constexpr (std::is_same_v<Change, detail::SetSignal>) {
          if (!live(change.id)) return;
          world_.sources[change.id].signal = std::move(change.signal);
          world_.sources[change.id].loop = change.loop;
        } else if constexpr (std::is_same_v<Change, detail::SetVoice>) {
          if (live(change.id)) apply_voice(change.id, change.state, t);
        } else if constexpr (std::is_same_v<Change, detail::SetVoiceLevel>) {
          if (live(change.id)) play_windows_[change.id].level_db = change.level_db;
        } else if constexpr (std::is_same_v<Change, detail::PlaceInstance>) {
          world_.instance_transforms[change.instance] = change.transform;
          geometry_pending_ = true;
        }
      },
      command.change);
}

// A voice plays from the step that learns it started until one learns it
// stopped: an open-ended window, its signal's position kept running
// unless the host says where it is.
void SoundScene::apply_voice(std::uint32_t id, const VoiceState& state, double t) {
  world_.sources[id].position = state.position;
  PlayWindow& window = play_windows_[id];
  window.gain = state.gain;
  const bool sounding = t >= window.start && t < window.end;
  if (state.playing) {
    if (!sounding || window.end != std::numeric_limits<double>::infinity()) {
      window.start = t;
      window.end = std::numeric_limits<double>::infinity();
      window.signal_origin = t;
    }
    if (state.signal_position >= 0.0) window.signal_origin = t - state.signal_position;
  } else if (sounding) {
    window.end = t;
    window.level_db = std::numeric_limits<double>::quiet_NaN();
  }
}

void SoundScene::plan(std::uint64_t step, StepPlan& out) {
  note_stepping_thread();
  next_step_ = step;
  {
    std::lock_guard lock(inbox_->mutex);
    take_changes();
    // A one-shot whose window closed before this step is over: free its
    // slot, here and in the inbox (whose queue is empty now, so the two agree).
    const double t = next_step_time();
    for (std::uint32_t id = 0; id < world_.sources.size(); ++id) {
      if (one_shot_[id] && world_.source_active[id] && t >= play_windows_[id].end) {
        end_source(id);
        inbox_->release(id);
      }
    }
  }
  out = plan_step(world_, step, world_.listener, play_windows_);
  next_step_ = step + 1;
}

BvhChanges SoundScene::update_geometry() {
  note_stepping_thread();
  {
    std::lock_guard lock(inbox_->mutex);
    take_changes();
    inbox_->transform_queued = false;
  }
  if (!geometry_pending_) return {};
  geometry_pending_ = false;
  // The first move gives this scene a geometry of its own (the others that
  // shared it keep the rest pose).
  return move_geometry(world_.geometry.mutate(), world_.instance_transforms);
}

}  // namespace sp
