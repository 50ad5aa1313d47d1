#include "cli/world_loading.h"

#include <cstdio>

#include "gpu/gpu_simulator.h"
#include "vk/context.h"

namespace sp::cli {

LoadedWorld load_scene_and_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                                 std::optional<std::uint64_t> seed_override) {
  Config config;
  if (config_path) config = load_config(*config_path).value();
  if (seed_override) config.seed = static_cast<std::uint32_t>(*seed_override);
  Scene scene = load_scene(scene_path).value();
  World world = make_world(scene, config).value();
  return LoadedWorld{std::move(scene), std::move(world)};
}

World load_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                 std::optional<std::uint64_t> seed_override) {
  return load_scene_and_world(scene_path, config_path, seed_override).world;
}

BackendChoice parse_backend(const std::string& name) {
  if (name == "cpu") return BackendChoice::Cpu;
  if (name == "gpu") return BackendChoice::Gpu;
  if (name == "auto") return BackendChoice::Auto;
  throw Exception(ErrorCode::InvalidArgument, "option --backend: expected cpu, gpu or auto, got '" + name + "'");
}

const char* backend_name(Backend backend) { return backend == Backend::Gpu ? "gpu" : "cpu"; }

std::unique_ptr<Simulator> create_simulator(World world, BackendChoice backend, unsigned cpu_threads) {
  if (backend != BackendChoice::Cpu) {
    // auto wants a real GPU: on a CPU-only Vulkan device (lavapipe) the CPU
    // backend does the same work faster. --backend gpu takes any device.
    GpuSettings settings;
    settings.allow_cpu_device = backend == BackendChoice::Gpu;
    auto gpu = create_gpu_simulator(world, settings);
    if (gpu) return std::move(gpu.value());
    if (backend == BackendChoice::Gpu || gpu.error().code != ErrorCode::Vulkan) throw Exception(gpu.error());
    std::fprintf(stderr, "soundpaint: GPU backend not used (%s); using the CPU backend\n",
                 gpu.error().message.c_str());
  }
  return std::move(create_cpu_simulator(std::move(world), CpuSettings{cpu_threads}).value());
}

std::unique_ptr<Simulator> create_simulator_on(vk::Context& context, World world, BackendChoice backend,
                                               unsigned cpu_threads) {
  // The same policy as create_simulator: auto wants a real GPU, since on a
  // CPU-only Vulkan device the CPU backend does the same work faster.
  const bool cpu_device = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  if (backend == BackendChoice::Auto && cpu_device) {
    std::fprintf(stderr, "soundpaint: GPU backend not used (the only Vulkan device is a CPU device (%s)); "
                 "using the CPU backend\n", context.properties().deviceName);
  } else if (backend != BackendChoice::Cpu) {
    auto gpu = gpu::create_simulator(world, context);
    if (gpu) return std::move(gpu.value());
    if (backend == BackendChoice::Gpu || gpu.error().code != ErrorCode::Vulkan) throw Exception(gpu.error());
    std::fprintf(stderr, "soundpaint: GPU backend not used (%s); using the CPU backend\n", gpu.error().message.c_str());
  }
  return std::move(create_cpu_simulator(std::move(world), CpuSettings{cpu_threads}).value());
}

}  // namespace sp::cli
