// soundpaint_embed_example: a stand-alone Vulkan renderer -- its own
// instance, device, frame loop and offscreen target -- showing what adding
// soundpaint to such a host takes. Every line that exists for soundpaint
// sits between "// >>> soundpaint" and "// <<< soundpaint"; everything else
// is what the host has anyway. tests/test_embed_example.cpp counts them.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <utility>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/matrix.hpp>

#include "frame_slots.h"
#include "host_error.h"
#include "host_vulkan.h"
#include "offscreen_target.h"
#include "options.h"
#include "png_output.h"
#include "scene_renderer.h"
// >>> soundpaint
#include "soundpaint/visualizer.h"
// <<< soundpaint

namespace {

struct CameraMatrices {
  glm::mat4 view;
  glm::mat4 projection;
};

// The camera in Vulkan clip space (tests/test_embed_example.cpp re-derives it):
//   view       = inverse(camera_world)
//   projection = perspectiveRH_ZO(yfov, width / height, znear, zfar), then projection[1][1] *= -1
// RH: a glTF camera looks down its -Z; ZO: Vulkan's depth range is [0, 1];
// the flip: Vulkan's framebuffer y points down where GL's points up.
CameraMatrices camera_matrices(const glm::mat4& camera_world, float yfov, float znear, float zfar, std::uint32_t width,
                               std::uint32_t height) {
  CameraMatrices camera;
  camera.view = glm::inverse(camera_world);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  camera.projection = glm::perspectiveRH_ZO(yfov, aspect, znear, zfar);
  camera.projection[1][1] *= -1.0f;
  return camera;
}

// soundpaint's calls return sp::Result; its value() throws the error as an
// std::exception whose what() is the error's one-line message, which main()
// prints like the host's own failures.
void run(const Options& options, ValidationLog* log) {
  // >>> soundpaint
  const sp::Scene scene = sp::load_scene(options.scene).value();
  if (!scene.camera) fail(options.scene.string() + ": the scene has no camera to render from");
  const CameraMatrices camera = camera_matrices(scene.camera->world, scene.camera->yfov, scene.camera->znear,
                                                scene.camera->zfar, options.width, options.height);
  // The default configuration puts the listener at the scene's camera.
  sp::Config config;
  config.display.offscreen_arrows = true;  // arrows for sources heard out of view
  sp::World world = sp::make_world(scene, config).value();
  const double dt = world.config.dt;  // a frame per simulation step
  // <<< soundpaint

  HostContext host(log);
  OffscreenTarget target(host, options.width, options.height);
  // >>> soundpaint
  const SceneRenderer scene_renderer(host, scene.vertices, OffscreenTarget::kColorFormat,
                                     OffscreenTarget::kDepthFormat);
  const sp::HostVulkan host_vulkan{.instance = host.instance(),
                                   .physical_device = host.physical_device(),
                                   .device = host.device(),
                                   .queue_family = host.queue_family(),
                                   .enabled_features = host.enabled_features()};
  const sp::DrawTarget draw_target{.color_format = OffscreenTarget::kColorFormat,
                                   .depth_format = OffscreenTarget::kDepthFormat};
  sp::VisualizerSettings settings;
  settings.backend = options.backend == "cpu"   ? sp::BackendChoice::Cpu
                     : options.backend == "gpu" ? sp::BackendChoice::Gpu
                                                : sp::BackendChoice::Auto;
  const std::unique_ptr<sp::Visualizer> visualizer =
      sp::Visualizer::create(host_vulkan, draw_target, std::move(world), settings).value();
  visualizer->set_scene_depth(std::array{target.depth_view()}).value();  // spots clipped to the scene's surfaces
  const sp::DrawOptions spots{.viewport_width = target.width(), .viewport_height = target.height(), .scene_depth = 0};
  // <<< soundpaint
  // Declared after the visualizer so that it is destroyed first, waiting for
  // the frames in flight that use the visualizer's buffers.
  FrameSlots frames(host);

  // --frames 0 renders the bare scene once: the picture without soundpaint.
  const bool simulate = options.frames > 0;
  const std::uint64_t frame_count = std::max<std::uint32_t>(options.frames, 1);
  for (std::uint64_t frame = 0; frame < frame_count; ++frame) {
    const VkCommandBuffer cmd = frames.begin(frame);
    // >>> soundpaint
    if (simulate) visualizer->record_simulation(cmd, dt).value();
    // <<< soundpaint
    target.begin(cmd);
    scene_renderer.draw(cmd, camera.projection * camera.view);
    // >>> soundpaint
    target.begin_overlays(cmd);
    if (simulate) visualizer->record_draw(cmd, camera.view, camera.projection, spots).value();
    // <<< soundpaint
    target.end(cmd);
    if (frame + 1 == frame_count) target.record_readback(cmd);
    frames.submit(frame);
  }
  frames.wait_idle();
  write_png(options.output, target.width(), target.height(), target.pixels());
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    options = parse_options(argc, argv);
  } catch (const UsageError& error) {
    std::fprintf(stderr, "soundpaint_embed_example: %s\n%s\n", error.what(), kUsage);
    return 2;
  }
  if (options.help) {
    std::printf("%s\n", kUsage);
    return 0;
  }

  ValidationLog log;
  int status = 0;
  try {
    run(options, options.validation ? &log : nullptr);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "soundpaint_embed_example: %s\n", error.what());
    status = 1;
  }
  // Read after run() has destroyed the instance, whose teardown reports leaks.
  const std::uint32_t messages = log.count.load();
  if (messages > 0) {
    std::fprintf(stderr, "soundpaint_embed_example: validation messages: %u\n", messages);
    if (status == 0) status = 3;
  }
  return status;
}
