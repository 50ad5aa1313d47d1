// What a scene may make soundpaint read (README "Security"): its buffers,
// from regular files inside its own folder tree, and nothing else. Every
// refusal is checked twice: by the load's result, and by an inotify watch
// on a canary file outside the folder that must never be opened. The
// canary is a valid buffer, so a URI that slipped through would load.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/beneath_open.h"
#include "soundpaint/scene.h"
#include "support/canary_watch.h"
#include "support/gltf_builder.h"
#include "support/test_directory.h"

namespace {

namespace fs = std::filesystem;
using sp::test::CanaryWatch;
using sp::test::GltfBuilder;

// The unit triangle, its buffer to be written wherever a test needs it.
GltfBuilder triangle() {
  GltfBuilder b;
  b.root(b.node({{"name", "Tri"}, {"mesh", b.unit_triangle_mesh()}}));
  return b;
}

// root/level/    the scene's folder (scene files, sub/inside.bin)
// root/outside/  canary.bin, a valid buffer that must never be opened
class Confinement : public sp::test::TestDirectory {
 protected:
  void SetUp() override {
    TestDirectory::SetUp();
    fs::create_directories(level() / "sub");
    fs::create_directories(outside());
    write(canary(), bin_);
    write(level() / "sub" / "inside.bin", bin_);
    watch_ = std::make_unique<CanaryWatch>(canary());
  }
  void TearDown() override {
    watch_.reset();
    TestDirectory::TearDown();
  }

  fs::path level() const { return dir_ / "level"; }
  fs::path outside() const { return dir_ / "outside"; }
  fs::path canary() const { return outside() / "canary.bin"; }

  // A scene in the level folder whose buffer is `uri`.
  fs::path scene_with_uri(const std::string& uri, const std::string& name = "scene.gltf") const {
    const fs::path path = level() / name;
    write(path, triangle().gltf_with_buffer_uri(uri));
    return path;
  }

  sp::Result<sp::Scene> load(const fs::path& path, bool allow_external = false) const {
    sp::SceneLoadOptions options;
    options.allow_external_uris = allow_external;
    return sp::load_scene(path, options);
  }

  // The load fails with a one-line InvalidScene message that names the
  // file, the URI as written and `reason`; the canary was not opened.
  void expect_refused(const fs::path& path, const std::string& uri, const std::string& reason,
                      bool allow_external = false) {
    SCOPED_TRACE(uri);
    const sp::Result<sp::Scene> scene = load(path, allow_external);
    ASSERT_FALSE(scene.ok()) << "loaded " << uri;
    const std::string& message = scene.error().message;
    EXPECT_EQ(scene.error().code, sp::ErrorCode::InvalidScene);
    // Messages cut a URI to 80 characters.
    const std::string shown = uri.size() > 80 ? uri.substr(0, 77) + "..." : uri;
    EXPECT_EQ(message.rfind(path.string() + ": buffer URI \"" + shown + "\": ", 0), 0u) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(watch_->take_events(), 0) << "the canary was opened for " << uri;
  }

  std::vector<std::uint8_t> bin_ = triangle().bin;
  std::unique_ptr<CanaryWatch> watch_;
};

TEST_F(Confinement, ReadsBuffersInsideTheSceneFolderTree) {
  for (const std::string uri :
       {"sub/inside.bin", "./sub/inside.bin", "sub/../sub/inside.bin", "sub%2Finside.bin", "sub//inside.bin"}) {
    SCOPED_TRACE(uri);
    const sp::Result<sp::Scene> scene = load(scene_with_uri(uri));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->triangle_count(), 1u);
  }
  // A symbolic link that stays inside the folder is followed, to a file or
  // to a folder, and ".." in its target may climb back inside.
  fs::create_symlink("sub/inside.bin", level() / "alias.bin");
  fs::create_directory_symlink("sub", level() / "same");
  fs::create_symlink("../sub/inside.bin", level() / "sub" / "back.bin");
  for (const std::string uri : {"alias.bin", "same/inside.bin", "sub/back.bin", "same/back.bin"}) {
    SCOPED_TRACE(uri);
    const sp::Result<sp::Scene> scene = load(scene_with_uri(uri));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
  }
  EXPECT_EQ(watch_->take_events(), 0);
}

// Binary glTF: a JSON chunk only, its buffer in an external file.
std::vector<std::uint8_t> glb_with_external_buffer(const std::string& uri) {
  std::string text = triangle().gltf_with_buffer_uri(uri);
  while (text.size() % 4 != 0) text += ' ';
  std::vector<std::uint8_t> out;
  auto u32 = [&out](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  u32(0x46546C67u);  // "glTF"
  u32(2);
  u32(static_cast<std::uint32_t>(20 + text.size()));
  u32(static_cast<std::uint32_t>(text.size()));
  u32(0x4E4F534Au);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  return out;
}

TEST_F(Confinement, BinaryGltfObeysTheSameRules) {
  write(level() / "inside.glb", glb_with_external_buffer("sub/inside.bin"));
  const sp::Result<sp::Scene> scene = load(level() / "inside.glb");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  write(level() / "escape.glb", glb_with_external_buffer("%2e%2e/outside/canary.bin"));
  expect_refused(level() / "escape.glb", "%2e%2e/outside/canary.bin", "leads out of the scene's folder");
}

TEST_F(Confinement, RefusesParentEscapesPlainOrPercentEncoded) {
  const std::vector<std::string> uris = {
      "../outside/canary.bin",         "%2e%2e/outside/canary.bin",
      "%2E%2E%2Foutside%2Fcanary.bin", "sub/../../outside/canary.bin",
      "./../outside/canary.bin",       "../../../../../../../../.." + outside().string() + "/canary.bin"};
  for (const std::string& uri : uris) {
    expect_refused(scene_with_uri(uri), uri, "leads out of the scene's folder with \"..\"");
  }
}

TEST_F(Confinement, RefusesAbsolutePathsAndUriSchemes) {
  expect_refused(scene_with_uri(canary().string()), canary().string(), "is an absolute path");
  expect_refused(scene_with_uri("/etc/passwd"), "/etc/passwd", "is an absolute path");
  expect_refused(scene_with_uri("%2Fetc%2Fpasswd"), "%2Fetc%2Fpasswd", "is an absolute path");
  const std::string file_uri = "file://" + canary().string();
  expect_refused(scene_with_uri(file_uri), file_uri, "URI scheme");
  expect_refused(scene_with_uri("C:/canary.bin"), "C:/canary.bin", "URI scheme");
}

TEST_F(Confinement, RefusesSymbolicLinksLeadingOut) {
  fs::create_symlink(canary(), level() / "link.bin");
  expect_refused(scene_with_uri("link.bin"), "link.bin", "through a symbolic link");
  fs::create_directory_symlink(outside(), level() / "sub" / "door");
  expect_refused(scene_with_uri("sub/door/canary.bin"), "sub/door/canary.bin", "through a symbolic link");
}

// Only relative links are followed: a link's absolute target is refused
// even when it names a file inside (the folder cannot be checked from an
// absolute path without looking it up a second time).
TEST_F(Confinement, RefusesAbsoluteLinkTargetsAndLinkLoops) {
  fs::create_symlink(level() / "sub" / "inside.bin", level() / "absolute.bin");
  expect_refused(scene_with_uri("absolute.bin"), "absolute.bin", "through a symbolic link");
  fs::create_symlink("loop.bin", level() / "loop.bin");
  expect_refused(scene_with_uri("loop.bin"), "loop.bin", "cannot open: Too many levels of symbolic links");
}

TEST_F(Confinement, RefusesWhatIsNotARegularFile) {
  expect_refused(scene_with_uri("sub"), "sub", "is a directory");
  ASSERT_EQ(::mkfifo((level() / "pipe.bin").c_str(), 0600), 0);
  expect_refused(scene_with_uri("pipe.bin"), "pipe.bin", "not a regular file");
  expect_refused(scene_with_uri("missing.bin"), "missing.bin", "file not found");
  expect_refused(scene_with_uri("a%00.bin"), "a%00.bin", "NUL");
}

// The folder rule goes, the rest stays: /proc, /sys and devices are never
// read. The canary then is opened, which shows the watch works.
TEST_F(Confinement, AllowExternalUrisLiftsOnlyTheFolderRule) {
  const sp::Result<sp::Scene> scene = load(scene_with_uri("../outside/canary.bin"), true);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->triangle_count(), 1u);
  EXPECT_GT(watch_->take_events(), 0);
  EXPECT_TRUE(load(scene_with_uri(canary().string()), true).ok());
  EXPECT_GT(watch_->take_events(), 0);
  expect_refused(scene_with_uri("/proc/self/environ"), "/proc/self/environ", "under /proc", true);
  expect_refused(scene_with_uri("/sys/devices/system/cpu/online"), "/sys/devices/system/cpu/online", "under /sys",
                 true);
  expect_refused(scene_with_uri("/dev/zero"), "/dev/zero", "not a regular file", true);
  expect_refused(scene_with_uri("file:///etc/passwd"), "file:///etc/passwd", "URI scheme", true);
}

// tinygltf's own callbacks also look in the current directory; ours never do.
TEST_F(Confinement, NeverLooksInTheCurrentDirectory) {
  const fs::path scene = scene_with_uri("canary.bin");
  const fs::path previous = fs::current_path();
  fs::current_path(outside());
  const sp::Result<sp::Scene> loaded = load(scene);
  fs::current_path(previous);
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.error().message.find("\"canary.bin\": file not found"), std::string::npos) << loaded.error().message;
  EXPECT_EQ(watch_->take_events(), 0);
}

// Only buffers matter: an image is never opened, wherever it points, and a
// scene whose image is missing or forbidden still loads.
TEST_F(Confinement, NeverReadsImages) {
  GltfBuilder b = triangle();
  b.doc["images"] = {{{"uri", canary().string()}}, {{"uri", "../outside/canary.bin"}}, {{"uri", "sub/inside.bin"}}};
  b.doc["textures"] = {{{"source", 0}}};
  write(level() / "textured.gltf", b.gltf_with_buffer_uri("sub/inside.bin"));
  for (const bool allow_external : {false, true}) {
    SCOPED_TRACE(allow_external);
    const sp::Result<sp::Scene> scene = load(level() / "textured.gltf", allow_external);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(watch_->take_events(), 0);
  }
}

// Buffers and the scene file share the rules of a regular file: a device
// named as the scene is refused before it is opened.
TEST_F(Confinement, RefusesDevicesAndFifosAsTheSceneItself) {
  for (const fs::path& device : {fs::path("/dev/zero"), fs::path("/dev/null")}) {
    const sp::Result<sp::Scene> scene = sp::load_scene(device);
    ASSERT_FALSE(scene.ok());
    EXPECT_EQ(scene.error().message, device.string() + ": is not a regular file (a device, FIFO or socket)");
  }
  ASSERT_EQ(::mkfifo((level() / "fifo.gltf").c_str(), 0600), 0);
  const sp::Result<sp::Scene> fifo = sp::load_scene(level() / "fifo.gltf");  // would block if opened
  ASSERT_FALSE(fifo.ok());
  EXPECT_NE(fifo.error().message.find("not a regular file"), std::string::npos);
}

// sp::open_beneath's two ways, each on a fixed tree (no race; the race is
// tests/test_scene_load_race.cpp):
//   root/sub/f.bin                 "inside"
//   root/alias -> sub/f.bin        a link inside, staying inside
//   root/sub/up -> ../sub/f.bin    ".." in a link, staying inside
//   root/folder -> sub             a link to a folder inside
//   root/out -> ../outside/f.bin   a link leading out
//   root/door -> ../outside        a link to a folder outside
//   root/absolute -> <root>/sub/f.bin, an absolute target, though inside
//   root/loop -> loop; root/ping -> pong -> ping
//   outside/f.bin                  "outside"
using OpenBeneathWay = sp::OpenResult (*)(int, std::string_view, int);

class OpenBeneath : public sp::test::TestDirectory, public ::testing::WithParamInterface<OpenBeneathWay> {
 protected:
  void SetUp() override {
    TestDirectory::SetUp();
    fs::create_directories(root() / "sub");
    fs::create_directories(root() / "a");
    fs::create_directories(dir_ / "outside");
    write(root() / "sub" / "f.bin", std::string("inside"));
    write(dir_ / "outside" / "f.bin", std::string("outside"));
    fs::create_symlink("sub/f.bin", root() / "alias");
    fs::create_symlink("../sub/f.bin", root() / "sub" / "up");
    fs::create_directory_symlink("sub", root() / "folder");
    fs::create_symlink("../outside/f.bin", root() / "out");
    fs::create_directory_symlink("../outside", root() / "door");
    fs::create_symlink(root() / "sub" / "f.bin", root() / "absolute");
    fs::create_symlink("loop", root() / "loop");
    fs::create_symlink("pong", root() / "ping");
    fs::create_symlink("ping", root() / "pong");
    root_ = sp::FileDescriptor(::open(root().c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
    ASSERT_TRUE(root_.valid());
    if (open("sub/f.bin").error == ENOSYS) GTEST_SKIP() << "no openat2 in this kernel or build";
  }

  fs::path root() const { return dir_ / "root"; }
  sp::OpenResult open(const std::string& path, int flags = O_RDONLY) const {
    return GetParam()(root_.get(), path, flags);
  }
  // The file's text, or the error's name.
  std::string read(const std::string& path) const {
    const sp::OpenResult opened = open(path);
    if (!opened.fd.valid()) return strerrorname_np(opened.error);
    char text[16] = {};
    return ::read(opened.fd.get(), text, sizeof text - 1) >= 0 ? text : "read error";
  }

  sp::FileDescriptor root_;
};

TEST_P(OpenBeneath, FollowsLinksThatStayInside) {
  for (const char* path : {"sub/f.bin", "alias", "sub/up", "folder/f.bin", "folder/up", "folder/../alias",
                           "sub/../sub/./f.bin", "a/../sub//f.bin"}) {
    EXPECT_EQ(read(path), "inside") << path;
  }
  // Folders too, as O_PATH descriptors.
  for (const char* path : {"folder", "sub/", "folder/..", "."}) {
    const sp::OpenResult opened = open(path, O_PATH | O_DIRECTORY);
    EXPECT_TRUE(opened.fd.valid()) << path << ": " << std::strerror(opened.error);
  }
}

TEST_P(OpenBeneath, RefusesEveryWayOut) {
  for (const std::string& path : {std::string("out"), std::string("door/f.bin"), std::string("a/../../outside/f.bin"),
                                  std::string("../outside/f.bin"), std::string("folder/../../outside/f.bin"),
                                  std::string("absolute"), (dir_ / "outside" / "f.bin").string(), std::string("..")}) {
    EXPECT_EQ(read(path), "EXDEV") << path;
  }
}

TEST_P(OpenBeneath, LinkLoopsFailCleanly) {
  EXPECT_EQ(read("loop"), "ELOOP");
  EXPECT_EQ(read("ping"), "ELOOP");
  EXPECT_EQ(read("ping/f.bin"), "ELOOP");
}

// Linux's own limit: 40 links in one resolution, the 41st is a loop.
TEST_P(OpenBeneath, FollowsAsManyLinksAsLinuxDoes) {
  fs::create_symlink("sub/f.bin", root() / "chain0");
  for (int i = 1; i <= sp::kMaxSymbolicLinks; ++i) {
    fs::create_symlink("chain" + std::to_string(i - 1), root() / ("chain" + std::to_string(i)));
  }
  EXPECT_EQ(read("chain" + std::to_string(sp::kMaxSymbolicLinks - 1)), "inside");
  EXPECT_EQ(read("chain" + std::to_string(sp::kMaxSymbolicLinks)), "ELOOP");
}

TEST_P(OpenBeneath, ReportsMissingFilesAsOpenatDoes) {
  EXPECT_EQ(read("missing"), "ENOENT");
  EXPECT_EQ(read(""), "ENOENT");
  EXPECT_EQ(read("sub/f.bin/x"), "ENOTDIR");
  EXPECT_EQ(read("sub/f.bin/"), "ENOTDIR");
  EXPECT_EQ(read("alias/"), "ENOTDIR");
}

INSTANTIATE_TEST_SUITE_P(Ways, OpenBeneath,
                         ::testing::Values(&sp::open_beneath_by_walk, &sp::open_beneath_by_openat2, &sp::open_beneath),
                         [](const ::testing::TestParamInfo<OpenBeneathWay>& way) {
                           if (way.param == &sp::open_beneath_by_walk) return std::string("Walk");
                           if (way.param == &sp::open_beneath_by_openat2) return std::string("Openat2");
                           return std::string("Either");
                         });

}  // namespace
