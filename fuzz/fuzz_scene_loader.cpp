// Fuzz target: the glTF scene loader, with external buffers (scenes come
// from strangers), and what `soundpaint check` then does with the level.
// The input is a scene file, then up to three buffer files (fuzz_input.h),
// written into a scene folder that also holds a link out of it; beside the
// folder lies a canary buffer that must never be opened, watched with
// inotify. Any input must load or fail with a one-line message, and never
// open the canary.
//
// A scene that loads is then checked as `soundpaint check` checks it, with
// diffraction on and a small probe: mesh topology, the BVH build, the
// exposed edges and a few dozen rays cast through the tree. Loading is
// rarely where a level is slow; these are (issue 38: coincident triangles,
// slivers, far coordinates and combs that cost minutes), so a slow input
// counts as a finding (scripts/fuzz.sh --timeout).
#include <stdlib.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fuzz_input.h"
#include "soundpaint/check.h"
#include "soundpaint/config.h"
#include "soundpaint/scene.h"

namespace {

namespace fs = std::filesystem;

// The unit triangle's 36 bytes: a valid buffer, so that a URI reaching
// the canary would load rather than fail for some other reason.
constexpr float kTriangle[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

void write(const fs::path& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// root/level: scene.gltf, a.bin, sub/b.bin, c.bin, link.bin -> the canary;
// root/outside/canary.bin.
struct Sandbox {
  fs::path level;
  fs::path canary;
  int watch = -1;

  Sandbox() {
    char pattern[] = "/tmp/soundpaint-fuzz-XXXXXX";
    const char* root = ::mkdtemp(pattern);
    if (root == nullptr) std::abort();
    level = fs::path(root) / "level";
    fs::create_directories(level / "sub");
    fs::create_directories(fs::path(root) / "outside");
    canary = fs::path(root) / "outside" / "canary.bin";
    write(canary, std::string_view(reinterpret_cast<const char*>(kTriangle), sizeof kTriangle));
    fs::create_symlink(canary, level / "link.bin");
    watch = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (watch < 0 || inotify_add_watch(watch, canary.c_str(), IN_OPEN | IN_ACCESS) < 0) std::abort();
  }
  ~Sandbox() {
    std::error_code ignored;
    fs::remove_all(level.parent_path(), ignored);
  }

  bool canary_touched() const {
    alignas(inotify_event) char buffer[4096];
    return ::read(watch, buffer, sizeof buffer) > 0;
  }
};

Sandbox& sandbox() {
  static Sandbox instance;
  return instance;
}

// Levels up to this many triangles (every instance counted) are checked.
// An input within -max_len can instance a mesh to the loader's 2,000,000,
// whose O(n log n) build under the sanitizers takes seconds without any
// fault; the hostile shapes are quadratic, and at this size cost a minute
// or more (a comb of 51,200 teeth: issue 38).
constexpr std::size_t kMaxCheckedTriangles = 1u << 16;

bool one_line(const std::string& message) { return message.find('\n') == std::string::npos; }

// `soundpaint check` on a loaded level, shrunk to one probe step of 64
// rays, on one thread (deterministic, and no threads left behind).
void check_level(const sp::Scene& scene) {
  sp::Config config;
  config.diffraction.enabled = true;  // the exposed edges are found, and rays bend round them
  sp::CheckSettings settings;
  settings.probe_steps = 1;
  settings.probe_rays_per_step = 64;
  settings.threads = 1;
  const sp::Result<sp::CheckReport> report = sp::check_scene(scene, config, settings);
  if (!report.ok()) {
    if (!one_line(report.error().message)) __builtin_trap();
    return;
  }
  for (const sp::CheckFinding& finding : report->findings)
    if (!one_line(finding.message)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Sandbox& box = sandbox();
  const auto parts = sp::fuzz::split_parts(data, size);
  static const char* const kBufferNames[] = {"a.bin", "sub/b.bin", "c.bin"};
  write(box.level / "scene.gltf", parts[0]);
  for (std::size_t i = 0; i < 3; ++i) {
    write(box.level / kBufferNames[i], i + 1 < parts.size() ? parts[i + 1] : std::string_view());
  }
  const sp::Result<sp::Scene> scene = sp::load_scene(box.level / "scene.gltf");
  if (!scene.ok() && !one_line(scene.error().message)) __builtin_trap();
  if (box.canary_touched()) {
    std::fprintf(stderr, "the canary outside the scene's folder was opened\n");
    __builtin_trap();
  }
  if (scene.ok() && scene->triangle_count() <= kMaxCheckedTriangles) check_level(*scene);
  return 0;
}
