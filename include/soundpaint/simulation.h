// The simulation: a scene and a configuration resolved into a World, and the
// Simulator interface that the CPU and GPU backends implement.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "soundpaint/bvh.h"
#include "soundpaint/config.h"
#include "soundpaint/result.h"
#include "soundpaint/scene.h"
#include "sp_types.h"

namespace sp {

// An indicator (SPEC 1.4). Category is sources[source_id].category.
using Indicator = shader::Indicator;

// Everything a backend needs, resolved once: geometry, per-layer acoustics,
// sources (scene's then config's) and the listener.
struct World {
  Config config;
  Bvh bvh;
  std::vector<std::string> layer_names;
  std::vector<LayerProperties> layer_properties;  // per layer id
  std::vector<std::uint32_t> layer_triangle_counts;
  std::vector<SourceDesc> sources;                // source id == index
  glm::vec3 listener{0.0f};
};

// Resolves scene + config. Errors: no listener (neither a camera in the scene
// nor config.listener), invalid source fields.
Result<World> make_world(const Scene& scene, const Config& config, const BvhBuildSettings& bvh_settings = {});

// Counters of one layer (SPEC 4, --stats).
struct LayerCounters {
  std::uint64_t hits = 0;             // every surface hit on this layer
  std::uint64_t reflections = 0;
  std::uint64_t penetrations = 0;     // every decision to penetrate (backcast misses included)
  std::uint64_t backcast_misses = 0;  // penetrations absorbed because thicker than W_max
};

// Totals over every step run so far.
struct SimulationStats {
  std::uint64_t steps = 0;
  std::uint64_t casts = 0;             // forward casts + backcasts
  std::uint64_t max_casts_per_step = 0;
  std::uint64_t rays_emitted = 0;
  std::uint64_t indicators = 0;        // every indicator created
  std::vector<LayerCounters> layers;   // per layer id
};

enum class Backend { Cpu, Gpu };

struct GpuSettings {
  bool validation = false;  // Khronos validation layer (also SOUNDPAINT_VALIDATION=1)
  std::string device_name;  // substring of the device to use; empty: SOUNDPAINT_DEVICE, else the best
  // Accept a device that is a CPU in disguise (lavapipe / llvmpipe). When
  // false and that is all there is, creation fails with ErrorCode::Vulkan:
  // the CPU backend is faster on the same cores.
  bool allow_cpu_device = true;
};

struct CpuSettings {
  unsigned threads = 0;  // worker threads; 0: std::thread::hardware_concurrency()
};

// A running simulation. Not thread-safe: call from one thread at a time.
class Simulator {
 public:
  virtual ~Simulator() = default;

  virtual Backend backend() const = 0;

  // What runs the simulation: the device and driver for the GPU backend,
  // the thread count for the CPU backend.
  virtual std::string device_description() const = 0;
  virtual const World& world() const = 0;

  // Runs the next step (registry, distribution, propagation). Step n runs at
  // time n * dt. Returns an error only for device failures.
  virtual Result<bool> step() = 0;

  // Steps run so far (== the index of the next step).
  virtual std::uint64_t steps_run() const = 0;

  // Moves the listener (metres) for the following steps. Error if not finite.
  virtual Result<bool> set_listener(glm::vec3 position) = 0;

  // Makes `source_id` play for `duration` seconds from the next step on,
  // regardless of its emission pattern. Error on an unknown id or a negative
  // or non-finite duration.
  virtual Result<bool> play(std::uint32_t source_id, double duration) = 0;

  // The indicators created by the last step, in canonical order
  // (iteration, then ray index). May read back from the device.
  virtual Result<std::vector<Indicator>> last_step_indicators() = 0;

  // The ring buffer's indicators that are still visible (age below
  // indicator_lifetime), oldest first.
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

// Opacity of an indicator of the given age (SPEC 1.4).
float indicator_opacity(const Indicator& indicator, double age_seconds, float lifetime_seconds);

}  // namespace sp
