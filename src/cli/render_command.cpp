// `soundpaint render`: simulate N steps, then draw the scene and the live
// indicators through the graphics pass into a PNG (or K PNGs of K further
// steps with --frames).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <utility>

#include "cli/commands.h"
#include "cli/frame_pattern.h"
#include "cli/limit_options.h"
#include "cli/options.h"
#include "cli/world_loading.h"
#include "cli/event_options.h"
#include "render/png_writer.h"
#include "render/renderer.h"
#include "render/view_camera.h"
#include "io/atomic_file.h"
#include "io/output_path.h"
#include "vk/context.h"

namespace sp::cli {
namespace {

constexpr const char* kRenderHelp =
    "usage: soundpaint render SCENE --out IMAGE.png [--config FILE] [--backend cpu|gpu|auto]\n"
    "                         [--steps N] [--seed S] [--threads T] [--width W] [--height H]\n"
    "                         [--camera-pos x,y,z] [--look-at x,y,z] [--fov DEGREES] [--frames K]\n"
    "                         [--max-triangles N] [--allow-external-uris] [--memory-budget SIZE]\n"
    "\n"
    "Simulates N steps (default 60) of SCENE, then draws the scene (tinted by layer, with\n"
    "markers at the sources and the listener) and every live indicator into a PNG.\n"
    "  --out FILE           the PNG to write (a regular file, written through a symbolic link,\n"
    "                       or - for standard output); with --frames a pattern such as frame%04d.png\n"
    "  --config FILE        JSON configuration (see README: configuration keys)\n"
    "  --backend B          cpu, gpu or auto (default auto); drawing always needs a Vulkan device\n"
    "  --steps N            steps simulated before the (first) picture, each dt seconds (default 60)\n"
    "  --seed S             overrides the config's seed (0..4294967295)\n"
    "  --threads T          CPU backend worker threads (default: all cores)\n"
    "  --width W, --height H  image size in pixels, 1..8192 (default 1280 x 720)\n"
    "  --camera-pos x,y,z   camera position in metres (default: the scene's camera, moved to\n"
    "                       the config's listener if it sets one; else the listener)\n"
    "  --look-at x,y,z      point the camera faces (default: the scene camera's direction, or\n"
    "                       the scene's centre when it has no camera)\n"
    "  --fov DEGREES        vertical field of view (default: the scene camera's, else 46)\n"
    "  --frames K           after the N steps, write K pictures of K further steps, frame k\n"
    "                       (0..K-1) to the --out pattern with k in its %d / %0Nd\n";

// Largest accepted --width / --height; the device may allow less.
constexpr std::uint64_t kMaxImageSide = 8192;

void check_device_limit(const vk::Context& context, std::uint32_t width, std::uint32_t height) {
  const std::uint32_t limit = context.properties().limits.maxImageDimension2D;
  for (auto [name, value] : {std::pair{"--width", width}, std::pair{"--height", height}}) {
    if (value > limit)
      throw Exception(ErrorCode::InvalidArgument, std::string("option ") + name + ": " + std::to_string(value) +
                                                      " exceeds the device's maximum image size " +
                                                      std::to_string(limit));
  }
}

}  // namespace

int run_render(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(
      args,
      with_options(with_options(with_options({"--config", "--backend", "--steps", "--seed", "--threads", "--out",
                                              "--width", "--height", "--camera-pos", "--look-at", "--fov", "--frames"},
                                             kSceneLimitValueOptions),
                                kMemoryLimitValueOptions),
                   kEventValueOptions),
      with_options({"--help"}, kSceneLimitFlagOptions));
  if (printed_help(parsed, {kRenderHelp, scene_limit_help(), memory_limit_help(), event_help(),
                            "  (with --events and no --camera-pos, the picture is taken from the trace's listener,\n"
                            "   the player, facing where the player faced)\n"}))
    return 0;
  const std::string& scene_path = scene_argument(parsed, "render");
  const std::optional<std::string> out = parsed.value("--out");
  if (!out) throw Exception(ErrorCode::InvalidArgument, "render needs --out IMAGE.png (see --help)");
  const std::uint64_t steps = parsed.unsigned_value("--steps", 0, 100'000'000).value_or(60);
  const auto seed = parsed.unsigned_value("--seed", 0, 0xFFFFFFFFull);
  const auto threads = parsed.unsigned_value("--threads", 1, 1024);
  draw::RenderSettings settings;
  settings.width = static_cast<std::uint32_t>(parsed.unsigned_value("--width", 1, kMaxImageSide).value_or(1280));
  settings.height = static_cast<std::uint32_t>(parsed.unsigned_value("--height", 1, kMaxImageSide).value_or(720));
  const std::optional<std::uint64_t> frames = parsed.unsigned_value("--frames", 1, 1'000'000);
  std::optional<FramePattern> pattern;
  if (frames) pattern = FramePattern::parse(*out, "--out");
  draw::CameraOverrides overrides;
  if (auto text = parsed.value("--camera-pos")) overrides.position = parse_vec3("--camera-pos", *text);
  if (auto text = parsed.value("--look-at")) overrides.look_at = parse_vec3("--look-at", *text);
  if (auto text = parsed.value("--fov")) overrides.yfov_degrees = parse_fov(*text);
  const BackendChoice backend = parse_backend(parsed.value("--backend").value_or("auto"));
  std::optional<events::TraceReplay> replay = load_event_replay(parsed);

  // An unwritable output fails now, not after the simulation; the file only
  // appears under its name once complete.
  std::optional<AtomicFile> single_output;
  if (pattern) {
    AtomicFile probe(pattern->format(0));  // removed again unless committed
  } else {
    single_output.emplace(*out);
  }

  LoadedWorld loaded = load_scene_and_world(scene_path, parsed.value("--config"), seed, scene_load_options(parsed));
  auto created = vk::Context::create();
  if (!created) throw Exception(ErrorCode::Vulkan, "render needs a Vulkan device to draw: " + created.error().message);
  // Declared first, destroyed last: the simulator and renderer use it.
  std::unique_ptr<vk::Context> context = std::move(created.value());
  check_device_limit(*context, settings.width, settings.height);
  std::unique_ptr<Simulator> simulator = create_simulator_on(
      *context, std::move(loaded.world), backend, static_cast<unsigned>(threads.value_or(0)), memory_budget(parsed));
  draw::Renderer renderer(*context, simulator->world(), settings);
  const double dt = simulator->world().config.dt;
  auto step = [&](std::uint64_t n) {
    if (replay) replay->advance(simulator->scene(), static_cast<double>(n) * dt);
    simulator->step().value();
  };
  for (std::uint64_t n = 0; n < steps; ++n) step(n);
  // A replayed game is seen from its player, unless the options say otherwise.
  if (replay && replay->listener() && !overrides.position) {
    overrides.position = glm::vec3(*replay->listener());
    if (replay->forward() && !overrides.look_at) {
      const Vec3 p = *replay->listener(), f = *replay->forward();
      overrides.look_at = glm::vec3(p.x + f.x, p.y + f.y, p.z + f.z);
    }
  }
  const draw::ViewCamera camera =
      draw::make_view_camera(loaded.scene.camera, simulator->world(), overrides, settings.width, settings.height);
  if (!pattern) {
    single_output->write(draw::encode_png(renderer.render(camera, *simulator)));
    single_output->commit();
    // A PNG on standard output leaves the summary to stderr.
    std::fprintf(names_stdout(*out) ? stderr : stdout, "%s: %ux%u after %llu steps on %s\n", out->c_str(),
                 settings.width, settings.height, static_cast<unsigned long long>(steps),
                 backend_name(simulator->backend()));
    return 0;
  }
  for (std::uint64_t k = 0; k < *frames; ++k) {
    step(steps + k);
    draw::write_png(pattern->format(k), renderer.render(camera, *simulator));
  }
  std::printf("%llu frames %s .. %s: %ux%u, after %llu..%llu steps on %s\n", static_cast<unsigned long long>(*frames),
              pattern->format(0).c_str(), pattern->format(*frames - 1).c_str(), settings.width, settings.height,
              static_cast<unsigned long long>(steps + 1), static_cast<unsigned long long>(steps + *frames),
              backend_name(simulator->backend()));
  return 0;
}

}  // namespace sp::cli
