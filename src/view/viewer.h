// `soundpaint view`: a window in which one flies through a level while
// sound paints it, live. The viewer is one more host of sp::Visualizer (the
// module games embed), drawing the level with the scene pass `render` uses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "render/view_camera.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"

namespace sp::view {

struct ViewerOptions {
  std::string scene_path;
  // Reloaded when its bytes change; a reload that fails for any reason
  // keeps the running config and says why.
  std::optional<std::string> config_path;
  SceneLoadOptions scene_options;
  BackendChoice backend = BackendChoice::Auto;
  std::uint32_t width = 1280;
  std::uint32_t height = 720;
  // > 0: exit after this many frames, each one config.dt of game time (a
  // scripted run: each frame also waits for the CPU backend's step, so the
  // frames show the same on any machine); 0: run in real time until the
  // window closes.
  std::uint64_t frames = 0;
  std::optional<std::filesystem::path> screenshot;  // the last frame, as PNG
  bool panel = true;                                // false: start with the panel hidden (F1 shows it)
  draw::CameraOverrides camera;
  // Scripted runs: at frame `resize_frame` (> 0) the window asks for
  // resize_width x resize_height, as a user dragging its border would.
  std::uint64_t resize_frame = 0;
  std::uint32_t resize_width = 0;
  std::uint32_t resize_height = 0;
  // A config whose rays and indicators could need more memory is refused,
  // at start and on reload (--memory-budget).
  std::uint64_t memory_budget_bytes = kDefaultMemoryBudgetBytes;
  // Scripted runs: instead of twice a second, the config file is checked
  // before the frames standard input names, one frame number a line (0 is
  // the first frame; a frame already reached means at once). The viewer
  // waits for each line at the start, and after each check, so a test
  // changes the file and then names the frame: the reload happens before
  // that frame, whatever the machine's speed. When the input ends the
  // remaining frames run with no more checks.
  bool config_checks_from_stdin = false;
};

// The keys and mouse, for --help and the panel.
extern const char* const kControls;

// Runs the viewer. Returns the validation messages seen (0 unless the
// Khronos layer is on: SOUNDPAINT_VALIDATION=1). Throws sp::Exception on
// bad input or when no window can be opened.
std::uint32_t run_viewer(const ViewerOptions& options);

}  // namespace sp::view
