#include "core/glm_interop.h"
#include "view/viewer.h"

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

namespace {

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
void apply_viewer_defaults(Config& config, const Scene& scene) {
  // Like render: off-screen arrows unless the config says no.
  if (!config.display.offscreen_arrows) config.display.offscreen_arrows = true;
  if (!config.listener_position && !scene.camera) config.listener_position = glm::vec3(0.0f);
}

// A change of config or backend, applied at the top of the next frame. The
// running config and painting stay until its painting has been built.
struct Change {
  Config config;
  BackendChoice backend = BackendChoice::Auto;
  bool reload = false;  // the --config file's; else the panel's or a key's
};

std::vector<std::string> category_names() {
  std::vector<std::string> names;
  for (const BuiltinCategory& c : builtin_categories()) names.emplace_back(c.name);
  return names;
}

// The scene pass clears and writes depth; the indicator pass then tests
// against it and samples it read-only (clipping spots to surfaces).
void begin_pass(VkCommandBuffer cmd, VkImageView color_view, VkImageView depth_view, VkExtent2D extent, bool first) {
  VkRenderingAttachmentInfo color = draw::attachment({color_view, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                                      first ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD,
                                                      VK_ATTACHMENT_STORE_OP_STORE});
  // The scene pass's clear colour is linear, as the sRGB swapchain expects.
  std::memcpy(color.clearValue.color.float32, draw::ScenePass::kClearColor, sizeof(float) * 4);
  VkRenderingAttachmentInfo depth =
      draw::attachment(first ? draw::AttachmentUse{depth_view, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                                   VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE}
                             : draw::AttachmentUse{depth_view, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL,
                                                   VK_ATTACHMENT_LOAD_OP_LOAD, VK_ATTACHMENT_STORE_OP_NONE});
  depth.clearValue.depthStencil = {1.0f, 0};
  draw::begin_rendering(cmd, extent, color, depth);
  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height),
                            0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

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

void Viewer::read_timestamps(std::uint32_t slot) {
  if (!submitted_[slot]) return;
  SimulationTotals totals;
  std::memcpy(&totals, totals_[slot].mapped(), sizeof totals);
  stats_.casts = totals.casts;
  stats_.rays_emitted = totals.rays_emitted;
  stats_.indicators = totals.indicators;
  stats_.live_indicators = static_cast<std::uint32_t>(totals.ring_filled);
  stats_.totals_known = true;
  if (!queries_) return;
  std::array<std::uint64_t, kQueriesPerFrame> ticks{};
  const VkResult result =
      vkGetQueryPoolResults(context_->device(), queries_.get(), slot * kQueriesPerFrame, kQueriesPerFrame,
                            sizeof(ticks), ticks.data(), sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT);
  if (result != VK_SUCCESS) return;  // the fence has passed, so this is rare; keep the last figures
  stats_.simulation_ms = double(ticks[1] - ticks[0]) * timestamp_ms_;
  stats_.scene_ms = double(ticks[3] - ticks[2]) * timestamp_ms_;
  stats_.indicators_ms = double(ticks[5] - ticks[4]) * timestamp_ms_;
}

bool Viewer::record_and_present(std::uint32_t slot, bool last, double dt) {
  const VkDevice device = context_->device();
  std::uint32_t image = 0;
  VkResult acquired =
      vkAcquireNextImageKHR(device, swapchain_->handle(), UINT64_MAX, acquired_[slot].get(), VK_NULL_HANDLE, &image);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return false;  // nothing was signalled: recreate and try again
  if (acquired != VK_SUBOPTIMAL_KHR) SP_VK_CHECK(acquired);
  const VkFence fence = fences_[slot].get();
  SP_VK_CHECK(vkResetFences(device, 1, &fence));

  const VkCommandBuffer cmd = commands_[slot];
  SP_VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SP_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  const std::uint32_t query = slot * kQueriesPerFrame;
  if (queries_) vkCmdResetQueryPool(cmd, queries_.get(), query, kQueriesPerFrame);
  auto stamp = [&](std::uint32_t k, VkPipelineStageFlags2 stage) {
    if (queries_) vkCmdWriteTimestamp2(cmd, stage, queries_.get(), query + k);
  };

  Visualizer& visualizer = *painting_.visualizer;
  if (!session_.listener_pinned) (void)visualizer.scene().set_listener(camera_.eye);
  stamp(0, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  // A scripted run shows what its frames computed, however long a step of
  // the CPU backend takes: the step started a frame ago is handed over now.
  // The picture of frame N is then the same on any machine, at any load.
  if (options_.frames > 0) visualizer.wait_for_simulation().value();
  if (!paused_ || step_once_) visualizer.record_simulation(cmd, paused_ ? session_.config.dt : dt).value();
  step_once_ = false;
  visualizer.record_totals(cmd, totals_[slot].get(), 0).value();
  stamp(1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);

  const VkImage color = swapchain_->image(image);
  const VkImage depth = swapchain_->depth_image(image);
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  // WAR: the image's last reader was presentation (ordered by the acquire
  // semaphore, waited at this stage); its contents are not kept.
  draw::image_barrier(cmd, color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  // WAR: the previous frame on this image sampled and tested its depth.
  draw::image_barrier(cmd, depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depth_stages | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      0, depth_stages,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  const VkExtent2D extent = swapchain_->extent();
  const draw::ViewCamera view = camera_.view_camera(extent.width, extent.height);
  stamp(2, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  begin_pass(cmd, swapchain_->views()[image], swapchain_->depth_view(image), extent, true);
  painting_.scene_pass->record(cmd, view, visualizer.scene().listener());
  vkCmdEndRendering(cmd);
  stamp(3, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  // RAW: the scene's depth lands before the indicators test and sample it
  // (their vertex stage samples each spot's centre).
  draw::image_barrier(cmd, depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, depth_stages,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      depth_stages | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  stamp(4, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT);
  begin_pass(cmd, swapchain_->views()[image], swapchain_->depth_view(image), extent, false);
  DrawOptions draw_options;
  draw_options.viewport_width = extent.width;
  draw_options.viewport_height = extent.height;
  draw_options.scene_depth = static_cast<std::int32_t>(image);
  visualizer.record_draw(cmd, view.view, view.projection, draw_options).value();
  vkCmdEndRendering(cmd);
  stamp(5, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  panel_->record(cmd, image);

  const bool screenshot = last && options_.screenshot && swapchain_->readable();
  if (screenshot) {
    screenshot_.record(*context_, cmd, color, extent);
  } else {
    // Presentation waits on the semaphore the submit signals after this.
    draw::image_barrier(cmd, color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0);
  }
  SP_VK_CHECK(vkEndCommandBuffer(cmd));

  VkSemaphoreSubmitInfo wait{};
  wait.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  wait.semaphore = acquired_[slot].get();
  // The simulation's transfers and dispatches do not touch the image: only
  // its first write waits for presentation to let go of it.
  wait.stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSemaphoreSubmitInfo signal{};
  signal.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
  signal.semaphore = swapchain_->rendered(image);
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo command{};
  command.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
  command.commandBuffer = cmd;
  VkSubmitInfo2 submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &command;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  SP_VK_CHECK(vkQueueSubmit2(context_->queue(), 1, &submit, fence));
  submitted_[slot] = true;

  const VkSemaphore rendered = swapchain_->rendered(image);
  const VkSwapchainKHR swapchain = swapchain_->handle();
  VkPresentInfoKHR present{};
  present.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain;
  present.pImageIndices = &image;
  const VkResult presented = vkQueuePresentKHR(context_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR) {
    swapchain_stale_ = true;
  } else {
    SP_VK_CHECK(presented);
  }
  if (screenshot) {
    SP_VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    screenshot_.write(*options_.screenshot, swapchain_->format());
  }
  return true;
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

}  // namespace

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
