// SoundScene: what the host changes while a simulation runs (listener,
// sources, voices, moving parts), from its render and audio threads.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "soundpaint/export.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/world.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// Sources a SoundScene holds unless the world starts with more: one GPU
// step's source table (48 bytes each) then fits one vkCmdUpdateBuffer.
inline constexpr std::uint32_t kDefaultSourceCapacity = 1024;

struct StepPlan;  // src/sim/step_plan.h

// A host-triggered play window [start, end) in seconds (SoundScene::play,
// emit, set_voice), and what the host said of the sound in it.
struct PlayWindow {
  double start = 0.0;
  double end = 0.0;  // end <= start: none; +infinity: until the voice stops
  // The time at which the source's signal (SourceDesc::signal) is at its
  // start: in the window its play position at time t is t - signal_origin.
  double signal_origin = 0.0;
  // A voice's latest level in dB re full scale (set_voice_level); NaN:
  // none, the signal (or the plain loudness) decides.
  double level_db = std::numeric_limits<double>::quiet_NaN();
  float gain = 1.0f;  // a voice's amplitude gain, scaling its level (set_voice)
};

// What an audio engine knows of one voice it plays (SoundScene::set_voice):
// where it is, whether it plays, how loud it is set, and where it is in its
// sound. docs/integrating.md shows where FMOD or Wwise would give it.
struct VoiceState {
  Vec3 position;         // metres, world space
  bool playing = false;  // false: stopped (or paused); nothing is emitted
  float gain = 1.0f;     // linear amplitude factor >= 0 on the level (AL_GAIN, a voice's volume)
  // Seconds into the source's signal at the next step, which then runs on
  // with the steps; negative: keep the running position (a voice that
  // starts now starts at 0).
  double signal_position = -1.0;
};

// The bound on where a moving part may be placed: every vertex a
// transform produces must be finite with |x|, |y|, |z| <= this many metres
// (SoundScene::set_instance_transform). The BVH and the watertight
// triangle test compute in float; their largest products grow as the cube
// of a coordinate (about 1e32 at this bound, float's limit being 3.4e38),
// so geometry within it never overflows the traversal. Levels are
// kilometres across.
inline constexpr float kMaxCoordinate = 1.0e10f;

namespace detail {
struct SceneInbox;    // src/sim/scene_inbox.h
struct SceneCommand;  // src/sim/scene_inbox.h
}  // namespace detail

// What the host changes while a simulation runs: the listener, the sound
// sources (added, moved, recoloured, removed, played, emitted once) and the
// transforms of moving parts. Methods validate their arguments and return an
// InvalidArgument error naming the problem; nothing is half-applied on error.
//
// Threads. A game steps on its render thread and learns of sounds on its
// audio thread (an FMOD/Wwise callback, its own mixer). So:
// - "Any thread": set_listener, add_source, update_source, move_source,
//   remove_source, play, emit, set_signal, set_voice, set_voice_level,
//   feed_voice and set_instance_transform check their
//   arguments at once (errors as documented) and queue the change under a
//   mutex; the next step takes the queue at its start, before it plans or
//   refits, and applies the changes in call order. They never wait for a
//   step, only for another call's short turn at the mutex (and they may
//   allocate). Ids are decided at the call: add_source and emit return the
//   slot they reserved, and a removed id is free for the next call at once.
//   listener, has_source, source_slot_count, source_capacity,
//   instance_count and geometry_pending are answered as the queued changes
//   will leave the scene, from any thread.
// - "The thread that steps": world() and set_display. world() is the World
//   the steps trace, changed only by the thread that steps, when a step
//   takes the queue: read it there, between steps (a change made since
//   shows from the next step on). Debug builds (NDEBUG undefined) abort
//   with a message when another thread calls these after the first step.
// Destroying the simulation (and this scene) while another thread is
// inside one of these calls is undefined behaviour.
class SoundScene {
 public:
  // `world` as make_world made it (a simulator makes its scene from it):
  // one whose per-source or per-instance tables disagree, made or edited by
  // hand, is refused with sp::Exception (InvalidArgument, naming the
  // tables), which the simulators' create functions return as their error.
  explicit SoundScene(World world);
  ~SoundScene();
  // Shared with other threads by address: it stays where it was made.
  SoundScene(const SoundScene&) = delete;
  SoundScene& operator=(const SoundScene&) = delete;

  // The thread that steps only (see above).
  const World& world() const;

  // Any thread. The latest set_listener's position (the world's until then).
  Vec3 listener() const;
  // Any thread.
  std::uint32_t source_capacity() const { return capacity_; }
  // Any thread: whether `id` is a live source once the queued changes are
  // applied (an added id at once, a removed one no longer).
  bool has_source(std::uint32_t id) const;
  // Any thread: source ids are below this (live or not, has_source tells).
  std::uint32_t source_slot_count() const;

  // Any thread. Moves the listener from the next step on.
  Result<bool> set_listener(Vec3 position);

  // Any thread. Adds a source and returns its id: the lowest free slot (ids
  // of removed sources are reused). LimitExceeded when source_capacity()
  // are live.
  Result<std::uint32_t> add_source(const SourceDesc& source);
  // Any thread. Replaces everything about a source: position, colour,
  // category, range (max_distance), loudness and emission pattern.
  Result<bool> update_source(std::uint32_t id, const SourceDesc& source);
  // Any thread.
  Result<bool> move_source(std::uint32_t id, Vec3 position);
  // Any thread. The source stops emitting; its indicators already drawn
  // fade as usual.
  Result<bool> remove_source(std::uint32_t id);

  // Any thread. Makes a source play for `duration` seconds from the next
  // step on, whatever its emission pattern says: "this sound just started"
  // from a game's audio engine (FMOD/Wwise callback, the engine's own mixer).
  Result<bool> play(std::uint32_t id, double duration);
  // Any thread. Attaches the sound a source plays (SourceDesc::signal and
  // ::loop); a null signal detaches it (E0 is then its loudness).
  Result<bool> set_signal(std::uint32_t id, std::shared_ptr<const Signal> signal, bool loop);

  // The voice API (docs/integrating.md#voices). A voice is a source whose
  // playing the host's audio engine tells, call by call, rather than a
  // pattern: add it with duration 0 (silent by pattern), then give its
  // state whenever it changes or once a frame. Any thread: its position,
  // whether it plays (from the next step until a call says it stopped),
  // its gain and where it is in its signal.
  Result<bool> set_voice(std::uint32_t id, const VoiceState& state);
  // Any thread: the level of what the voice plays now, in dB re full scale
  // (before its gain), as a mixer or DSP callback measures it; it holds
  // until the next level, and overrides the source's signal. -infinity is
  // silence; NaN hands the level back to the signal. Errors: +infinity.
  Result<bool> set_voice_level(std::uint32_t id, double level_db);
  // Any thread: set_voice_level with the RMS level of one block of the
  // voice's samples (interleaved float, full scale 1): what a DSP callback
  // calls with each block it processes (a few ms to a frame of sound).
  Result<bool> feed_voice(std::uint32_t id, std::span<const float> samples);

  // Any thread. A one-shot sound: a source that plays `source` for
  // `duration` seconds from the next step on, then removes itself. Its
  // pattern fields are ignored. Returns its id (valid until it ends).
  Result<std::uint32_t> emit(const SourceDesc& source, double duration);

  // The thread that steps only (see above). How indicators are drawn (the
  // config's `display`): checked, then applied at once (after the queued
  // changes) to world().config.display. Sources without a colour of their
  // own take their category's colour in the new palette from the next step
  // on. Errors: InvalidConfig naming the key.
  Result<bool> set_display(const DisplaySettings& settings);

  // Any thread. Places moving part `instance` (Scene::instance_names) at
  // `transform` applied to its rest pose (the vertices the scene gave): a
  // door swings by a rotation about its hinge. The BVH is refitted before
  // the next step. Errors (InvalidArgument, naming the instance and the
  // vertex; the previous transform stays): an unknown instance, a
  // non-finite matrix, or one that would place a vertex of the part
  // outside kMaxCoordinate or at a non-finite position (a finite but huge
  // scale, say), which the BVH could not hold.
  Result<bool> set_instance_transform(std::uint32_t instance, const Mat4& transform);
  // Any thread.
  std::uint32_t instance_count() const { return static_cast<std::uint32_t>(instance_triangles_.size()); }

  // Any thread: true from a set_instance_transform until the next step
  // takes it to refit the BVH.
  bool geometry_pending() const;

 private:
  // Used by the backends through detail::SoundSceneBackend, on the thread
  // that steps; a host never calls these (on a visualizer's scene,
  // update_geometry would race with the CPU backend's worker).
  friend struct detail::SoundSceneBackend;
  // The plan of step `step`: takes the queued changes, ends one-shot
  // sources whose sound is over, then lists the playing sources and their
  // rays. Steps are planned in increasing order.
  void plan(std::uint64_t step, StepPlan& out);
  // Takes the queued changes, then moves pending instance transforms into
  // the BVH: a refit, or a rebuild when refits have doubled its SAH cost.
  // Returns what changed (nothing when nothing moved). Must not run while
  // a step reads the BVH.
  BvhChanges update_geometry();
  // Simulator::set_config's change to the World, already checked and
  // resolved (src/sim/config_change.h): takes the queued changes first, as
  // set_display does, then replaces the config and the layers' acoustics
  // and re-resolves the sources' colours in the new palette. The sources,
  // play windows, voices, listener and moving parts stay as they are.
  void apply_config(Config config, std::vector<LayerProperties> layer_properties);

  // With the inbox's mutex held: applies the queued changes to world_.
  void take_changes();
  void apply(detail::SceneCommand& command);
  void end_source(std::uint32_t id);
  void apply_voice(std::uint32_t id, const VoiceState& state, double t);
  void note_stepping_thread();
  double next_step_time() const { return static_cast<double>(next_step_) * world_.config.dt; }
  // With the inbox's mutex held: InvalidArgument unless `id` is live.
  Result<bool> check_id(const char* what, std::uint32_t id) const;
  Result<std::uint32_t> add_slot(const char* what, const SourceDesc& source, bool one_shot, double duration);
  Result<bool> enqueue(detail::SceneCommand command);

  // Written only by the thread that steps:
  World world_;
  std::vector<PlayWindow> play_windows_;  // per source id
  std::vector<bool> one_shot_;            // per source id: emitted, ends with its window
  std::uint64_t next_step_ = 0;
  bool geometry_pending_ = false;  // a transform was applied, the BVH not yet refitted
  // Fixed at construction, read by any thread:
  std::uint32_t capacity_ = 0;
  std::vector<std::vector<std::uint32_t>> instance_triangles_;  // per instance
  // The queue and the slots as the host sees them (own mutex).
  std::unique_ptr<detail::SceneInbox> inbox_;
};

}  // namespace sp

SP_CPP_API_END
