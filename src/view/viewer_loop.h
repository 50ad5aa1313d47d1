// The viewer's frame loop (view/viewer.cpp), the frames it records and
// presents (viewer_frame.cpp) and the config it reloads
// (viewer_reload.cpp): internal to soundpaint view.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "soundpaint/config.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "view/config_watch.h"
#include "view/fly_camera.h"
#include "view/painting.h"
#include "view/screenshot.h"
#include "view/swapchain.h"
#include "view/ui_panel.h"
#include "view/viewer.h"
#include "view/window.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/objects.h"

namespace sp::view {

constexpr std::uint32_t kFramesInFlight = 2;
// Timestamps per frame: simulation, scene pass and indicator pass, each
// begin and end.
constexpr std::uint32_t kQueriesPerFrame = 6;
constexpr float kFlySpeed = 4.0f;  // metres a second; Shift: 4x

class Surface {
 public:
  Surface(VkInstance instance, VkSurfaceKHR surface) : instance_(instance), surface_(surface) {}
  ~Surface() { vkDestroySurfaceKHR(instance_, surface_, nullptr); }
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;
  VkSurfaceKHR get() const { return surface_; }

 private:
  VkInstance instance_;
  VkSurfaceKHR surface_;
};

// What the viewer can change and rebuild a visualizer from.
struct Session {
  Scene scene;
  // The level's geometry, built once: every rebuild of the visualizer (a
  // new ray budget, a reloaded config, the other backend) shares it.
  WorldGeometryHandle geometry;
  Config config;
  BackendChoice backend = BackendChoice::Auto;
  std::vector<SourceDesc> placed;  // sources placed by clicking, kept across rebuilds
  bool listener_pinned = false;
};

// What the viewer adds to a config, at start and on every reload alike.
void apply_viewer_defaults(Config& config, const Scene& scene);

// A change of config or backend, applied at the top of the next frame. The
// running config and painting stay until its painting has been built.
struct Change {
  Config config;
  BackendChoice backend = BackendChoice::Auto;
  bool reload = false;  // the --config file's; else the panel's or a key's
};

std::vector<std::string> category_names();

// The frame loop's state: the device, the window's swapchain, the frames in
// flight, and what is painted.
class Viewer {
 public:
  // `first_world`: make_world(session.scene, session.config), already made;
  // `watch`: the --config file's, already polled once for session.config.
  Viewer(const ViewerOptions& options, Window& window, Session session, World first_world,
         std::optional<ConfigWatch> watch);
  ~Viewer();
  void run();
  std::uint32_t validation_messages() const { return context_->validation_message_count(); }

 private:
  void handle_input(float seconds);
  void place_or_play(bool play);
  Change& change();
  std::optional<std::uint64_t> read_scripted_check();
  void check_config();
  void apply_change();
  void show_session_in_panel();
  void recreate_swapchain();
  void read_timestamps(std::uint32_t slot);
  bool record_and_present(std::uint32_t slot, bool last, double dt);

  const ViewerOptions& options_;
  Window& window_;
  Session session_;
  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<Surface> surface_;
  std::unique_ptr<Swapchain> swapchain_;
  vk::UniqueCommandPool pool_;
  std::array<VkCommandBuffer, kFramesInFlight> commands_{};
  std::array<vk::UniqueFence, kFramesInFlight> fences_;
  std::array<UniqueSemaphore, kFramesInFlight> acquired_;
  std::array<bool, kFramesInFlight> submitted_{};
  vk::UniqueQueryPool queries_;
  std::array<vk::Buffer, kFramesInFlight> totals_;  // record_totals' copy, read after the slot's fence
  double timestamp_ms_ = 0.0;                       // milliseconds per timestamp tick
  Screenshot screenshot_;
  Painting painting_;
  std::unique_ptr<UiPanel> panel_;
  PanelState panel_state_;
  PanelStats stats_;
  std::vector<std::string> categories_ = category_names();
  FlyCamera camera_;
  glm::vec2 last_cursor_{0.0f};
  bool paused_ = false;
  bool step_once_ = false;
  std::optional<Change> change_;
  bool swapchain_stale_ = false;
  std::optional<ConfigWatch> watch_;
  // config_checks_from_stdin: the frame before which the file is checked
  // next, as the input's last line named it; nothing once the input ended.
  std::optional<std::uint64_t> scripted_check_;
  std::uint64_t frame_ = 0;
};

}  // namespace sp::view
