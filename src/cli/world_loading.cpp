#include "cli/world_loading.h"

#include <cstdio>

namespace sp::cli {

World load_world(const std::string& scene_path, const std::optional<std::string>& config_path,
                 std::optional<std::uint64_t> seed_override) {
  Config config;
  if (config_path) config = load_config(*config_path).value();
  if (seed_override) config.seed = static_cast<std::uint32_t>(*seed_override);
  Scene scene = load_scene(scene_path).value();
  return make_world(scene, config).value();
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
    auto gpu = create_gpu_simulator(world);
    if (gpu) return std::move(gpu.value());
    // Only a missing or unusable device falls back; a scene or budget too big
    // for the device is the user's to fix and fails like any other input.
    if (backend == BackendChoice::Gpu || gpu.error().code != ErrorCode::Vulkan) throw Exception(gpu.error());
    std::fprintf(stderr, "soundpaint: GPU backend unavailable (%s); using the CPU backend\n",
                 gpu.error().message.c_str());
  }
  return std::move(create_cpu_simulator(std::move(world), CpuSettings{cpu_threads}).value());
}

}  // namespace sp::cli
