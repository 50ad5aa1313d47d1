// The viewer's config: checked, reloaded, and a new painting built beside the running one.
#include "core/glm_interop.h"
#include "view/viewer_loop.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "bvh/bvh.h"
#include "core/printable_text.h"
#include "draw/image_barrier.h"
#include "draw/rendering.h"
#include "render/scene_pass.h"
#include "soundpaint/ray_query.h"
#include "soundpaint/config.h"
#include "soundpaint/display.h"
#include "soundpaint/visualizer.h"
#include "view/config_watch.h"
#include "view/fly_camera.h"
#include "view/painting.h"
#include "view/screenshot.h"
#include "view/swapchain.h"
#include "view/ui_panel.h"
#include "view/window.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/objects.h"
#include "vk/vk_check.h"


namespace sp::view {

// config_checks_from_stdin: waits for the input's next line, the frame
// before which the file is checked next. Nothing when the input has ended.
std::optional<std::uint64_t> Viewer::read_scripted_check() {
  std::string line;
  if (!std::getline(std::cin, line)) return std::nullopt;
  std::uint64_t frame = 0;
  const char* const end = line.data() + line.size();
  const auto [stop, error] = std::from_chars(line.data(), end, frame);
  if (error != std::errc() || stop != end || line.empty())
    throw Exception(ErrorCode::InvalidArgument,
                    "--config-checks-from-stdin: expected a frame number on each line, got '" + printable_text(line) +
                        "'");
  return frame;
}

void Viewer::check_config() {
  std::optional<Result<Config>> found = watch_->poll();
  if (!found) return;
  if (!*found) {
    const std::string line = printable_text(found->error().message + " (keeping the running config)");
    std::fprintf(stderr, "view: %s\n", line.c_str());
    stats_.notice = line;
    return;
  }
  Change& wanted = change();
  wanted.config = std::move(found->value());
  apply_viewer_defaults(wanted.config, session_.scene);
  wanted.reload = true;
}

// The new painting is built beside the running one, which goes only once
// the new one stands: a config that parses but cannot run (over the memory
// budget, a source the level refuses, a device error) leaves the viewer as
// it was, and says why.
void Viewer::apply_change() {
  Change wanted = std::move(*change_);
  change_.reset();
  SP_VK_CHECK(vkDeviceWaitIdle(context_->device()));
  (void)painting_.visualizer->wait_for_simulation();
  // The panel's display edits, already applied, outlive a rebuild of its
  // own; a reloaded file brings its own display.
  if (!wanted.reload) wanted.config.display = painting_.visualizer->display();
  try {
    Painting next =
        paint(*context_, *swapchain_, make_world(session_.scene, wanted.config, session_.geometry).value(),
              {.backend = wanted.backend, .memory_budget_bytes = options_.memory_budget_bytes}, session_.placed);
    painting_ = std::move(next);
    session_.config = std::move(wanted.config);
    session_.backend = wanted.backend;
    stats_.notice.clear();
    // The level's BVH count says that the new settings share the geometry
    // (a reload and the panel's ray budget take this same path).
    if (wanted.reload)
      std::fprintf(stderr, "view: reloaded %s (ray budget %u; the level's BVH built %llu time(s) this run)\n",
                   printable_text(watch_->path().string()).c_str(), session_.config.ray_budget,
                   static_cast<unsigned long long>(bvh_builds()));
  } catch (const std::exception& e) {
    // Messages quote names from the files: escaped before the terminal or the panel shows them.
    const std::string line =
        printable_text(wanted.reload ? watch_->path().string() + ": " + e.what() + " (keeping the running config)"
                                     : std::string(e.what()) + " (keeping the running settings)");
    std::fprintf(stderr, "view: %s\n", line.c_str());
    stats_.notice = line;
  }
  show_session_in_panel();
}

// The panel's controls show what runs, after a rebuild that failed too.
void Viewer::show_session_in_panel() {
  panel_state_.ray_budget = session_.config.ray_budget;
  panel_state_.diffraction = session_.config.diffraction.enabled;
  panel_state_.display = painting_.visualizer->display();
}

}  // namespace sp::view
