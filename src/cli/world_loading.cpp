#include "cli/world_loading.h"

#include <cstdio>

#include "gpu/gpu_simulator.h"
#include "check/penetration_probe.h"
#include "soundpaint/check.h"
#include "vk/context.h"

namespace sp::cli {

LoadedWorld load_scene_and_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                                 std::optional<std::uint64_t> seed_override, const SceneLoadOptions& scene_options) {
  Config config;
  if (config_path) config = load_config(*config_path).value();
  if (seed_override) config.seed = static_cast<std::uint32_t>(*seed_override);
  Scene scene = load_scene(scene_path, scene_options).value();
  World world = make_world(scene, config).value();
  return LoadedWorld{std::move(scene), std::move(world)};
}

std::optional<PenetrationProbe> warn_if_penetration_fails(const Scene& scene, const World& world) {
  CheckSettings settings;
  settings.probe_reach = 0.0f;  // what a simulation with this config sees
  const Result<PenetrationProbe> probe =
      capture_errors([&] { return detail::probe_penetration_on(scene, world.config, settings, world.geometry); },
                     ErrorCode::InvalidScene);
  if (!probe) return std::nullopt;  // the scene loaded; the probe's own trouble is no reason to stop
  for (const std::string& warning : {penetration_warning(probe.value()), work_bound_warning(probe.value())})
    if (!warning.empty()) std::fprintf(stderr, "soundpaint: warning: %s\n", warning.c_str());
  return probe.value();
}

BackendChoice parse_backend(const std::string& name) {
  if (name == "cpu") return BackendChoice::Cpu;
  if (name == "gpu") return BackendChoice::Gpu;
  if (name == "auto") return BackendChoice::Auto;
  throw Exception(ErrorCode::InvalidArgument, "option --backend: expected cpu, gpu or auto, got '" + name + "'");
}

const char* backend_name(Backend backend) { return backend == Backend::Gpu ? "gpu" : "cpu"; }

namespace {

// The library decides; the CLI only says why when auto fell back.
std::unique_ptr<Simulator> report(Result<std::unique_ptr<Simulator>> made, const std::string& fallback_reason) {
  if (!made) throw Exception(made.error());
  if (!fallback_reason.empty())
    std::fprintf(stderr, "soundpaint: GPU backend not used (%s); using the CPU backend\n", fallback_reason.c_str());
  return std::move(made.value());
}

}  // namespace

std::unique_ptr<Simulator> create_simulator(World world, BackendChoice backend, unsigned cpu_threads,
                                            std::uint64_t memory_budget) {
  SimulatorSettings settings;
  settings.backend = backend;
  settings.cpu.threads = cpu_threads;
  settings.cpu.memory_budget_bytes = memory_budget;
  settings.gpu.memory_budget_bytes = memory_budget;
  std::string fallback_reason;
  auto made = sp::create_simulator(std::move(world), settings, &fallback_reason);
  return report(std::move(made), fallback_reason);
}

std::unique_ptr<Simulator> create_simulator_on(vk::Context& context, World world, BackendChoice backend,
                                               unsigned cpu_threads, std::uint64_t memory_budget) {
  std::string fallback_reason;
  CpuSettings cpu;
  cpu.threads = cpu_threads;
  cpu.memory_budget_bytes = memory_budget;
  auto made = gpu::create_simulator_on(context, std::move(world), backend, cpu, &fallback_reason);
  return report(std::move(made), fallback_reason);
}

}  // namespace sp::cli
