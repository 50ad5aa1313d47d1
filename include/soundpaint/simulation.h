// The simulation: the Simulator interface that the CPU and GPU backends
// implement, its settings and its counters. World (world.h) and
// SoundScene (sound_scene.h) come with it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "soundpaint/export.h"
#include "soundpaint/result.h"
#include "soundpaint/sound_scene.h"
#include "soundpaint/world.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

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
  // Threads per workgroup of the simulation's kernels; 0 (the default): the
  // device's choice, 64 on a GPU and the subgroup width on a CPU device
  // (lavapipe), which runs a workgroup's invocations in turn, every branch
  // of them, so a partly empty one costs in full (wider only if the ray
  // budget needs it). Otherwise a multiple of the device's subgroup width
  // within its limits, else creation fails (InvalidArgument). The results
  // do not depend on it.
  std::uint32_t workgroup_size = 0;
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

  // Takes other settings from the next step on, between steps, on the
  // thread that steps; no new World or simulator, and the level is not
  // built again (a first switch to diffraction finds the edges sound bends
  // round, once for every world of the level).
  // Changes: every key of `config` but those below (ray budget and its
  // split, bounces, the layers' acoustics, air, diffraction, cues, display,
  // signal law, seed, CPU traversal, ...). Storage sized by ray_budget,
  // max_bounces and max_indicators is resized: the CPU backend's ring, the
  // GPU backend's buffers and descriptor set (its kernels are kept).
  // Stays:
  // - the sources: every slot, whether it came from the scene, from the
  //   config the World was made with or from the host (add_source, emit),
  //   keeps its id, description, play window, voice and what its guide
  //   learned (Config::cues). `config.sources` and `listener_position` are
  //   not read: they seed a new World, and world().config keeps those it
  //   was made with. Change sources and the listener through scene();
  // - the listener, moving parts' transforms, steps_run(), stats() and
  //   last_step_indicators();
  // - the ring's spots, in order, as many of the newest as the new
  //   max_indicators holds (a smaller ring drops those that would have
  //   faded first); they age by the new indicator_lifetime.
  // Called before the first step, the simulator then steps exactly as one
  // created with `config` would (the CPU backend bit for bit).
  // Errors, after which the simulator is exactly as it was: InvalidConfig
  // naming the key (make_world's checks, and a dt other than the running
  // one once a step has run: step n runs at n * dt); LimitExceeded, naming
  // the keys, when the config's rays and indicators could need more than
  // the memory budget the simulator was created with, or (GPU) a buffer
  // beyond a device limit, naming the buffer; Vulkan: a device failure
  // (as after a failed step, go on with a new simulator). A CPU simulator
  // stopped by a failed step returns that step's error.
  virtual Result<bool> set_config(const Config& config) = 0;

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
