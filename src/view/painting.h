// What the viewer paints for one config: the level as one draw, and the
// simulation and indicators as a visualizer on the viewer's own device.
// Built together, and replaced together when the config, the ray budget,
// diffraction or the backend change.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "render/scene_pass.h"
#include "soundpaint/simulation.h"
#include "soundpaint/visualizer.h"
#include "view/swapchain.h"
#include "vk/context.h"

namespace sp::view {

struct Painting {
  std::unique_ptr<draw::ScenePass> scene_pass;
  std::unique_ptr<Visualizer> visualizer;
};

struct PaintSettings {
  BackendChoice backend = BackendChoice::Auto;
  // A config whose rays and indicators could need more is refused
  // (--memory-budget).
  std::uint64_t memory_budget_bytes = kDefaultMemoryBudgetBytes;
};

// Paints `world` (from make_world) for `swapchain`'s formats and depth
// views, with the sources placed by clicking added. Throws sp::Exception
// naming the problem (a config over the memory budget, a source the world
// refuses, a device error); nothing of a failed painting is left behind.
Painting paint(vk::Context& context, const Swapchain& swapchain, World world, const PaintSettings& settings,
               const std::vector<SourceDesc>& placed);

}  // namespace sp::view
