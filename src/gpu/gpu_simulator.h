// The GPU backend: the ray model as Vulkan compute, one submit per step.
#pragma once

#include <memory>

#include "soundpaint/simulation.h"
#include "vk/context.h"

namespace sp::gpu {

// Creates a GPU simulator on `context`, which must outlive it (tests share
// one context per binary this way).
Result<std::unique_ptr<Simulator>> create_simulator(World world, vk::Context& context);

}  // namespace sp::gpu
