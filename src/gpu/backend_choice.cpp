// The backend policy shared by the CLI, the C API and library users: which
// simulator a BackendChoice gets.
#include <string>

#include "gpu/gpu_simulator.h"
#include "sim/memory_estimate.h"

namespace sp {
namespace {

// `make_gpu` tries the GPU backend; an ErrorCode::Vulkan failure under Auto
// falls back to the CPU backend and is reported through `fallback_reason`.
template <class MakeGpu>
Result<std::unique_ptr<Simulator>> choose(World world, BackendChoice backend, const CpuSettings& cpu,
                                          std::string* fallback_reason, MakeGpu&& make_gpu) {
  if (backend != BackendChoice::Cpu) {
    Result<std::unique_ptr<Simulator>> gpu = make_gpu(world);
    if (gpu) return gpu;
    if (backend == BackendChoice::Gpu || gpu.error().code != ErrorCode::Vulkan) return gpu.error();
    if (fallback_reason) *fallback_reason = gpu.error().message;
  }
  return create_cpu_simulator(std::move(world), cpu);
}

}  // namespace

Result<std::unique_ptr<Simulator>> create_simulator(World world, const SimulatorSettings& settings,
                                                    std::string* fallback_reason) {
  return choose(std::move(world), settings.backend, settings.cpu, fallback_reason, [&](const World& w) {
    GpuSettings gpu = settings.gpu;
    gpu.allow_cpu_device = settings.backend == BackendChoice::Gpu;
    return create_gpu_simulator(w, gpu);
  });
}

namespace gpu {

Result<std::unique_ptr<Simulator>> create_simulator_on(vk::Context& context, World world, BackendChoice backend,
                                                       const CpuSettings& cpu, std::string* fallback_reason) {
  return choose(std::move(world), backend, cpu, fallback_reason,
                [&](const World& w) -> Result<std::unique_ptr<Simulator>> {
                  if (backend == BackendChoice::Auto && context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
                    return Error{ErrorCode::Vulkan, "the only Vulkan device is a CPU device (" +
                                                        std::string(context.properties().deviceName) + ")"};
                  // On a shared context the CPU settings' budget holds for both backends.
                  Result<bool> fits = capture_errors([&] {
                    check_memory_budget(w.config, Backend::Gpu, cpu.memory_budget_bytes);
                    return true;
                  });
                  if (!fits) return fits.error();
                  return create_simulator(w, context, cpu.memory_budget_bytes);
                });
}

}  // namespace gpu
}  // namespace sp
