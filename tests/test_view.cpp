// `soundpaint view` end to end under Xvfb with lavapipe: scripted runs
// (--frames, --screenshot) on both backends show the indicators with zero
// validation messages, a window resized while it runs keeps working, and
// with no display the command fails with one line that suggests render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "sp_types.h"
#include "support/render_checks.h"
#include "support/run_command.h"
#include "support/vulkan_environment.h"

namespace sp {
namespace {

using test::run_command;
using test::ScratchDir;

const std::string kCli = SP_CLI_PATH;
const std::string kScene = std::string(SP_SCENES_DIR) + "/two_rooms.gltf";

bool have_xvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

// A virtual X display of its own for each run (-a), validation on.
std::string under_xvfb(const std::string& args) {
  return "SOUNDPAINT_VALIDATION=1 xvfb-run -a -s '-screen 0 1024x768x24' " + kCli + " view " + args;
}

#define SKIP_WITHOUT_XVFB()                                                                            \
  do {                                                                                                 \
    if (!have_xvfb()) {                                                                                \
      if (test::ci_requires_vulkan()) FAIL() << "xvfb-run is missing on CI (scripts/install-deps.sh)"; \
      GTEST_SKIP() << "xvfb-run is not installed";                                                     \
    }                                                                                                  \
  } while (0)

class ViewBackends : public ::testing::TestWithParam<const char*> {};

// 90 frames of 1/60 s: the spots drawn are what a scripted run shows; the
// same run with no rays shows the bare level. The difference is the spots.
TEST_P(ViewBackends, ScriptedRunShowsTheIndicatorsWithoutValidationMessages) {
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view");
  std::ofstream(dir / "silent.json") << R"({"ray_budget": 0})";
  const std::string common = kScene + " --backend " + GetParam() + " --width 480 --height 320 --frames 90 --no-panel";
  auto sound = run_command(under_xvfb(common + " --screenshot " + (dir / "sound.png").string()), dir.path());
  ASSERT_EQ(sound.status, 0) << sound.err;
  EXPECT_EQ(sound.err.find("alidation"), std::string::npos) << sound.err;
  auto silent = run_command(under_xvfb(common + " --config " + (dir / "silent.json").string() + " --screenshot " +
                                       (dir / "silent.png").string()),
                            dir.path());
  ASSERT_EQ(silent.status, 0) << silent.err;
  const auto with_sound = test::load_png(dir / "sound.png");
  const auto without = test::load_png(dir / "silent.png");
  ASSERT_TRUE(with_sound && without);
  EXPECT_EQ(with_sound->width, 480u);
  EXPECT_EQ(with_sound->height, 320u);
  // The spots are in one only: hundreds of pixels, not the whole picture.
  const std::size_t spots = test::differing_pixels(*with_sound, *without, 24, nullptr);
  EXPECT_GT(spots, 400u);
  EXPECT_LT(spots, std::size_t{480} * 320 / 2);
  // The panel, shown by default, covers a good part of the top left.
  auto panel =
      run_command(under_xvfb(kScene + " --backend " + GetParam() + " --width 480 --height 320 --frames 90 --config " +
                             (dir / "silent.json").string() + " --screenshot " + (dir / "panel.png").string()),
                  dir.path());
  ASSERT_EQ(panel.status, 0) << panel.err;
  const auto with_panel = test::load_png(dir / "panel.png");
  ASSERT_TRUE(with_panel);
  EXPECT_GT(test::differing_pixels(*with_panel, *without, 24, nullptr), std::size_t{480} * 320 / 10);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewBackends, ::testing::Values("cpu", "gpu"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           return std::string(param_info.param);
                         });

TEST(View, AResizedWindowGetsANewSwapchainAndKeepsDrawing) {
  // The window grows at frame 10 (no window manager under Xvfb: the X
  // server grants the size at once); the swapchain, depth images and the
  // panel's framebuffers follow, and the last frame has the new size.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-resize");
  auto r =
      run_command(under_xvfb(kScene + " --backend gpu --width 320 --height 240 --frames 30 --resize-at 10,400,300" +
                             " --screenshot " + (dir / "resized.png").string()),
                  dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("alidation"), std::string::npos) << r.err;
  const auto picture = test::load_png(dir / "resized.png");
  ASSERT_TRUE(picture);
  EXPECT_EQ(picture->width, 400u);
  EXPECT_EQ(picture->height, 300u);
}

TEST(View, AConfigFileSavedWhileRunningIsReloaded) {
  // The run starts silent (no rays); once the viewer says it watches the
  // file, the file is saved with rays: the last frame shows spots, and
  // stderr says it reloaded. Silent frames take milliseconds, so 300 of
  // them leave time for the save and the check (every 30 frames).
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-reload");
  const auto config = dir / "live.json";
  const auto log = dir / "viewer.err";
  std::ofstream(config) << R"({"ray_budget": 0})";
  std::ofstream(dir / "loud.json") << R"({"ray_budget": 100})";
  const std::string viewer =
      under_xvfb(kScene + " --backend cpu --width 320 --height 240 --frames 300 --no-panel --config " +
                 config.string() + " --screenshot " + (dir / "reloaded.png").string());
  // At most 30 s of waiting, so a viewer that fails early cannot hang the test.
  const std::string save_when_watched = "(for i in $(seq 600); do grep -q watching " + log.string() +
                                        " 2>/dev/null && break; sleep 0.05; done; cp " + (dir / "loud.json").string() +
                                        " " + config.string() + ")";
  auto r = run_command("{ " + save_when_watched + " & " + viewer + " 2>" + log.string() + "; status=$?; wait; cat " +
                           log.string() + " >&2; exit $status; }",
                       dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("reloaded"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("alidation"), std::string::npos) << r.err;
  std::ofstream(config, std::ios::trunc) << R"({"ray_budget": 0})";
  auto silent =
      run_command(under_xvfb(kScene + " --backend cpu --width 320 --height 240 --frames 10 --no-panel --config " +
                             config.string() + " --screenshot " + (dir / "silent.png").string()),
                  dir.path());
  ASSERT_EQ(silent.status, 0) << silent.err;
  const auto reloaded = test::load_png(dir / "reloaded.png");
  const auto without = test::load_png(dir / "silent.png");
  ASSERT_TRUE(reloaded && without);
  EXPECT_GT(test::differing_pixels(*reloaded, *without, 24, nullptr), 200u);
}

TEST(View, TheStartViewComesFromTheCommandLine) {
  // Looking at the floor from above and at the ceiling from below: two
  // different pictures of the same level, each drawn without a message.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-camera");
  auto shot = [&](const std::string& look, const std::string& name) {
    auto r = run_command(under_xvfb(kScene + " --backend cpu --width 160 --height 120 --frames 2 --no-panel " + look +
                                    " --screenshot " + (dir / name).string()),
                         dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    return test::load_png(dir / name);
  };
  const auto down = shot("--camera-pos 0,2.5,0 --look-at 0.1,0,0", "down.png");
  const auto up = shot("--camera-pos 0,0.5,0 --look-at 0.1,3,0", "up.png");
  ASSERT_TRUE(down && up);
  EXPECT_GT(test::differing_pixels(*down, *up, 24, nullptr), std::size_t{160} * 120 / 4);
}

TEST(View, WithoutADisplayFailsWithOneLineSuggestingRender) {
  ScratchDir dir("view-headless");
  auto r = run_command("env -u DISPLAY -u WAYLAND_DISPLAY " + kCli + " view " + kScene + " --frames 1", dir.path());
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("render"), std::string::npos) << r.err;
}

TEST(View, HelpListsTheControlsAndBadOptionsFail) {
  ScratchDir dir("view-help");
  auto help = run_command(kCli + " view --help", dir.path());
  EXPECT_EQ(help.status, 0);
  for (const char* control : {"W A S D", "right mouse", "left click", "Space", "Esc", "--screenshot"})
    EXPECT_NE(help.out.find(control), std::string::npos) << control;
  auto bad = run_command(kCli + " view " + kScene + " --screenshot x.png", dir.path());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--frames"), std::string::npos) << bad.err;
  auto missing = run_command(kCli + " view /nonexistent.gltf --frames 1", dir.path());
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.err.find("/nonexistent.gltf"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace sp
