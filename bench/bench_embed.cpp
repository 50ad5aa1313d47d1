// The integration module's costs, as a host engine sees them:
//  1. render-thread time of Visualizer::record_simulation and record_draw
//     per frame (what the host's frame budget pays on the CPU), for each
//     backend, with the GPU time of the frame beside it; for the CPU
//     backend also how many frames received a finished step;
//  2. what a game pays per frame, the paper's own metric (Figure 6): the
//     host's whole frame (record, submit, wait) with the visualizer's
//     simulation and draw in it, minus the same frame without them, at
//     100, 500 and 2,500 rays (--overhead-budgets);
//  3. BVH refit of a moving door, per transform change, on the level and on
//     a large generated level (SoundScene::update_geometry), and the bytes a
//     GPU upload of the changes carries.
// Medians over frames; the bench plays the host (own context and command
// buffers, submit + wait per frame).
//
//   bench_embed --scene scenes/level.gltf --frames 600 --budget 500 --big 250000
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_common.h"
#include "core/glm_interop.h"
#include "render/render_target.h"
#include "render/view_camera.h"
#include "generated_level.h"
#include "sim/sound_scene_backend.h"
#include "soundpaint/visualizer.h"
#include "sp_types.h"
#include "vk/context.h"
#include "vk/handle.h"
#include "vk/vk_check.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::uint32_t frames = 600;
  std::uint32_t budget = 500;
  std::uint32_t big = 250000;  // triangles of the generated level for the refit; 0 skips it
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::vector<std::uint32_t> overhead_budgets = {100, 500, 2500};
};

Options parse(const spbench::CommandLine& cli, int argc, char** argv) {
  Options o;
  cli.parse(argc, argv, [&](const std::string& flag, const std::string& value) {
    if (flag == "--scene") o.scene = value;
    else if (flag == "--frames") o.frames = cli.to_uint(value, flag);
    else if (flag == "--budget") o.budget = cli.to_uint(value, flag);
    else if (flag == "--big") o.big = cli.to_uint(value, flag);
    else if (flag == "--width") o.width = cli.to_uint(value, flag);
    else if (flag == "--height") o.height = cli.to_uint(value, flag);
    else if (flag == "--overhead-budgets") o.overhead_budgets = cli.to_uint_list(value, flag);
    else return false;
    return true;
  });
  if (o.frames == 0 || o.width == 0 || o.height == 0) cli.fail("--frames, --width and --height must be > 0");
  return o;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The host: one command buffer and fence reused per frame, a render target.
class Host {
 public:
  Host(sp::vk::Context& context, std::uint32_t width, std::uint32_t height)
      : context_(context), target_(context, width, height) {
    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    SP_VK_CHECK(vkCreateCommandPool(context.device(), &pool_info, nullptr, &pool));
    pool_ = sp::vk::UniqueCommandPool(context.device(), pool);
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    SP_VK_CHECK(vkAllocateCommandBuffers(context.device(), &alloc, &cmd_));
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence = VK_NULL_HANDLE;
    SP_VK_CHECK(vkCreateFence(context.device(), &fence_info, nullptr, &fence));
    fence_ = sp::vk::UniqueFence(context.device(), fence);
  }

  sp::HostVulkan vulkan() const {
    sp::HostVulkan host;
    host.instance = context_.instance();
    host.physical_device = context_.physical_device();
    host.device = context_.device();
    host.queue_family = context_.queue_family();
    return host;
  }

  struct FrameTimes {
    double simulation_ms = 0.0;  // record_simulation on the render thread
    double draw_ms = 0.0;        // record_draw on the render thread
    double frame_ms = 0.0;       // record + submit + wait: the whole frame
    std::uint32_t steps = 0;     // steps recorded / handed over
  };

  // One frame; without `vis`, the host's own frame alone (the clear and the
  // copy out), the baseline of the overhead.
  FrameTimes frame(sp::Visualizer* vis, const sp::draw::ViewCamera& camera, double dt) {
    FrameTimes t;
    const auto frame_start = Clock::now();
    SP_VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    SP_VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    auto start = Clock::now();
    if (vis != nullptr) t.steps = vis->record_simulation(cmd_, dt).value();
    t.simulation_ms = ms_since(start);
    const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    target_.begin(cmd_, clear);
    const VkRect2D area{{0, 0}, {target_.width(), target_.height()}};
    start = Clock::now();
    if (vis != nullptr) vis->record_draw(cmd_, camera.view, camera.projection, &area).value();
    t.draw_ms = ms_since(start);
    target_.end_and_copy(cmd_);
    SP_VK_CHECK(vkEndCommandBuffer(cmd_));
    VkFence fence = fence_.get();
    context_.submit(cmd_, fence);
    SP_VK_CHECK(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    SP_VK_CHECK(vkResetFences(context_.device(), 1, &fence));
    t.frame_ms = ms_since(frame_start);
    return t;
  }

 private:
  sp::vk::Context& context_;
  sp::draw::RenderTarget target_;
  sp::vk::UniqueCommandPool pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  sp::vk::UniqueFence fence_;
};

void bench_record_calls(const Options& o, const sp::World& world) {
  const std::unique_ptr<sp::vk::Context> owned = sp::vk::Context::create().value();
  sp::vk::Context& context = *owned;
  std::printf("device: %s\n", context.description().c_str());
  Host host(context, o.width, o.height);
  const sp::draw::ViewCamera camera = sp::draw::make_view_camera(std::nullopt, world, {}, o.width, o.height);
  std::printf("backend  budget  frames  record_simulation ms  record_draw ms  frame ms  frames with a step\n");
  for (sp::BackendChoice backend : {sp::BackendChoice::Gpu, sp::BackendChoice::Cpu}) {
    sp::VisualizerSettings settings;
    settings.backend = backend;
    sp::DrawTarget target;
    target.color_format = sp::draw::RenderTarget::kColorFormat;
    target.depth_format = sp::draw::RenderTarget::kDepthFormat;
    auto vis = sp::Visualizer::create(host.vulkan(), target, world, settings).value();
    std::vector<double> sim_ms, draw_ms, frame_ms;
    std::uint32_t frames_with_step = 0;
    for (std::uint32_t f = 0; f < o.frames + 30; ++f) {
      const Host::FrameTimes t = host.frame(vis.get(), camera, world.config.dt);
      if (f < 30) continue;  // warm-up
      sim_ms.push_back(t.simulation_ms);
      draw_ms.push_back(t.draw_ms);
      frame_ms.push_back(t.frame_ms);
      frames_with_step += t.steps > 0 ? 1 : 0;
    }
    std::printf("%-7s  %6u  %6u  %20.4f  %14.4f  %8.3f  %u / %u\n", backend == sp::BackendChoice::Gpu ? "gpu" : "cpu",
                o.budget, o.frames, median(sim_ms), median(draw_ms), median(frame_ms), frames_with_step, o.frames);
    vkDeviceWaitIdle(context.device());
  }
}

// The scene with a door: the triangles in a 1 m box around the level's
// centre become instance 0.
sp::Scene with_door(sp::Scene scene) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const sp::Vec3& v : scene.vertices) {
    lo = glm::min(lo, sp::to_glm(v));
    hi = glm::max(hi, sp::to_glm(v));
  }
  const glm::vec3 centre = 0.5f * (lo + hi);
  scene.instance_names = {"door"};
  scene.triangle_instances.assign(scene.triangle_count(), sp::kStaticInstance);
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const glm::vec3 c = (sp::to_glm(scene.vertices[3 * t]) + sp::to_glm(scene.vertices[3 * t + 1]) +
                         sp::to_glm(scene.vertices[3 * t + 2])) /
                        3.0f;
    if (glm::all(glm::lessThan(glm::abs(c - centre), glm::vec3(1.0f)))) scene.triangle_instances[t] = 0;
  }
  return scene;
}

void bench_refit(const std::string& name, sp::Scene scene, const sp::Config& config) {
  scene = with_door(std::move(scene));
  const auto door =
      static_cast<std::size_t>(std::count(scene.triangle_instances.begin(), scene.triangle_instances.end(), 0u));
  sp::SoundScene live(sp::make_world(scene, config).value());
  std::vector<double> ms;
  std::size_t bytes = 0;
  for (int k = 0; k < 41; ++k) {
    // Swings about the vertical through the door's centre, 2 degrees a frame.
    const glm::mat4 swing = glm::rotate(glm::mat4(1.0f), glm::radians(2.0f * static_cast<float>(k + 1)), {0, 1, 0});
    (void)live.set_instance_transform(0, swing);
    const auto start = Clock::now();
    const sp::BvhChanges changes = sp::detail::SoundSceneBackend::update_geometry(live);
    ms.push_back(ms_since(start));
    bytes = 0;
    for (const auto& r : changes.nodes) bytes += (r.last - r.first) * sizeof(sp::BvhNode);
    for (const auto& r : changes.triangles) bytes += (r.last - r.first) * sizeof(sp::BvhTriangle);
  }
  std::printf("refit  %-10s %8zu triangles, door %5zu: %8.3f ms per move (median of 41), %8zu bytes to upload\n",
              name.c_str(), scene.triangle_count(), door, median(ms), bytes);
}

// The paper's metric: a game's frame with soundpaint minus without, per
// budget and backend (the host's frame here: a clear and a copy out, so the
// difference is all soundpaint's). Simulation and draw share the host's
// queue: this device has no compute-only queue family to overlap them on
// (docs/integrating.md, "Async compute", for a device that has one).
void bench_overhead(const Options& o, const sp::Scene& scene, sp::Config config) {
  const std::unique_ptr<sp::vk::Context> owned = sp::vk::Context::create().value();
  sp::vk::Context& context = *owned;
  Host host(context, o.width, o.height);
  std::printf("frame overhead (frame with soundpaint - without), %u frames each, medians:\n", o.frames);
  std::printf("backend  budget  without ms  with ms  overhead ms\n");
  for (std::uint32_t budget : o.overhead_budgets) {
    config.ray_budget = budget;
    const sp::World world = sp::make_world(scene, config).value();
    const sp::draw::ViewCamera camera = sp::draw::make_view_camera(std::nullopt, world, {}, o.width, o.height);
    for (sp::BackendChoice backend : {sp::BackendChoice::Gpu, sp::BackendChoice::Cpu}) {
      sp::VisualizerSettings settings;
      settings.backend = backend;
      sp::DrawTarget target;
      target.color_format = sp::draw::RenderTarget::kColorFormat;
      target.depth_format = sp::draw::RenderTarget::kDepthFormat;
      auto vis = sp::Visualizer::create(host.vulkan(), target, world, settings).value();
      // Alternating frames with and without, so that a drifting machine
      // moves both alike.
      std::vector<double> with_ms, without_ms;
      for (std::uint32_t f = 0; f < o.frames + 30; ++f) {
        const double with = host.frame(vis.get(), camera, world.config.dt).frame_ms;
        const double without = host.frame(nullptr, camera, world.config.dt).frame_ms;
        if (f < 30) continue;  // warm-up
        with_ms.push_back(with);
        without_ms.push_back(without);
      }
      std::printf("%-7s  %6u  %10.4f  %7.4f  %11.4f\n", backend == sp::BackendChoice::Gpu ? "gpu" : "cpu", budget,
                  median(without_ms), median(with_ms), median(with_ms) - median(without_ms));
      vkDeviceWaitIdle(context.device());
    }
  }
}

int run(const spbench::CommandLine& cli, const Options& o) {
  std::printf("host: %s\n", spbench::host_description().c_str());
  sp::Scene scene = spbench::load_scene_or_exit(cli, o.scene);
  sp::Config config;
  config.ray_budget = o.budget;
  spbench::apply_pattern(scene, spbench::Pattern::Paper, config.dt);
  const sp::World world = sp::make_world(scene, config).value();
  bench_record_calls(o, world);
  if (!o.overhead_budgets.empty()) bench_overhead(o, scene, config);
  bench_refit("level", scene, config);
  if (o.big > 0) bench_refit("generated", spbench::load_scene_or_exit(cli, "gen:" + std::to_string(o.big)), config);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return spbench::bench_main(argc, argv, "bench_embed",
                             "usage: bench_embed [--scene FILE] [--frames N] [--budget RAYS] [--big TRIANGLES]\n"
                             "                   [--width W] [--height H] [--overhead-budgets A,B,...]",
                             parse, run);
}
