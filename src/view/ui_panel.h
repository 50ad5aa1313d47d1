// The viewer's panel (Dear ImGui 1.86): what runs and how fast, the buttons
// and keys' equivalents, and every display setting, drawn over the
// swapchain image after the level and its indicators. ImGui's Vulkan backend
// of that version draws only inside a classic VkRenderPass, so the panel has
// one of its own (colour kept, no depth) and a framebuffer per image.
//
// One panel at a time: ImGui's context and both backends are process-wide.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "soundpaint/display.h"
#include "vk/handle.h"

struct GLFWwindow;

namespace sp::vk {
class Context;
}  // namespace sp::vk

namespace sp::view {

// What the panel shows; the viewer fills it in before build().
struct PanelStats {
  std::string device;        // the Vulkan device's description
  std::string backend;       // "gpu" or "cpu"
  double frame_ms = 0;       // wall time of the last frame
  double simulation_ms = 0;  // GPU timestamps around the simulation's commands (GPU backend), or the CPU step time
  double scene_ms = 0;       // GPU time of the scene pass
  double indicators_ms = 0;
  // The simulation's stages (sp::Visualizer::stage_timings): GPU time per
  // kernel on the GPU backend, the worker's step time on the CPU backend.
  std::vector<std::pair<std::string, double>> stages;                    // GPU time of the indicator pass
  std::uint64_t steps = 0, casts = 0, rays_emitted = 0, indicators = 0;  // totals so far
  std::uint32_t live_indicators = 0;                                     // ring slots filled
  // Whether the counts above are known (after the first frame's fence).
  bool totals_known = false;
  bool paused = false;
  bool listener_pinned = false;
  glm::vec3 eye{0.0f};
  // Why the last reload or rebuild was refused (the running config stays);
  // empty once one succeeds.
  std::string notice;
};

// What the panel edits in place; the viewer applies changes.
struct PanelState {
  std::uint32_t ray_budget = 500;
  bool diffraction = false;
  sp::DisplaySettings display;
  int category = 0;  // index into `categories` for placing sources by click
};

// One frame's button presses and edits. ray_budget_changed comes once, when
// the slider is let go: the viewer rebuilds the simulation for it.
struct PanelActions {
  bool toggle_pause = false, single_step = false, switch_backend = false, toggle_pin = false;
  bool ray_budget_changed = false, diffraction_changed = false, display_changed = false;
};

class UiPanel {
 public:
  // Creates ImGui's context, its GLFW backend (which chains the window's
  // input callbacks installed before it and restores them at the end), a
  // descriptor pool, the render pass over `color_format` and a framebuffer
  // per view, and uploads the font with a one-time submission on `queue`.
  // `image_count` is also how many vertex/index buffer sets ImGui cycles
  // through, one per recorded frame: it must be at least the frames in
  // flight. Throws sp::Exception(ErrorCode::Vulkan) on failure,
  // (ErrorCode::InvalidArgument) if another panel exists.
  // `context` must be an owned one (the fonts go up on its queue).
  UiPanel(GLFWwindow* window, vk::Context& context, VkFormat color_format, std::uint32_t image_count,
          const std::vector<VkImageView>& views, VkExtent2D extent);
  // vkDeviceWaitIdle is the caller's job: destroys everything the panel made
  // and shuts ImGui down.
  ~UiPanel();
  UiPanel(const UiPanel&) = delete;
  UiPanel& operator=(const UiPanel&) = delete;

  // New swapchain images of the same format (after a resize); the caller has
  // waited for the device.
  void resize(const std::vector<VkImageView>& views, VkExtent2D extent);

  // One ImGui frame, NewFrame to Render: the window "soundpaint" at the top
  // left. Edits `state` in place and returns what was pressed. `categories`
  // names the categories (hide, shape, click placement).
  PanelActions build(const PanelStats& stats, PanelState& state, const std::vector<std::string>& categories);
  // Records the panel's render pass into `cmd` over swapchain image
  // `image_index`, which is in COLOR_ATTACHMENT_OPTIMAL and stays so; after
  // the level's colour writes (the pass waits for them). Call after build().
  void record(VkCommandBuffer cmd, std::uint32_t image_index);

  // Whether ImGui wants the mouse / keyboard this frame: the viewer then
  // ignores them for flying and picking.
  bool wants_mouse() const;
  bool wants_keyboard() const;
  // F1: build() still runs (ImGui keeps its timing and input), but nothing
  // is drawn and nothing is captured.
  void set_visible(bool visible) { visible_ = visible; }
  bool visible() const { return visible_; }

 private:
  // Calls a shutdown function when it goes, unless empty: ImGui's context
  // and backends as members, so that a constructor that throws halfway
  // undoes what it had done.
  class Teardown {
   public:
    Teardown() = default;
    explicit Teardown(void (*fn)()) : fn_(fn) {}
    ~Teardown() {
      if (fn_ != nullptr) fn_();
    }
    Teardown(const Teardown&) = delete;
    Teardown& operator=(const Teardown&) = delete;
    Teardown& operator=(void (*fn)()) {
      fn_ = fn;
      return *this;
    }

   private:
    void (*fn_)() = nullptr;
  };
  using UniqueRenderPass = vk::DeviceObject<VkRenderPass, vkDestroyRenderPass>;
  using UniqueFramebuffer = vk::DeviceObject<VkFramebuffer, vkDestroyFramebuffer>;

  void create_framebuffers(const std::vector<VkImageView>& views, VkExtent2D extent);
  void upload_fonts(vk::Context& context);
  void build_display(PanelState& state, const std::vector<std::string>& categories, PanelActions& actions);

  VkDevice device_ = VK_NULL_HANDLE;
  VkExtent2D extent_{};
  std::uint32_t image_count_ = 0;
  bool visible_ = true;
  // Declaration order is creation order; ImGui's backends go first, while
  // the pool their descriptor set came from and their render pass live.
  vk::UniqueDescriptorPool pool_;
  UniqueRenderPass render_pass_;
  std::vector<UniqueFramebuffer> framebuffers_;
  Teardown context_;
  Teardown glfw_backend_;
  Teardown vulkan_backend_;
};

}  // namespace sp::view
