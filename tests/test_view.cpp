// `soundpaint view` end to end under Xvfb with lavapipe: scripted runs
// (--frames, --screenshot) on both backends show the indicators with zero
// validation messages, a window resized while it runs keeps working, a
// config reload that fails keeps the running config, a bad screenshot path
// fails before the first frame, and with no display the command fails with
// one line that suggests render.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

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

// A virtual X display of its own for each run (-a), validation on. The X
// cookie is kept in the test's scratch folder (-f): left to itself,
// xvfb-run makes a folder of its own for it and, when removing that folder
// fails at the end, exits 5 in place of the viewer's status, which a test
// would then read as the viewer's.
std::string under_xvfb(const ScratchDir& scratch, const std::string& args) {
  return "SOUNDPAINT_VALIDATION=1 xvfb-run -a -f '" + (scratch / "xauthority").string() +
         "' -s '-screen 0 1024x768x24' " + kCli + " view " + args;
}

// A viewer run with --config-checks-from-stdin, driven by the test: each
// line sent names the frame before which the viewer checks its config next,
// and the viewer waits for that line; the checks' reports are read back from
// its stderr. The test changes the file, then names the frame: the reload
// happens before that frame on any machine, with no sleeping. Nothing here
// can hang: a read gives up after five minutes without output (a hang
// guard, under ctest's --timeout, not a timing check), and a run not
// finished is killed with its whole process group (xvfb-run, Xvfb, the
// viewer).
class DrivenViewer {
 public:
  explicit DrivenViewer(const std::string& command) {
    ::signal(SIGPIPE, SIG_IGN);  // a viewer that died early: send() fails instead
    int to_child[2], from_child[2];
    if (::pipe(to_child) != 0 || ::pipe(from_child) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::setpgid(0, 0);
      ::dup2(to_child[0], 0);
      ::dup2(from_child[1], 2);
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      for (int fd : {to_child[0], to_child[1], from_child[0], from_child[1], null}) ::close(fd);
      ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(to_child[0]);
    ::close(from_child[1]);
    input_ = to_child[1];
    errors_ = from_child[0];
  }
  ~DrivenViewer() {
    if (input_ >= 0) ::close(input_);
    if (errors_ >= 0) ::close(errors_);
    if (pid_ > 0 && status_ < 0) {
      ::kill(-pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  DrivenViewer(const DrivenViewer&) = delete;
  DrivenViewer& operator=(const DrivenViewer&) = delete;

  bool send(const std::string& line) {
    const std::string text = line + "\n";
    return ::write(input_, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  }

  // The first line of stderr not yet returned that contains `text`, or
  // nothing when stderr ends first.
  std::optional<std::string> wait_for(const std::string& text) {
    for (;;) {
      const std::size_t found = err_.find(text, consumed_);
      const std::size_t end = found == std::string::npos ? std::string::npos : err_.find('\n', found);
      if (end != std::string::npos) {
        const std::size_t begin = err_.rfind('\n', found);
        const std::size_t start = begin == std::string::npos || begin < consumed_ ? consumed_ : begin + 1;
        consumed_ = end + 1;
        return err_.substr(start, end - start);
      }
      if (!read_some()) return std::nullopt;
    }
  }

  // Ends the input (the remaining frames then run) and waits for the exit.
  int finish() {
    ::close(input_);
    input_ = -1;
    while (read_some()) {
    }
    int raw = 0;
    if (::waitpid(pid_, &raw, 0) != pid_) return -1;
    status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    return status_;
  }

  const std::string& err() const { return err_; }

 private:
  bool read_some() {
    pollfd ready{errors_, POLLIN, 0};
    if (::poll(&ready, 1, 300'000) != 1) return false;  // a hang guard, not a timing check
    char buffer[4096];
    const ssize_t got = ::read(errors_, buffer, sizeof buffer);
    if (got <= 0) return false;
    err_.append(buffer, static_cast<std::size_t>(got));
    return true;
  }

  pid_t pid_ = -1;
  int input_ = -1;
  int errors_ = -1;
  int status_ = -1;
  std::string err_;
  std::size_t consumed_ = 0;
};

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
  auto sound = run_command(under_xvfb(dir, common + " --screenshot " + (dir / "sound.png").string()), dir.path());
  ASSERT_EQ(sound.status, 0) << sound.err;
  EXPECT_EQ(sound.err.find("alidation"), std::string::npos) << sound.err;
  auto silent = run_command(under_xvfb(dir, common + " --config " + (dir / "silent.json").string() + " --screenshot " +
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
  auto panel = run_command(
      under_xvfb(dir, kScene + " --backend " + GetParam() + " --width 480 --height 320 --frames 90 --config " +
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
  auto r = run_command(
      under_xvfb(dir, kScene + " --backend gpu --width 320 --height 240 --frames 30 --resize-at 10,400,300" +
                          " --screenshot " + (dir / "resized.png").string()),
      dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("alidation"), std::string::npos) << r.err;
  const auto picture = test::load_png(dir / "resized.png");
  ASSERT_TRUE(picture);
  EXPECT_EQ(picture->width, 400u);
  EXPECT_EQ(picture->height, 300u);
}

// A CPU run of `frames` frames with the config in `config` (cut to what the
// tests below compare: no panel, a small window), its last frame as `shot`.
std::string scripted_cpu_run(const std::filesystem::path& config, std::uint64_t frames,
                             const std::filesystem::path& shot) {
  return kScene + " --backend cpu --width 320 --height 240 --no-panel --frames " + std::to_string(frames) +
         " --config " + config.string() + " --screenshot " + shot.string();
}

// The pixels two screenshots differ in (by more than rounding).
std::size_t pixels_between(const std::filesystem::path& a, const std::filesystem::path& b) {
  const auto first = test::load_png(a);
  const auto second = test::load_png(b);
  if (!first || !second) {
    ADD_FAILURE() << "unreadable: " << a << " or " << b;
    return SIZE_MAX;
  }
  return test::differing_pixels(*first, *second, 8, nullptr);
}

TEST(View, AConfigFileSavedWhileRunningIsReloadedBeforeTheFrameNamed) {
  // The run starts silent (no rays); the file is saved with rays and the
  // check named for frame 20 of 50. Every frame of a scripted run shows the
  // steps of the frames before it (the CPU backend's too), so from frame 20
  // on the run draws what a run started with the new file draws in its
  // first 30 frames: the same last frame, pixel for pixel. A reload one
  // frame early or late would show spots a step older or younger; that this
  // is visible is checked too, as is that the spots are there at all.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-reload");
  const auto config = dir / "live.json";
  std::ofstream(config) << R"({"ray_budget": 0})";
  DrivenViewer viewer(
      under_xvfb(dir, scripted_cpu_run(config, 50, dir / "reloaded.png") + " --config-checks-from-stdin"));
  ASSERT_TRUE(viewer.wait_for("watching")) << viewer.err();
  std::ofstream(config, std::ios::trunc) << R"({"ray_budget": 100})";
  ASSERT_TRUE(viewer.send("20"));
  const auto reloaded = viewer.wait_for("view: reloaded " + config.string());
  ASSERT_TRUE(reloaded) << viewer.err();
  // The new ray budget (the panel's slider takes the same path) shares the
  // level's geometry: the BVH built at start is the only one.
  EXPECT_NE(reloaded->find("(ray budget 100; the level's BVH built 1 time(s) this run)"), std::string::npos)
      << *reloaded;
  ASSERT_EQ(viewer.finish(), 0) << viewer.err();
  EXPECT_EQ(viewer.err().find("alidation"), std::string::npos) << viewer.err();

  for (const std::uint64_t frames : {std::uint64_t{30}, std::uint64_t{29}}) {
    auto fresh = run_command(under_xvfb(dir, scripted_cpu_run(config, frames, dir / (std::to_string(frames) + ".png"))),
                             dir.path());
    ASSERT_EQ(fresh.status, 0) << fresh.err;
  }
  std::ofstream(dir / "silent.json") << R"({"ray_budget": 0})";
  auto silent = run_command(under_xvfb(dir, scripted_cpu_run(dir / "silent.json", 50, dir / "silent.png")), dir.path());
  ASSERT_EQ(silent.status, 0) << silent.err;
  EXPECT_EQ(pixels_between(dir / "reloaded.png", dir / "30.png"), 0u) << "not the frames of the new config from 20 on";
  EXPECT_GT(pixels_between(dir / "30.png", dir / "29.png"), 0u) << "a frame's shift would not show";
  EXPECT_GT(pixels_between(dir / "reloaded.png", dir / "silent.png"), 200u) << "no spots after the reload";
}

TEST(View, AReloadThatCannotRunKeepsTheRunningConfigAndSaysWhy) {
  // The file is saved with a config that parses but is far over the memory
  // budget, checked before frame 10: the viewer says why on one line, keeps
  // drawing with the config it had, exactly as a run never given the bad
  // file (which shows spots, where a silent run has none), and exits 0.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-over-budget");
  const auto config = dir / "live.json";
  std::ofstream(config) << R"({"ray_budget": 100})";
  DrivenViewer viewer(under_xvfb(dir, scripted_cpu_run(config, 40, dir / "kept.png") + " --config-checks-from-stdin"));
  ASSERT_TRUE(viewer.wait_for("watching")) << viewer.err();
  std::ofstream(config, std::ios::trunc) << R"({"ray_budget": 16777216, "max_bounces": 64})";
  ASSERT_TRUE(viewer.send("10"));
  const auto kept = viewer.wait_for("keeping the running config");
  ASSERT_TRUE(kept) << viewer.err();
  for (const char* part : {"live.json", "over the memory budget of 2.0 GiB", "--memory-budget"})
    EXPECT_NE(kept->find(part), std::string::npos) << part << " in: " << *kept;
  ASSERT_EQ(viewer.finish(), 0) << viewer.err();
  EXPECT_EQ(viewer.err().find("reloaded"), std::string::npos) << viewer.err();

  std::ofstream(config, std::ios::trunc) << R"({"ray_budget": 100})";
  auto unchanged = run_command(under_xvfb(dir, scripted_cpu_run(config, 40, dir / "unchanged.png")), dir.path());
  ASSERT_EQ(unchanged.status, 0) << unchanged.err;
  std::ofstream(config, std::ios::trunc) << R"({"ray_budget": 0})";
  auto silent = run_command(under_xvfb(dir, scripted_cpu_run(config, 40, dir / "silent.png")), dir.path());
  ASSERT_EQ(silent.status, 0) << silent.err;
  EXPECT_EQ(pixels_between(dir / "kept.png", dir / "unchanged.png"), 0u);
  EXPECT_GT(pixels_between(dir / "kept.png", dir / "silent.png"), 200u);
}

TEST(View, ASaveInTwoPartsWithinOneMtimeTickIsReloaded) {
  // A save cut in two: the check before frame 2 finds half a file (refused,
  // the silent config stays); the rest lands within the same mtime tick (set
  // back here, as a coarse clock would leave it) and is checked before frame
  // 5. The whole file is still seen and reloaded: the viewer watches the
  // bytes, not the mtime.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-two-part");
  const auto config = dir / "live.json";
  std::ofstream(config) << R"({"ray_budget": 0})";
  DrivenViewer viewer(under_xvfb(dir, kScene +
                                          " --backend cpu --width 320 --height 240 --frames 10 --no-panel --config " +
                                          config.string() + " --config-checks-from-stdin"));
  ASSERT_TRUE(viewer.wait_for("watching")) << viewer.err();
  std::ofstream(config, std::ios::trunc) << R"({"ray_budget": 1)";
  struct stat first {};
  ASSERT_EQ(::stat(config.c_str(), &first), 0);
  ASSERT_TRUE(viewer.send("2"));
  const auto refused = viewer.wait_for("keeping the running config");
  ASSERT_TRUE(refused) << viewer.err();
  EXPECT_NE(refused->find("live.json"), std::string::npos) << *refused;

  std::ofstream(config, std::ios::app) << "00}";
  const timespec times[2] = {{0, UTIME_OMIT}, first.st_mtim};
  ASSERT_EQ(::utimensat(AT_FDCWD, config.c_str(), times, 0), 0);
  ASSERT_TRUE(viewer.send("5"));
  ASSERT_TRUE(viewer.wait_for("view: reloaded " + config.string())) << viewer.err();
  ASSERT_EQ(viewer.finish(), 0) << viewer.err();
}

TEST(View, AScriptedCheckMustNameAFrame) {
  // The input is the test's script: a line that is not a frame number is an
  // error that says what was expected, not a check at some frame.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-bad-script");
  const auto config = dir / "live.json";
  std::ofstream(config) << R"({"ray_budget": 0})";
  DrivenViewer viewer(under_xvfb(dir, kScene +
                                          " --backend cpu --width 160 --height 120 --frames 10 --no-panel --config " +
                                          config.string() + " --config-checks-from-stdin"));
  ASSERT_TRUE(viewer.wait_for("watching")) << viewer.err();
  ASSERT_TRUE(viewer.send("check"));
  EXPECT_NE(viewer.finish(), 0) << viewer.err();
  EXPECT_NE(viewer.err().find("expected a frame number on each line, got 'check'"), std::string::npos) << viewer.err();
}

TEST(View, AScreenshotPathThatCannotBeWrittenFailsBeforeTheFirstFrame) {
  // Run with no display: a refusal made before the window opens names the
  // path, while one made later would be the missing display's. So the path
  // is refused before any frame could run (with no timing involved), on
  // one line, and nothing is left behind in the folder.
  ScratchDir dir("view-bad-screenshot");
  for (const std::string& bad : {dir.path().string(), (dir / "missing" / "shot.png").string()}) {
    auto r = run_command("env -u DISPLAY -u WAYLAND_DISPLAY " + kCli + " view " + kScene +
                             " --width 64 --height 64 --no-panel --frames 100000 --screenshot " + bad,
                         dir.path());
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("render"), std::string::npos) << "refused for the display, not the path: " << r.err;
  }
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    if (name != "stdout.txt" && name != "stderr.txt") left.push_back(name);
  }
  EXPECT_TRUE(left.empty()) << left.front();
}

TEST(View, MemoryBudgetIsAnOptionThatReachesTheSimulator) {
  // 50000 rays of up to 64 bounces could need 2.3 GiB on the CPU backend:
  // refused under the default 2 GiB budget, run under 4G. The default config
  // is refused under 1M: the budget is the one the visualizer checks.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-budget");
  std::ofstream(dir / "big.json") << R"({"ray_budget": 50000, "max_bounces": 64})";
  const std::string common = kScene + " --backend cpu --width 160 --height 120 --frames 3 --no-panel";
  auto refused = run_command(under_xvfb(dir, common + " --config " + (dir / "big.json").string()), dir.path());
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("over the memory budget of 2.0 GiB"), std::string::npos) << refused.err;
  auto raised = run_command(
      under_xvfb(dir, common + " --config " + (dir / "big.json").string() + " --memory-budget 4G"), dir.path());
  EXPECT_EQ(raised.status, 0) << raised.err;
  auto lowered = run_command(under_xvfb(dir, common + " --memory-budget 1M"), dir.path());
  EXPECT_EQ(lowered.status, 1);
  EXPECT_NE(lowered.err.find("over the memory budget of 1.0 MiB"), std::string::npos) << lowered.err;
  auto bad = run_command(kCli + " view " + kScene + " --frames 1 --memory-budget 4Q", dir.path());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("option --memory-budget"), std::string::npos) << bad.err;
}

TEST(View, TheStartViewComesFromTheCommandLine) {
  // Looking at the floor from above and at the ceiling from below: two
  // different pictures of the same level, each drawn without a message.
  SKIP_WITHOUT_XVFB();
  ScratchDir dir("view-camera");
  auto shot = [&](const std::string& look, const std::string& name) {
    auto r = run_command(under_xvfb(dir, kScene + " --backend cpu --width 160 --height 120 --frames 2 --no-panel " +
                                             look + " --screenshot " + (dir / name).string()),
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
  for (const char* control :
       {"W A S D", "right mouse", "left click", "Space", "Esc", "--screenshot", "--memory-budget"})
    EXPECT_NE(help.out.find(control), std::string::npos) << control;
  auto bad = run_command(kCli + " view " + kScene + " --screenshot x.png", dir.path());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--frames"), std::string::npos) << bad.err;
  auto unscripted = run_command(kCli + " view " + kScene + " --config-checks-from-stdin", dir.path());
  EXPECT_EQ(unscripted.status, 2);
  EXPECT_NE(unscripted.err.find("--config-checks-from-stdin needs"), std::string::npos) << unscripted.err;
  auto missing = run_command(kCli + " view /nonexistent.gltf --frames 1", dir.path());
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.err.find("/nonexistent.gltf"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace sp
