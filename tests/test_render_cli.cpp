// `soundpaint render` end to end: image size, --frames, and bad inputs
// failing with one line on stderr and no file left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>

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

std::size_t count_files(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

std::uint32_t big_endian_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < 4; ++k) value = (value << 8) | static_cast<std::uint8_t>(bytes[at + k]);
  return value;
}

// Width and height from a PNG's IHDR chunk, which the format requires first:
// 8-byte signature, chunk length (4), "IHDR" (4), width (4), height (4).
std::pair<std::uint32_t, std::uint32_t> png_size(const std::filesystem::path& path) {
  const std::string bytes = test::read_text(path);
  EXPECT_GE(bytes.size(), 24u);
  if (bytes.size() < 24) return {0, 0};
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  return {big_endian_u32(bytes, 16), big_endian_u32(bytes, 20)};
}

TEST(RenderCli, WritesAPngOfTheRequestedSize) {
  ScratchDir dir("render-size");
  const auto out = dir / "picture.png";
  // Validation on: its messages would land on stderr, which must stay empty.
  auto r = run_command("SOUNDPAINT_VALIDATION=1 " + kCli + " render " + kScene +
                           " --backend gpu --steps 3 --width 64 --height 40 --out " + out.string(),
                       dir.path());
  SKIP_WITHOUT_VULKAN(r);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(png_size(out), std::make_pair(64u, 40u));
  const auto decoded = test::load_png(out);
  ASSERT_TRUE(decoded.has_value());
  EXPECT_GT(test::count_pixels(*decoded, test::is_saturated), 0u) << "no indicator or marker in the picture";
  EXPECT_EQ(count_files(dir.path()), 3u);  // picture, stdout, stderr: no temporary left
}

TEST(RenderCli, FramesWritesOnePictureForEachFurtherStep) {
  ScratchDir dir("render-frames");
  auto r =
      run_command(kCli + " render " + kScene + " --backend cpu --steps 1 --frames 3 --width 32 --height 24 --out " +
                      (dir / "f%03d.png").string(),
                  dir.path());
  SKIP_WITHOUT_VULKAN(r);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name : {"f000.png", "f001.png", "f002.png"})
    EXPECT_EQ(png_size(dir / name), std::make_pair(32u, 24u)) << name;
  EXPECT_EQ(count_files(dir.path()), 5u);  // exactly 3 frames + stdout + stderr
}

TEST(RenderCli, Help) {
  ScratchDir dir("render-help");
  auto r = run_command(kCli + " render --help", dir.path());
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("usage: soundpaint render"), std::string::npos) << r.out;
  auto top = run_command(kCli + " --help", dir.path());
  EXPECT_NE(top.out.find("render SCENE"), std::string::npos) << top.out;
}

// Non-zero exit, one stderr line containing `needle`, nothing written.
void expect_clean_failure(const std::string& args, const std::string& needle) {
  ScratchDir dir("render-bad");
  const std::string out = (dir / "out.png").string();
  std::string command = kCli + " render " + args;
  if (command.find("OUT") != std::string::npos) command.replace(command.find("OUT"), 3, out);
  auto r = run_command(command, dir.path());
  EXPECT_NE(r.status, 0) << args;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": " << r.err;
  EXPECT_EQ(count_files(dir.path()), 2u) << args;  // stdout.txt and stderr.txt only
}

TEST(RenderCli, BadInputsFailCleanly) {
  expect_clean_failure(kScene + " --steps 1 --out /nonexistent-dir/picture.png", "/nonexistent-dir/picture.png");
  expect_clean_failure(kScene + " --steps 1 --width 0 --out OUT", "--width");
  expect_clean_failure(kScene + " --steps 1 --width 100000 --out OUT", "--width");
  expect_clean_failure(kScene + " --steps 1 --height 0 --out OUT", "--height");
  expect_clean_failure("/nonexistent/level.gltf --steps 1 --out OUT", "/nonexistent/level.gltf");
  expect_clean_failure(kScene + " --steps 1 --frames 2 --out OUT", "%d");                 // no conversion
  expect_clean_failure(kScene + " --steps 1 --frames 2 --out OUT%d%d", "more than one");  // two
  expect_clean_failure(kScene + " --steps 1 --frames 2 --out OUT%s", "--out");            // not an integer
  expect_clean_failure(kScene + " --steps 1 --frames 0 --out OUT%d", "--frames");
  expect_clean_failure(kScene + " --steps 1 --camera-pos 1,2 --out OUT", "--camera-pos");
  expect_clean_failure(kScene + " --steps 1 --fov 180 --out OUT", "--fov");
  expect_clean_failure(kScene + " --steps 1", "--out");
}

TEST(RenderCli, WithoutAVulkanDeviceFailsCleanlyEvenForTheCpuBackend) {
  ScratchDir dir("render-novulkan");
  // Points the Vulkan loader at a driver manifest that does not exist.
  auto r = run_command("VK_DRIVER_FILES=/nonexistent/icd.json VK_ICD_FILENAMES=/nonexistent/icd.json " + kCli +
                           " render " + kScene + " --backend cpu --steps 1 --out " + (dir / "x.png").string(),
                       dir.path());
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("render needs a Vulkan device"), std::string::npos) << r.err;
  EXPECT_EQ(count_files(dir.path()), 2u);  // stdout, stderr; no x.png, no temporary
}

TEST(RenderCli, ABadSceneFileFailsCleanly) {
  ScratchDir dir("render-bad-scene");
  std::ofstream(dir / "broken.gltf") << "{ \"asset\": ";
  const std::size_t before = count_files(dir.path());  // broken.gltf
  auto r = run_command(kCli + " render " + (dir / "broken.gltf").string() + " --out " + (dir / "x.png").string(),
                       dir.path());
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("broken.gltf"), std::string::npos) << r.err;
  EXPECT_EQ(count_files(dir.path()), before + 2);  // + stdout, stderr; no x.png
}

}  // namespace
}  // namespace sp
