// A folder swapped for a symbolic link while scenes load (issue 39): a
// check that resolves a path and an open that resolves it again can be told
// apart by a stranger who controls the level's folder. Here a thread swaps
// a subfolder of the level for a link to an outside folder, atomically and
// without pause, while the main thread loads the scene again and again. The
// outside folder holds files of the same names whose triangle sits far from
// the inside one, so a load that read outside shows it in its vertices.
// Every load must either read the inside files or fail naming the buffer;
// none may mix in outside bytes. Loops are bounded by count, not time.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdio.h>  // renameat2 (a GNU extension, so not <cstdio>)
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/beneath_open.h"
#include "soundpaint/scene.h"
#include "support/gltf_builder.h"
#include "support/test_directory.h"

namespace {

namespace fs = std::filesystem;
using sp::test::GltfBuilder;

// Loads per test: enough that the old check-then-open code read outside
// bytes in every run tried (25 of 25, from 2 to 900 of the loads), yet about
// two seconds a test.
constexpr int kLoads = 20000;

// Folders between the swapped one and the buffer: a check that resolves
// them one by one leaves that much longer for the swap to land in.
constexpr const char* kDeep = "a/b/c/d/e/f/g/h/";

// Where a triangle starts tells inside from outside bytes.
constexpr float kInsideX = 1.0f;
constexpr float kOutsideX = 100.0f;

sp::test::json json_primitive(GltfBuilder& b, float x) {
  return sp::test::json::array({{{"attributes", {{"POSITION", b.positions({{x, 0, 0}, {0, x, 0}, {0, 0, x}})}}}}});
}

// A one-triangle scene, (x,0,0) (0,x,0) (0,0,x), on layer `layer`.
GltfBuilder triangle_at(float x, const std::string& layer) {
  GltfBuilder b;
  const int mesh = b.mesh(json_primitive(b, x));
  b.root(b.node({{"mesh", mesh}, {"extras", {{"acoustic_layer", layer}}}}));
  return b;
}

// Swaps `a` and `b` (a folder and a link) atomically, over and over, until
// told to stop; in between, both names always exist.
class Swapper {
 public:
  Swapper(fs::path a, fs::path b) : a_(std::move(a)), b_(std::move(b)) {}
  ~Swapper() { stop(); }
  Swapper(const Swapper&) = delete;
  Swapper& operator=(const Swapper&) = delete;

  // False (with the reason) when this file system cannot exchange names.
  bool start(std::string& why_not) {
    if (!exchange()) {
      why_not = std::string("renameat2(RENAME_EXCHANGE): ") + std::strerror(errno);
      return false;
    }
    thread_ = std::thread([this] {
      while (!stop_.load(std::memory_order_relaxed)) {
        if (exchange()) swaps_.fetch_add(1, std::memory_order_relaxed);
      }
    });
    return true;
  }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  long swaps() const { return swaps_.load(); }

 private:
  bool exchange() { return ::renameat2(AT_FDCWD, a_.c_str(), AT_FDCWD, b_.c_str(), RENAME_EXCHANGE) == 0; }

  fs::path a_, b_;
  std::atomic<bool> stop_{false};
  std::atomic<long> swaps_{0};
  std::thread thread_;
};

// What the loads saw: `good` loads read what they may, `bad` ones did not.
struct Tally {
  int good = 0;
  int refused = 0;
  int bad = 0;
  std::string first_bad;

  std::string summary() const {
    return std::to_string(good) + " good, " + std::to_string(refused) + " refused, " + std::to_string(bad) + " bad" +
           (first_bad.empty() ? "" : " (" + first_bad + ")");
  }
};

// root/level/           the scene's folder
// root/level/sub        a folder, swapped without pause with level/door
// root/level/door       a symbolic link to ../outside
// root/outside/         files named as in sub/, holding the outside triangle
class SceneLoadRace : public sp::test::TestDirectory {
 protected:
  fs::path level() const { return dir_ / "level"; }
  fs::path outside() const { return dir_ / "outside"; }

  void SetUp() override {
    TestDirectory::SetUp();
    fs::create_directories(level() / "sub");
    fs::create_directories(outside());
    fs::create_directory_symlink("../outside", level() / "door");
  }

  // Runs `attempt` kLoads times while sub/ and door swap; it files each
  // outcome in the tally.
  template <class Attempt>
  Tally while_swapping(const std::string& what, Attempt attempt) {
    Swapper swapper(level() / "sub", level() / "door");
    std::string why_not;
    if (!swapper.start(why_not)) {
      ADD_FAILURE() << why_not;
      return {};
    }
    Tally tally;
    for (int i = 0; i < kLoads; ++i) attempt(tally);
    swapper.stop();
    RecordProperty(what, tally.summary() + " in " + std::to_string(swapper.swaps()) + " swaps");
    return tally;
  }

  // Loads `scene` kLoads times while sub/ and door swap; `judge` files each
  // result in the tally.
  template <class Judge>
  Tally load_while_swapping(const fs::path& scene, Judge judge) {
    return while_swapping("loads", [&](Tally& tally) { judge(sp::load_scene(scene), tally); });
  }
};

// The buffer's URI runs through the swapped folder; the scene file does not.
TEST_F(SceneLoadRace, ABufferIsReadFromInsideOrRefusedNeverFromOutside) {
  const GltfBuilder inside = triangle_at(kInsideX, "inside");
  fs::create_directories(level() / "sub" / kDeep);
  fs::create_directories(outside() / kDeep);
  write(level() / "sub" / kDeep / "tri.bin", inside.bin);
  write(outside() / kDeep / "tri.bin", triangle_at(kOutsideX, "outside").bin);
  const std::string uri = "sub/" + std::string(kDeep) + "tri.bin";
  const fs::path scene = write(level() / "scene.gltf", inside.gltf_with_buffer_uri(uri));
  ASSERT_TRUE(sp::load_scene(scene).ok());

  const Tally tally = load_while_swapping(scene, [&](const sp::Result<sp::Scene>& loaded, Tally& t) {
    if (loaded.ok()) {
      const bool is_inside = loaded->vertices.at(0).x == kInsideX;
      (is_inside ? t.good : t.bad) += 1;
      if (!is_inside) t.first_bad = "read the outside triangle";
      return;
    }
    // A refusal names the buffer and why: the link leads out, or the file
    // checked is not the file opened.
    const std::string& message = loaded.error().message;
    const bool named = message.find("buffer URI \"" + uri + "\": ") != std::string::npos;
    const bool why = message.find("through a symbolic link") != std::string::npos ||
                     message.find("changed while being read") != std::string::npos;
    EXPECT_TRUE(named && why) << message;
    t.refused += 1;
  });
  EXPECT_EQ(tally.bad, 0) << tally.summary();
  EXPECT_EQ(tally.good + tally.refused, kLoads) << tally.summary();
}

// The scene file's path itself runs through the swapped folder: whichever
// folder the load found the scene in, its buffer comes from that folder too
// (a scene read inside must not take its triangles from outside).
TEST_F(SceneLoadRace, TheSceneAndItsBufferComeFromOneFolder) {
  const GltfBuilder inside = triangle_at(kInsideX, "inside");
  const GltfBuilder other = triangle_at(kOutsideX, "outside");
  write(level() / "sub" / "scene.gltf", inside.gltf_with_buffer_uri("tri.bin"));
  write(level() / "sub" / "tri.bin", inside.bin);
  write(outside() / "scene.gltf", other.gltf_with_buffer_uri("tri.bin"));
  write(outside() / "tri.bin", other.bin);

  const Tally tally =
      load_while_swapping(level() / "sub" / "scene.gltf", [](const sp::Result<sp::Scene>& loaded, Tally& t) {
        if (!loaded.ok()) {
          t.refused += 1;
          return;
        }
        const bool layer_inside = loaded->layer_names.at(0) == "inside";
        const bool bytes_inside = loaded->vertices.at(0).x == kInsideX;
        if (layer_inside != bytes_inside) {
          t.bad += 1;
          if (t.first_bad.empty()) t.first_bad = "scene from " + loaded->layer_names.at(0) + ", buffer from the other";
        } else {
          t.good += 1;  // either folder, whole
        }
      });
  EXPECT_EQ(tally.bad, 0) << tally.summary();
  // The folder is opened once; both files are there whichever it is.
  EXPECT_EQ(tally.refused, 0) << tally.summary();
}

// A load takes one way to open beneath the folder (openat2 where the
// kernel has it); here both are raced directly, the walk included.
TEST_F(SceneLoadRace, BothWaysOfOpeningBeneathTheFolderNeverLeaveIt) {
  write(level() / "sub" / "tri.bin", std::string("inside"));
  write(outside() / "tri.bin", std::string("outside"));
  const sp::FileDescriptor root(::open(level().c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  ASSERT_TRUE(root.valid());
  using OpenBeneath = sp::OpenResult (*)(int, std::string_view, int);
  const std::pair<const char*, OpenBeneath> ways[] = {{"walk", &sp::open_beneath_by_walk},
                                                      {"openat2", &sp::open_beneath_by_openat2}};
  for (const auto& [way, open_beneath] : ways) {
    SCOPED_TRACE(way);
    const int probe = open_beneath(root.get(), "sub/tri.bin", O_RDONLY).error;
    if (probe == ENOSYS || probe == EPERM) continue;  // no openat2 here
    const Tally tally = while_swapping(way, [&, open_beneath = open_beneath](Tally& t) {
      const sp::OpenResult opened = open_beneath(root.get(), "sub/tri.bin", O_RDONLY);
      if (!opened.fd.valid()) {
        // EXDEV: the link leads out; EAGAIN: openat2 saw a rename race a "..".
        EXPECT_TRUE(opened.error == EXDEV || opened.error == EAGAIN) << std::strerror(opened.error);
        t.refused += 1;
        return;
      }
      char text[16] = {};
      const ::ssize_t got = ::read(opened.fd.get(), text, sizeof text - 1);
      const bool inside = got >= 0 && std::string(text) == "inside";
      (inside ? t.good : t.bad) += 1;
      if (!inside) t.first_bad = std::string("read \"") + text + "\"";
    });
    EXPECT_EQ(tally.bad, 0) << tally.summary();
  }
}

}  // namespace
