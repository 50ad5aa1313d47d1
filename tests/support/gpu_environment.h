// GpuTest: the shared-context fixture (support/vulkan_environment.h: one
// context per binary, validation messages fail the test, leaks fail the
// binary, no device skips except on CI) plus a simulator of either backend.
#pragma once

#include <memory>

#include "gpu/gpu_simulator.h"
#include "soundpaint/simulation.h"
#include "support/vulkan_environment.h"

namespace sp::test {

class GpuTest : public VulkanTest {
 protected:
  std::unique_ptr<Simulator> make_simulator(World world, Backend backend) {
    if (backend == Backend::Cpu) return create_cpu_simulator(std::move(world), CpuSettings{2}).value();
    return gpu::create_simulator(std::move(world), *GpuEnvironment::context()).value();
  }
};

}  // namespace sp::test
