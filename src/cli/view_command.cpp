// `soundpaint view`: the interactive viewer (src/view/), when the build has
// it (GLFW and Dear ImGui found: cmake/imgui.cmake).
#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "cli/commands.h"
#include "cli/limit_options.h"
#include "cli/options.h"
#include "cli/world_loading.h"
#include "io/atomic_file.h"
#include "io/output_path.h"
#include "soundpaint/result.h"
#ifdef SOUNDPAINT_HAVE_VIEWER
#include "view/viewer.h"
#endif

namespace sp::cli {
namespace {

constexpr const char* kViewHelp =
    "usage: soundpaint view SCENE [--config FILE] [--backend cpu|gpu|auto] [--width W] [--height H]\n"
    "                       [--camera-pos x,y,z] [--look-at x,y,z] [--fov DEGREES]\n"
    "                       [--frames N] [--screenshot OUT.png] [--memory-budget SIZE]\n"
    "\n"
    "Opens a window in which you fly through SCENE while sound paints it, live. The\n"
    "listener follows the camera. Needs a display (X11 or Wayland); without one, use\n"
    "`soundpaint render`, which draws the same picture into a PNG.\n"
    "  --config FILE        JSON configuration (README: configuration keys), reloaded when its content\n"
    "                       changes; a reload that fails keeps the running config and says why\n"
    "  --backend B          cpu, gpu or auto (default auto); B switches while running\n"
    "  --width W, --height H  window size in pixels (default 1280 x 720)\n"
    "  --camera-pos, --look-at, --fov   the start view, as in render\n"
    "  --frames N           exit after N frames, each config.dt of game time (scripted runs)\n"
    "  --screenshot FILE    write the last frame as a PNG (with --frames); checked before the first\n"
    "                       frame, written as render's --out is\n"
    "  --resize-at K,W,H    at frame K ask the window for W x H pixels (scripted runs)\n"
    "  --config-checks-from-stdin  check --config before the frames standard input names, one\n"
    "                       number a line, until the input ends (scripted runs, with --frames)\n"
    "  --no-panel           start with the panel hidden (F1 shows it)\n"
    "\n"
    "controls:\n";

}  // namespace

int run_view(const std::vector<std::string>& args) {
  ParsedArgs parsed =
      parse_args(args,
                 with_options(with_options({"--config", "--backend", "--width", "--height", "--camera-pos", "--look-at",
                                            "--fov", "--frames", "--screenshot", "--resize-at"},
                                           kSceneLimitValueOptions),
                              kMemoryLimitValueOptions),
                 with_options({"--help", "--no-panel", "--config-checks-from-stdin"}, kSceneLimitFlagOptions));
#ifdef SOUNDPAINT_HAVE_VIEWER
  if (printed_help(parsed, {kViewHelp, view::kControls, scene_limit_help(), memory_limit_help()})) return 0;
  view::ViewerOptions options;
  options.scene_path = scene_argument(parsed, "view");
  options.config_path = parsed.value("--config");
  options.panel = parsed.flags.count("--no-panel") == 0;
  options.scene_options = scene_load_options(parsed);
  options.backend = parse_backend(parsed.value("--backend").value_or("auto"));
  options.width = static_cast<std::uint32_t>(parsed.unsigned_value("--width", 64, 8192).value_or(1280));
  options.height = static_cast<std::uint32_t>(parsed.unsigned_value("--height", 64, 8192).value_or(720));
  options.frames = parsed.unsigned_value("--frames", 1, 100'000'000).value_or(0);
  options.memory_budget_bytes = memory_budget(parsed);
  if (auto path = parsed.value("--screenshot")) {
    if (options.frames == 0)
      throw Exception(ErrorCode::InvalidArgument, "--screenshot needs --frames N (the frame it writes is the last)");
    // An unwritable path (a directory, a missing folder, a device) fails
    // now, not after the frames: the probe is removed again at once.
    AtomicFile probe(*path);
    options.screenshot = *path;
  }
  options.config_checks_from_stdin = parsed.flags.count("--config-checks-from-stdin") != 0;
  if (options.config_checks_from_stdin && (options.frames == 0 || !options.config_path))
    throw Exception(ErrorCode::InvalidArgument,
                    "--config-checks-from-stdin needs --config FILE and --frames N (it is for scripted runs)");
  if (auto text = parsed.value("--resize-at")) {
    const glm::vec3 v = parse_vec3("--resize-at", *text);
    if (!(v.x >= 1.0f && v.y >= 64.0f && v.z >= 64.0f && v.y <= 8192.0f && v.z <= 8192.0f))
      throw Exception(ErrorCode::InvalidArgument,
                      "option --resize-at: expected K,W,H with K >= 1 and 64 <= W, H <= 8192, got '" + *text + "'");
    options.resize_frame = static_cast<std::uint64_t>(v.x);
    options.resize_width = static_cast<std::uint32_t>(v.y);
    options.resize_height = static_cast<std::uint32_t>(v.z);
  }
  if (auto text = parsed.value("--camera-pos")) options.camera.position = parse_vec3("--camera-pos", *text);
  if (auto text = parsed.value("--look-at")) options.camera.look_at = parse_vec3("--look-at", *text);
  if (auto text = parsed.value("--fov")) options.camera.yfov_degrees = parse_fov(*text);
  const std::uint32_t messages = view::run_viewer(options);
  if (messages > 0) {
    std::fprintf(stderr, "soundpaint: view: %u Vulkan validation messages\n", messages);
    return 3;
  }
  // A PNG on standard output leaves the summary to stderr.
  if (options.screenshot)
    std::fprintf(names_stdout(*options.screenshot) ? stderr : stdout, "%s: the last of %llu frames\n",
                 options.screenshot->c_str(), static_cast<unsigned long long>(options.frames));
  return 0;
#else
  if (printed_help(parsed, {kViewHelp, scene_limit_help(), memory_limit_help(),
                            "  (this build has no viewer: GLFW or Dear ImGui was missing when it was configured)\n"}))
    return 0;
  throw Exception(ErrorCode::InvalidArgument,
                  "this soundpaint was built without the viewer (GLFW and Dear ImGui: libglfw3-dev, libimgui-dev); "
                  "`soundpaint render` draws the same picture into a PNG");
#endif
}

}  // namespace sp::cli
