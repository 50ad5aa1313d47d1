#include "core/glm_interop.h"
#include "view/viewer.h"
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

const char* const kControls =
    "  W A S D       fly forward, left, back, right (Shift: faster); Q E: down, up\n"
    "  right mouse   hold and drag to look around\n"
    "  left click    place a source of the panel's category on the surface under the cursor\n"
    "  Shift+click   play the source nearest the surface under the cursor for a second\n"
    "  Space         pause / resume the simulation;  N: one step while paused\n"
    "  B             switch the backend (GPU <-> CPU)\n"
    "  P             pin the listener where it is / let it follow the camera again\n"
    "  F1            hide / show the panel;  Esc: quit\n"
    "  The panel also sets the ray budget, diffraction and every display setting;\n"
    "  a --config file is reloaded when it changes (a bad one is not: the running config stays).\n";

// What the viewer adds to a config, at start and on every reload alike.
void apply_viewer_defaults(Config& config, const Scene& scene) {
  // Like render: off-screen arrows unless the config says no.
  if (!config.display.offscreen_arrows) config.display.offscreen_arrows = true;
  if (!config.listener_position && !scene.camera) config.listener_position = glm::vec3(0.0f);
}

std::vector<std::string> category_names() {
  std::vector<std::string> names;
  for (const BuiltinCategory& c : builtin_categories()) names.emplace_back(c.name);
  return names;
}

Viewer::Viewer(const ViewerOptions& options, Window& window, Session session, World first_world,
               std::optional<ConfigWatch> watch)
    : options_(options), window_(window), session_(std::move(session)), watch_(std::move(watch)) {
  vk::ContextSettings settings;
  settings.instance_extensions = Window::required_instance_extensions();
  settings.device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  context_ = vk::Context::create(settings).value();
  surface_ = std::make_unique<Surface>(context_->instance(), window_.create_surface(context_->instance()));
  swapchain_ = std::make_unique<Swapchain>(*context_, surface_->get(), window_.framebuffer_size());

  pool_ = vk::create_command_pool(*context_, context_->queue_family(), VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  "viewer frames");
  for (std::uint32_t i = 0; i < kFramesInFlight; ++i) {
    commands_[i] = vk::allocate_command_buffer(*context_, pool_.get(), "viewer frame");
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait finds nothing in flight
    fences_[i] = vk::create_object<vk::UniqueFence>(*context_, vkCreateFence, fence_info, VK_OBJECT_TYPE_FENCE,
                                                    "viewer frame done");
    VkSemaphoreCreateInfo semaphore_info{};
    semaphore_info.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
    acquired_[i] = vk::create_object<UniqueSemaphore>(*context_, vkCreateSemaphore, semaphore_info,
                                                      VK_OBJECT_TYPE_SEMAPHORE, "viewer image acquired");
    totals_[i] = vk::Buffer(*context_, sizeof(SimulationTotals), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            vk::MemoryUsage::Readback, "viewer totals");
  }
  // Timestamps are optional; this limit promises them on every graphics and
  // compute queue.
  if (context_->properties().limits.timestampComputeAndGraphics) {
    queries_ = vk::create_timestamp_pool(*context_, kQueriesPerFrame * kFramesInFlight, "viewer stage timestamps");
    timestamp_ms_ = double(context_->properties().limits.timestampPeriod) * 1e-6;
  }

  const VkExtent2D extent = swapchain_->extent();
  camera_ = FlyCamera::from(
      draw::make_view_camera(session_.scene.camera, first_world, options_.camera, extent.width, extent.height));
  painting_ =
      paint(*context_, *swapchain_, std::move(first_world),
            {.backend = session_.backend, .memory_budget_bytes = options_.memory_budget_bytes}, session_.placed);
  show_session_in_panel();
  panel_ = std::make_unique<UiPanel>(window_.handle(), *context_, swapchain_->format(), swapchain_->image_count(),
                                     swapchain_->views(), extent);
  panel_->set_visible(options_.panel);
  stats_.device = context_->description();
  if (watch_) std::fprintf(stderr, "view: watching %s for changes\n", printable_text(watch_->path().string()).c_str());
  last_cursor_ = window_.cursor();
}

Viewer::~Viewer() {
  // Frames in flight use everything below; a CPU step in progress is
  // finished before its visualizer goes.
  if (context_) (void)vkDeviceWaitIdle(context_->device());
  if (painting_.visualizer) (void)painting_.visualizer->wait_for_simulation();
}

Change& Viewer::change() {
  if (!change_) change_ = Change{.config = session_.config, .backend = session_.backend};
  return *change_;
}

void Viewer::recreate_swapchain() {
  window_.wait_while_minimised();
  if (window_.should_close()) return;
  SP_VK_CHECK(vkDeviceWaitIdle(context_->device()));
  swapchain_->recreate(window_.framebuffer_size());
  painting_.visualizer->set_scene_depth(swapchain_->depth_views()).value();
  panel_->resize(swapchain_->views(), swapchain_->extent());
  swapchain_stale_ = false;
}

void Viewer::place_or_play(bool play) {
  const VkExtent2D extent = swapchain_->extent();
  const glm::vec3 dir = camera_.ray_through(window_.cursor(), extent.width, extent.height);
  const World& world = painting_.visualizer->scene().world();
  const std::optional<RayHit> hit = cast_ray(world, camera_.eye, dir, 1000.0f).value();
  if (!hit) return;
  const glm::vec3 point = to_glm(hit->position);
  SoundScene& scene = painting_.visualizer->scene();
  if (play) {
    std::optional<std::uint32_t> nearest;
    float best = 2.0f;  // metres: farther sources are not "this one"
    for (std::uint32_t id = 0; id < world.sources.size(); ++id) {
      if (!scene.has_source(id)) continue;
      const float d = glm::distance(to_glm(world.sources[id].position), point);
      if (d < best) best = d, nearest = id;
    }
    if (nearest) (void)scene.play(*nearest, 1.0);
    return;
  }
  SourceDesc source;
  source.position = point - dir * 0.25f;  // just off the surface, on the viewer's side
  source.category = categories_[static_cast<std::size_t>(panel_state_.category) % categories_.size()];
  source.max_distance = 30.0f;
  if (scene.add_source(source)) session_.placed.push_back(source);
}

void Viewer::handle_input(float seconds) {
  // Presses are taken every frame, so one made while the panel had the
  // keyboard or mouse does not fire later.
  const bool keys = !panel_->wants_keyboard();
  if (window_.key_pressed(GLFW_KEY_ESCAPE) && keys) window_.request_close();
  if (window_.key_pressed(GLFW_KEY_SPACE) && keys) paused_ = !paused_;
  if (window_.key_pressed(GLFW_KEY_N) && keys) step_once_ = true;
  if (window_.key_pressed(GLFW_KEY_P) && keys) session_.listener_pinned = !session_.listener_pinned;
  if (window_.key_pressed(GLFW_KEY_F1) && keys) panel_->set_visible(!panel_->visible());
  if (window_.key_pressed(GLFW_KEY_B) && keys)
    change().backend = painting_.visualizer->backend() == Backend::Gpu ? BackendChoice::Cpu : BackendChoice::Gpu;
  const bool shift = window_.key_down(GLFW_KEY_LEFT_SHIFT) || window_.key_down(GLFW_KEY_RIGHT_SHIFT);
  if (keys) {
    glm::vec3 axes(0.0f);
    axes.z += window_.key_down(GLFW_KEY_W) ? 1.0f : 0.0f;
    axes.z -= window_.key_down(GLFW_KEY_S) ? 1.0f : 0.0f;
    axes.x += window_.key_down(GLFW_KEY_D) ? 1.0f : 0.0f;
    axes.x -= window_.key_down(GLFW_KEY_A) ? 1.0f : 0.0f;
    axes.y += window_.key_down(GLFW_KEY_E) ? 1.0f : 0.0f;
    axes.y -= window_.key_down(GLFW_KEY_Q) ? 1.0f : 0.0f;
    camera_.fly(axes, shift ? 4.0f * kFlySpeed : kFlySpeed, seconds);
  }
  const glm::vec2 cursor = window_.cursor();
  const bool mouse = !panel_->wants_mouse();
  if (mouse && window_.mouse_down(GLFW_MOUSE_BUTTON_RIGHT)) camera_.turn(cursor - last_cursor_);
  if (window_.mouse_clicked(GLFW_MOUSE_BUTTON_LEFT) && mouse) place_or_play(shift);
  last_cursor_ = cursor;
}

void Viewer::run() {
  if (watch_ && options_.config_checks_from_stdin) scripted_check_ = read_scripted_check();
  auto previous = std::chrono::steady_clock::now();
  while (!window_.should_close() && (options_.frames == 0 || frame_ < options_.frames)) {
    if (options_.resize_frame > 0 && frame_ == options_.resize_frame)
      window_.request_size(options_.resize_width, options_.resize_height);
    window_.poll_events();
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - previous).count();
    previous = now;
    stats_.frame_ms = seconds * 1e3;
    // A scripted run advances config.dt a frame, whatever the frame took.
    const double dt = options_.frames > 0 ? session_.config.dt : std::min(seconds, 0.25);
    handle_input(static_cast<float>(std::min(seconds, 0.1)));
    if (window_.should_close()) break;

    // The config file: reloaded when it changes (checked twice a second,
    // or before the frames a scripted run's input names, in turn).
    if (watch_ && options_.config_checks_from_stdin) {
      // Each check's outcome is applied, and reported, before the viewer
      // waits for the next line: the test reads the report first.
      while (scripted_check_ && *scripted_check_ <= frame_) {
        check_config();
        if (change_) apply_change();
        scripted_check_ = read_scripted_check();
      }
    } else if (watch_ && frame_ % 30 == 0) {
      check_config();
    }
    if (change_) apply_change();
    if (swapchain_stale_ || swapchain_->extent().width != window_.framebuffer_size().width ||
        swapchain_->extent().height != window_.framebuffer_size().height) {
      recreate_swapchain();
      if (window_.should_close()) break;
    }

    const std::uint32_t slot = static_cast<std::uint32_t>(frame_ % kFramesInFlight);
    const VkFence fence = fences_[slot].get();
    SP_VK_CHECK(vkWaitForFences(context_->device(), 1, &fence, VK_TRUE, UINT64_MAX));
    read_timestamps(slot);

    Visualizer& visualizer = *painting_.visualizer;
    stats_.backend = visualizer.backend() == Backend::Gpu ? "gpu" : "cpu";
    stats_.steps = visualizer.steps_run();
    const StageTimings stages = visualizer.stage_timings();
    stats_.stages.clear();
    if (stages.measured && visualizer.backend() == Backend::Gpu) {
      stats_.stages = {{"emit", stages.emit_ms},
                       {"trace", stages.trace_ms},
                       {"resolve", stages.resolve_ms},
                       {"prepare", stages.prepare_ms},
                       {"admit", stages.admit_ms}};
    } else if (stages.measured) {
      stats_.stages = {{"cpu step", stages.cpu_step_ms}};
    }
    stats_.paused = paused_;
    stats_.listener_pinned = session_.listener_pinned;
    stats_.eye = camera_.eye;
    const PanelActions actions = panel_->build(stats_, panel_state_, categories_);
    if (actions.toggle_pause) paused_ = !paused_;
    if (actions.single_step) step_once_ = true;
    if (actions.toggle_pin) session_.listener_pinned = !session_.listener_pinned;
    if (actions.switch_backend)
      change().backend = visualizer.backend() == Backend::Gpu ? BackendChoice::Cpu : BackendChoice::Gpu;
    if (actions.ray_budget_changed) change().config.ray_budget = panel_state_.ray_budget;
    if (actions.diffraction_changed) change().config.diffraction.enabled = panel_state_.diffraction;
    if (actions.display_changed) {
      auto applied = visualizer.set_display(panel_state_.display);
      if (!applied) std::fprintf(stderr, "view: %s\n", printable_text(applied.error().message).c_str());
    }

    const bool last = options_.frames > 0 && frame_ + 1 == options_.frames;
    if (!record_and_present(slot, last, dt)) {
      swapchain_stale_ = true;
      continue;  // out of date before anything was recorded: the same frame again
    }
    ++frame_;
  }
  SP_VK_CHECK(vkDeviceWaitIdle(context_->device()));
}


std::uint32_t run_viewer(const ViewerOptions& options) {
  Session session;
  session.scene = load_scene(options.scene_path, options.scene_options).value();
  // The watch's first read is the config that runs: a change made while
  // the viewer starts is not mistaken for the one it started with.
  std::optional<ConfigWatch> watch;
  if (options.config_path) {
    watch.emplace(*options.config_path);
    session.config = watch->poll().value().value();
  }
  apply_viewer_defaults(session.config, session.scene);
  session.backend = options.backend;
  // Bad sources and the like fail before a window opens; the World is the
  // viewer's first.
  session.geometry = build_geometry(session.scene).value();
  World world = make_world(session.scene, session.config, session.geometry).value();

  Window window(options.width, options.height, "soundpaint view: " + options.scene_path);
  std::uint32_t messages = 0;
  {
    Viewer viewer(options, window, std::move(session), std::move(world), std::move(watch));
    viewer.run();
    messages = viewer.validation_messages();
  }
  return messages;
}

}  // namespace sp::view
