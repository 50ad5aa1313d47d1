// The two visualizer backends, made by Visualizer::create.
#pragma once

#include <memory>

#include "embed/visualizer_base.h"

namespace sp::embed {

// Throw sp::Exception on failure.
std::unique_ptr<Visualizer> make_gpu_visualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target,
                                                World world, const VisualizerSettings& settings,
                                                bool simulation_on_graphics_queue);
std::unique_ptr<Visualizer> make_cpu_visualizer(std::unique_ptr<vk::Context> context, const DrawTarget& target,
                                                World world, const VisualizerSettings& settings,
                                                bool simulation_on_graphics_queue);

}  // namespace sp::embed
