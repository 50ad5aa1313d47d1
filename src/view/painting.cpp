#include "view/painting.h"

#include <utility>

#include "render/scene_mesh.h"

namespace sp::view {

Painting paint(vk::Context& context, const Swapchain& swapchain, World world, const PaintSettings& settings,
               const std::vector<SourceDesc>& placed) {
  Painting painting;
  painting.scene_pass = std::make_unique<draw::ScenePass>(context, draw::build_scene_mesh(world, true),
                                                          swapchain.format(), Swapchain::kDepthFormat);
  const HostVulkan host{.instance = context.instance(),
                        .physical_device = context.physical_device(),
                        .device = context.device(),
                        .queue_family = context.queue_family()};
  const DrawTarget target{.color_format = swapchain.format(), .depth_format = Swapchain::kDepthFormat};
  VisualizerSettings visualizer_settings;
  visualizer_settings.backend = settings.backend;
  // Visualizer::create checks the budget held in its CPU settings, whichever
  // backend it picks.
  visualizer_settings.cpu.memory_budget_bytes = settings.memory_budget_bytes;
  painting.visualizer = Visualizer::create(host, target, std::move(world), visualizer_settings).value();
  for (const SourceDesc& source : placed) painting.visualizer->scene().add_source(source).value();
  painting.visualizer->set_scene_depth(swapchain.depth_views()).value();
  return painting;
}

}  // namespace sp::view
