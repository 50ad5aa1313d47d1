// The simulation: a scene and a configuration resolved into a World, and the
// Simulator interface that the CPU and GPU backends implement.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/math.h"
#include "soundpaint/result.h"
#include "soundpaint/scene.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// Indicator::kind values.
inline constexpr std::uint32_t kIndicatorHit = 0;   // a ray struck a surface
inline constexpr std::uint32_t kIndicatorExit = 1;  // a ray left matter it had crossed

// An indicator (docs/model.md#indicators): a cue painted where a ray met a
// surface. Category is sources[source_id].category. 96 bytes, laid out as
// the GPU's ring buffer holds them.
struct Indicator {
  Vec3 position;
  float energy = 0.0f;
  Vec3 normal;        // facing the side the ray came from (hit) or leaves to (exit)
  float size = 0.0f;  // metres: indicator_size * E / E0
  Vec3 color;         // linear RGB
  float intensity = 0.0f;
  Vec3 dir;                  // the ray's direction of travel: incoming (hit), outgoing (exit)
  float path_length = 0.0f;  // metres from the source
  std::uint32_t kind = kIndicatorHit;
  std::uint32_t source_id = 0;
  std::uint32_t bounces = 0;
  std::uint32_t penetrations = 0;
  std::uint32_t diffractions = 0;
  std::uint32_t step = 0;
  std::uint32_t ray_index = 0;
  std::uint32_t iteration = 0;
  // What reaches the player (docs/model.md#cues-for-the-player), with
  // Config::cues.listen: the unit direction from the listener to this spot,
  // the way its sound arrives, and the energy that arrives along it, 0 when
  // the listener does not hear it (its surface faces away, the way is
  // blocked, or no more than tau_min would arrive).
  Vec3 arrival;
  float heard_energy = 0.0f;
  std::uint32_t emit_cell = 0;    // the guide cell its ray was emitted into
  std::uint32_t source_slot = 0;  // its source's entry in its step's source table
  float toward = 0.0f;            // in [0, 1]: how nearly `arrival` points at its source; 0 when not heard
  std::uint32_t reserved = 0;
};

// How make_world builds its BVH (binned SAH).
inline constexpr std::uint32_t kBvhMaxDepth = 32;  // the traversal stack's depth
struct BvhBuildSettings {
  std::uint32_t bins = 16;          // SAH bins per axis and split
  std::uint32_t max_leaf_size = 4;  // leaves never hold more unless the depth cap forces it
  // SAH cost of visiting a node, relative to one triangle test. 3 makes
  // leaves of up to four triangles, which the CPU tests as one packet:
  // casts 3-7 % faster than with 1 (leaves of two), 25 % at 1M triangles,
  // on bench/RESULTS.md section 22's machine.
  float traversal_cost = 3.0f;
  std::uint32_t max_depth = kBvhMaxDepth;  // levels including the root; <= kBvhMaxDepth
  // Threads the build may use: 0 means std::thread::hardware_concurrency(),
  // 1 builds on the calling thread only. Subtrees near the root are built
  // concurrently and spliced in a fixed order, so the result (nodes,
  // triangles, depth) is byte-identical for every value.
  unsigned threads = 0;
};

struct BvhChanges;  // src/bvh/bvh.h
namespace detail {
struct WorldGeometry;      // src/sim/world_geometry.h
struct SoundSceneBackend;  // src/sim/sound_scene_backend.h
}  // namespace detail

// The level's geometry a backend traces (the BVH, which triangles form one
// solid, the rest pose of moving parts and what rebuilding needs, and, once
// a world with diffraction asks, the edges sound bends round), opaque
// outside the library. Built once (build_geometry) and shared: copies of a
// handle, and the Worlds, simulators, visualizers and probes made from
// them, read one geometry; only a scene whose moving parts move gets a copy
// of its own, when they first move. A moved-from handle holds no geometry
// and reads as an empty one (no triangles).
class WorldGeometryHandle {
 public:
  WorldGeometryHandle();
  ~WorldGeometryHandle();
  WorldGeometryHandle(const WorldGeometryHandle& other);
  WorldGeometryHandle& operator=(const WorldGeometryHandle& other);
  WorldGeometryHandle(WorldGeometryHandle&& other) noexcept;
  WorldGeometryHandle& operator=(WorldGeometryHandle&& other) noexcept;

  const detail::WorldGeometry& operator*() const;
  const detail::WorldGeometry* operator->() const { return &**this; }
  // The geometry to change (moving parts), this handle's own: copied first
  // when it is shared, so that no other holder sees the change.
  detail::WorldGeometry& mutate();
  // Whether the two read the same geometry.
  bool shares_with(const WorldGeometryHandle& other) const { return geometry_ == other.geometry_; }

 private:
  std::shared_ptr<detail::WorldGeometry> geometry_;
};

// Everything a backend needs, resolved once: geometry, per-layer acoustics,
// sources (scene's then config's) and the listener. A running simulation
// keeps its World in a SoundScene, which changes sources and moving parts.
struct World {
  Config config;
  std::vector<std::string> layer_names;
  std::vector<LayerProperties> layer_properties;  // per layer id
  std::vector<std::uint32_t> layer_triangle_counts;
  std::vector<SourceDesc> sources;  // source id == index
  // Per source id: its category's index in category_names (built-in
  // categories first, then others in order of first appearance), and the
  // colour its indicators carry: its own, else its category's palette
  // colour. Kept up to date by make_world and SoundScene.
  std::vector<std::uint32_t> source_categories;
  std::vector<Vec3> source_colors;
  std::vector<std::string> category_names;
  // Per source id: false once removed (SoundScene::remove_source); the slot
  // keeps its last description and a later add_source may reuse it.
  std::vector<bool> source_active;
  Vec3 listener;

  // Moving parts (Scene::instance_names); empty when the scene has none.
  // Kept so that an instance transform can re-place its triangles.
  std::vector<std::string> instance_names;
  std::vector<Mat4> instance_transforms;  // per instance, applied to the rest pose

  // The triangles and their BVH, opaque.
  WorldGeometryHandle geometry;
  std::size_t triangle_count() const;
};

// Resolves scene + config. Errors: no listener (neither a camera in the scene
// nor config.listener), invalid source fields, a config value out of range
// (InvalidConfig naming the key, as the JSON reader does). Builds the
// level's geometry: to make several worlds of one level (other settings,
// another backend, a probe), build it once with build_geometry and use the
// overload below.
Result<World> make_world(const Scene& scene, const Config& config, const BvhBuildSettings& bvh_settings = {});

// The level's geometry, built once: weld and topology, the BVH, and what
// moving parts need (the edges diffraction needs are built when a world
// first asks). Errors: InvalidScene as make_world.
Result<WorldGeometryHandle> build_geometry(const Scene& scene, const BvhBuildSettings& bvh_settings = {});

// A World for `scene` and `config` around `geometry`, built from the same
// scene: nothing is built again (diffraction's edges once, the first time
// a world with diffraction on asks). Errors as make_world, and
// InvalidArgument when `geometry` was built from another scene (its
// triangle count differs).
Result<World> make_world(const Scene& scene, const Config& config, WorldGeometryHandle geometry);

// Counters of one layer (--stats; contract: README.md, "Command line").
struct LayerCounters {
  std::uint64_t hits = 0;  // every surface hit on this layer
  std::uint64_t reflections = 0;
  std::uint64_t penetrations = 0;  // every decision to penetrate (no_way_out included)
  // Penetrations that found no way out of matter within W_max (the ray is
  // absorbed); `check`'s no_way_out. Was backcast_misses before 0.2.
  std::uint64_t no_way_out = 0;
  // Rays in air that struck the back of a face: a leak or winding that
  // disagrees with the geometry (docs/model.md#the-back-of-a-face-struck-from-air).
  // Counted in hits too.
  std::uint64_t back_face_hits = 0;
  // Rays that turned round an exposed edge of this layer's faces
  // (docs/model.md#diffraction); 0 while diffraction is off.
  std::uint64_t diffractions = 0;
};

// Totals over every step run so far.
struct SimulationStats {
  std::uint64_t steps = 0;
  std::uint64_t casts = 0;  // closest-hit casts + matter queries
  std::uint64_t max_casts_per_step = 0;
  std::uint64_t rays_emitted = 0;
  std::uint64_t indicators = 0;  // every indicator created
  // Casts that reached the per-cast work bound (SP_MAX_CAST_PACKETS leaf
  // packets) and ended there: 0 on any sane level; many mean a stack of
  // coincident or overlapping triangles (docs/model.md#work-bounds).
  std::uint64_t casts_cut_short = 0;
  // Casts from spots to the listener (docs/model.md#cues-for-the-player):
  // one for each spot whose face turns to the listener with energy enough.
  std::uint64_t connections = 0;
  std::vector<LayerCounters> layers;  // per layer id
};

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

enum class Backend { Cpu, Gpu };

// The default memory budget of a simulator: what its rays and indicators may
// take at worst, estimated from the config at creation (README "Security").
inline constexpr std::uint64_t kDefaultMemoryBudgetBytes = std::uint64_t{2} << 30;

struct GpuSettings {
  bool validation = false;  // Khronos validation layer, synchronization checks included (also SOUNDPAINT_VALIDATION=1)
  std::string device_name;  // substring of the device to use; empty: SOUNDPAINT_DEVICE, else the best
  // Accept a device that is a CPU in disguise (lavapipe / llvmpipe). When
  // false and that is all there is, creation fails with ErrorCode::Vulkan:
  // the CPU backend is faster on the same cores.
  bool allow_cpu_device = true;
  // Creation fails (LimitExceeded) when the config's rays and indicators
  // could need more than this many bytes (host and device together).
  std::uint64_t memory_budget_bytes = kDefaultMemoryBudgetBytes;
};

struct CpuSettings {
  unsigned threads = 0;  // worker threads; 0: std::thread::hardware_concurrency()
  // Creation fails (LimitExceeded) when the config's indicators could need
  // more than this many bytes.
  std::uint64_t memory_budget_bytes = kDefaultMemoryBudgetBytes;
};

// A running simulation. Not thread-safe: call from one thread at a time,
// the thread that steps; except scene() and the set_listener / play
// shorthands, which any thread may call for SoundScene's "any thread"
// calls (a game's audio thread while its render thread steps).
class Simulator {
 public:
  virtual ~Simulator() = default;

  virtual Backend backend() const = 0;

  // What runs the simulation: the device and driver for the GPU backend,
  // the thread count for the CPU backend.
  virtual std::string device_description() const = 0;

  // Threads that cast rays: the CPU backend's pool, the calling thread
  // included (CpuSettings::threads, or one per core); 0 for the GPU backend.
  virtual std::uint32_t thread_count() const { return 0; }

  // Sources, listener and moving parts, changed between steps.
  virtual SoundScene& scene() = 0;
  virtual const SoundScene& scene() const = 0;
  const World& world() const { return scene().world(); }

  // Runs the next step (registry, distribution, propagation). Step n runs at
  // time n * dt. Errors: Vulkan (a device failure), LimitExceeded (the CPU
  // backend ran out of memory). A CPU step that fails stops the simulator:
  // this and every later step() and last_step_indicators() return the same
  // error, while live_indicators() and stats() still describe the steps
  // before it; create a new simulator to go on.
  virtual Result<bool> step() = 0;

  // Steps run so far (== the index of the next step).
  virtual std::uint64_t steps_run() const = 0;

  // Shorthands for scene().set_listener / scene().play.
  Result<bool> set_listener(Vec3 position) { return scene().set_listener(position); }
  Result<bool> play(std::uint32_t source_id, double duration) { return scene().play(source_id, duration); }

  // The indicators created by the last step, in canonical order
  // (iteration, then ray index). May read back from the device.
  virtual Result<std::vector<Indicator>> last_step_indicators() = 0;

  // The ring buffer's indicators that are live, oldest first: exactly those
  // the display draws (a hidden, capped, back-facing or too faint spot
  // aside). A spot is live while its age, (last step run - its step) * dt,
  // is below the display lifetime, max(indicator_lifetime, 1/3 s): no spot
  // is shown for less than 1/3 s, the flash limit
  // (docs/model.md#the-ring-spots-that-live-out-their-lifetime).
  virtual Result<std::vector<Indicator>> live_indicators() = 0;

  // Casts made by the last step (for timing reports).
  virtual std::uint64_t last_step_casts() const = 0;

  // GPU time of the last step from timestamp queries, in milliseconds; empty
  // for the CPU backend or a device without timestamps.
  virtual std::optional<double> last_gpu_ms() const { return std::nullopt; }

  virtual Result<SimulationStats> stats() = 0;
};

// Creates the multithreaded CPU backend.
Result<std::unique_ptr<Simulator>> create_cpu_simulator(World world, const CpuSettings& settings = {});

// Creates the Vulkan compute backend on its own instance and device.
// Errors (ErrorCode::Vulkan): no Vulkan device; (LimitExceeded): the scene or
// ray budget exceeds a device limit (each buffer names itself).
Result<std::unique_ptr<Simulator>> create_gpu_simulator(World world, const GpuSettings& settings = {});

enum class BackendChoice { Cpu, Gpu, Auto };

struct SimulatorSettings {
  BackendChoice backend = BackendChoice::Auto;
  CpuSettings cpu;
  GpuSettings gpu;  // allow_cpu_device is decided by `backend`
};

// Creates a simulator by the backend policy every front end shares.
// Cpu / Gpu: that backend (Gpu takes any Vulkan 1.3 device, lavapipe too).
// Auto: the GPU backend on a hardware GPU, else the CPU backend, which does
// the same work faster on a CPU-type Vulkan device; `fallback_reason`, when
// given, receives why the GPU was not used (left empty when it was). Only a
// missing or unusable device (ErrorCode::Vulkan) falls back: other GPU
// errors, such as a budget beyond a device limit, are returned.
Result<std::unique_ptr<Simulator>> create_simulator(World world, const SimulatorSettings& settings,
                                                    std::string* fallback_reason = nullptr);

// Opacity of an indicator of the given age (docs/model.md#indicators).
float indicator_opacity(const Indicator& indicator, double age_seconds, float lifetime_seconds);

}  // namespace sp

SP_CPP_API_END
