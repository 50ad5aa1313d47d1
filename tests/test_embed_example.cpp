// examples/embed end to end: the host's picture shows soundpaint's
// indicators where the library's own CPU simulator puts them (the GPU
// backend is bit-identical to it), under validation; the CPU backend draws
// too; bad command lines fail cleanly; and the integration stays small.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/glm_interop.h"
#include "sim/world_geometry.h"
#include "soundpaint/simulation.h"
#include "sp_draw_types.h"
#include "sp_shapes.h"
#include "support/render_checks.h"
#include "support/run_command.h"
#include "support/vulkan_environment.h"

namespace sp {
namespace {

using test::Rgb;
using test::run_command;
using test::ScratchDir;

const std::string kExample = SP_EMBED_EXAMPLE_PATH;
const std::string kLevel = std::string(SP_SCENES_DIR) + "/level.gltf";
constexpr std::uint32_t kWidth = 320;
constexpr std::uint32_t kHeight = 180;
constexpr int kFrames = 20;

// Validation only where a test asks for it with --validation.
test::CommandResult run_example(const std::string& args, const ScratchDir& dir) {
  return run_command("env -u SOUNDPAINT_VALIDATION " + kExample + " " + args, dir.path());
}

std::string picture_args(const std::filesystem::path& out, const std::string& backend, int frames) {
  return kLevel + " " + out.string() + " --backend " + backend + " --frames " + std::to_string(frames) + " --width " +
         std::to_string(kWidth) + " --height " + std::to_string(kHeight);
}

std::size_t count_files(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

int dominant_channel(glm::vec3 c) { return c.r >= c.g && c.r >= c.b ? 0 : (c.g >= c.b ? 1 : 2); }
int dominant_channel(Rgb c) { return dominant_channel(glm::vec3(c.r, c.g, c.b)); }

// The example's camera, re-derived from its documented formula.
struct Camera {
  glm::mat4 view_projection;
  glm::vec3 eye;
  float pixels_per_unit_at_depth_1;  // half the image height times the focal length
};

Camera scene_camera(const Scene& scene) {
  const glm::mat4 view = glm::inverse(sp::to_glm(scene.camera->world));
  glm::mat4 projection = glm::perspectiveRH_ZO(scene.camera->yfov, static_cast<float>(kWidth) / kHeight,
                                               scene.camera->znear, scene.camera->zfar);
  projection[1][1] *= -1.0f;
  return {projection * view, scene.camera->position(), 0.5f * kHeight * std::abs(projection[1][1])};
}

struct Projected {
  float x = 0, y = 0;  // pixel coordinates (x right, y down)
  float radius = 0;    // of the disc, in pixels, across its widest extent
  float narrow = 0;    // and along its foreshortened axis
  bool in_front = false;
};

Projected project(const Camera& camera, const Indicator& indicator) {
  const glm::vec4 clip = camera.view_projection * glm::vec4(sp::to_glm(indicator.position), 1.0f);
  Projected p;
  p.in_front = clip.w > 0.1f;
  if (!p.in_front) return p;
  p.x = (clip.x / clip.w * 0.5f + 0.5f) * kWidth;
  p.y = (clip.y / clip.w * 0.5f + 0.5f) * kHeight;
  const glm::vec3 to_eye = glm::normalize(camera.eye - sp::to_glm(indicator.position));
  const float facing = std::max(0.0f, glm::dot(glm::normalize(sp::to_glm(indicator.normal)), to_eye));
  p.radius = 0.5f * indicator.size * camera.pixels_per_unit_at_depth_1 / clip.w;
  p.narrow = p.radius * facing;
  return p;
}

// Marks the pixels an indicator's spot may touch: its shape, at least
// SP_SHAPE_MIN_PIXELS across and larger for direct sound, its tail behind
// it, the halo's margin, and 1.5 px of slack (shaders/indicator_vertex.glsl;
// the SP_SPOT_* sizes).
void mark_disc(std::vector<bool>& mask, const Projected& p) {
  const float radius = std::max(SP_SPOT_DIRECT_SIZE * p.radius, 0.5f * SP_SHAPE_MIN_PIXELS);
  const float reach = radius * (1.0f + SP_SPOT_MAX_TAIL + SP_SPOT_MARGIN_RADII) + 1.5f;
  const int x0 = std::max(0, static_cast<int>(p.x - reach));
  const int x1 = std::min(static_cast<int>(kWidth) - 1, static_cast<int>(p.x + reach));
  const int y0 = std::max(0, static_cast<int>(p.y - reach));
  const int y1 = std::min(static_cast<int>(kHeight) - 1, static_cast<int>(p.y + reach));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) mask[static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x)] = true;
}

float opacity_at(const Indicator& indicator, std::uint32_t current_step, const Config& config) {
  const double age = static_cast<double>(current_step - indicator.step) * config.dt;
  return indicator.intensity * std::max(0.0f, 1.0f - static_cast<float>(age) / config.indicator_lifetime);
}

bool in_image(float x, float y, float margin) {
  return x >= margin && y >= margin && x < kWidth - margin && y < kHeight - margin;
}

// Some pixel within 6 px of (x, y) has the indicator's colour: saturated,
// with the source colour's strongest channel strongest. (Spots are at
// least 16 px across; a neighbour's halo may cover this one's centre.)
bool shows_colour(const draw::RgbaImage& image, float x, float y, glm::vec3 colour) {
  for (int dy = -6; dy <= 6; ++dy)
    for (int dx = -6; dx <= 6; ++dx) {
      const int px = std::clamp(static_cast<int>(x) + dx, 0, static_cast<int>(kWidth) - 1);
      const int py = std::clamp(static_cast<int>(y) + dy, 0, static_cast<int>(kHeight) - 1);
      const Rgb c = test::pixel(image, static_cast<std::uint32_t>(px), static_cast<std::uint32_t>(py));
      if (test::is_saturated(c) && dominant_channel(c) == dominant_channel(colour)) return true;
    }
  return false;
}

TEST(EmbedExample, GpuBackendDrawsTheIndicatorsTheSimulationPredicts) {
  ScratchDir dir("embed-gpu");
  const auto out = dir / "frame.png";
  auto r = run_example(picture_args(out, "gpu", kFrames) + " --validation", dir);
  SKIP_WITHOUT_VULKAN(r);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  const auto picture = test::load_png(out);
  ASSERT_TRUE(picture.has_value());
  ASSERT_EQ(picture->width, kWidth);
  ASSERT_EQ(picture->height, kHeight);
  // The same host with no frame simulated: the bare level.
  const auto bare_out = dir / "bare.png";
  auto bare_run = run_example(picture_args(bare_out, "gpu", 0), dir);
  ASSERT_EQ(bare_run.status, 0) << bare_run.err;
  const auto bare = test::load_png(bare_out);
  ASSERT_TRUE(bare.has_value());
  EXPECT_EQ(test::count_pixels(*bare, test::is_saturated), 0u) << "the grey level alone has no indicator colour";

  // The indicators the example's simulation holds after its kFrames steps.
  const Scene scene = load_scene(kLevel).value();
  ASSERT_TRUE(scene.camera.has_value());
  const World world = make_world(scene, Config{}).value();
  auto simulator = create_cpu_simulator(world).value();
  for (int step = 0; step < kFrames; ++step) ASSERT_TRUE(simulator->step().ok());
  const std::vector<Indicator> live = simulator->live_indicators().value();
  const Camera camera = scene_camera(scene);
  const auto current_step = static_cast<std::uint32_t>(kFrames - 1);

  // Where indicators may colour the picture: every live one facing the eye,
  // occluded or not, with a pixel of slack around its disc.
  std::vector<bool> explained(std::size_t{kWidth} * kHeight, false);
  std::size_t checked = 0, shown = 0;
  for (const Indicator& indicator : live) {
    const Projected p = project(camera, indicator);
    if (!p.in_front || glm::dot(sp::to_glm(indicator.normal), camera.eye - sp::to_glm(indicator.position)) <= 0.0f)
      continue;
    mark_disc(explained, p);

    // Checked: clearly visible ones -- opaque, a few pixels wide, inside
    // the image and in plain sight of the eye.
    if (opacity_at(indicator, current_step, world.config) <= 0.5f || p.narrow < 1.5f || !in_image(p.x, p.y, 2.0f))
      continue;
    const float distance = glm::length(sp::to_glm(indicator.position) - camera.eye);
    const glm::vec3 direction = (sp::to_glm(indicator.position) - camera.eye) / distance;
    if (closest_hit(world.geometry->bvh, camera.eye, direction, 0.0f, distance - 0.05f).triangle != SP_INVALID)
      continue;
    ++checked;
    const glm::vec3 colour = world.source_colors[indicator.source_id];
    if (shows_colour(*picture, p.x, p.y, colour)) {
      ++shown;
      EXPECT_FALSE(shows_colour(*bare, p.x, p.y, colour));
    }
  }
  EXPECT_GE(checked, 10u) << "too few clearly visible indicators to check";
  EXPECT_GE(shown * 5, checked * 4) << shown << " of " << checked << " visible indicators show in their colour";

  // And nothing else: saturated pixels lie where some live indicator is.
  std::size_t saturated = 0, unexplained = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      if (!test::is_saturated(test::pixel(*picture, x, y))) continue;
      ++saturated;
      unexplained += explained[std::size_t{y} * kWidth + x] ? 0 : 1;
    }
  std::printf("%zu of %zu checked indicators shown; %zu of %zu coloured pixels near no live indicator\n", shown,
              checked, unexplained, saturated);
  EXPECT_GT(saturated, 100u);
  EXPECT_LE(unexplained * 100, saturated)
      << unexplained << " of " << saturated << " coloured pixels are near no live indicator";
}

TEST(EmbedExample, CpuBackendDrawsIndicators) {
  ScratchDir dir("embed-cpu");
  const auto out = dir / "frame.png";
  auto r = run_example(picture_args(out, "cpu", kFrames) + " --validation", dir);
  SKIP_WITHOUT_VULKAN(r);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  const auto picture = test::load_png(out);
  ASSERT_TRUE(picture.has_value());
  EXPECT_EQ(picture->width, kWidth);
  EXPECT_EQ(picture->height, kHeight);
  // Which steps the worker finished in time depends on timing: count only.
  EXPECT_GT(test::count_pixels(*picture, test::is_saturated), 500u);
}

// Status `status`, stderr naming `needle`, and no file written.
void expect_failure(const std::string& args, int status, const std::string& needle) {
  ScratchDir dir("embed-bad");
  std::string command = args;
  const std::string out = (dir / "out.png").string();
  for (auto at = command.find("OUT"); at != std::string::npos; at = command.find("OUT")) command.replace(at, 3, out);
  for (auto at = command.find("DIR"); at != std::string::npos; at = command.find("DIR"))
    command.replace(at, 3, dir.path().string());
  if (command.find("camera-less") != std::string::npos) {
    // One triangle, no camera node.
    std::ofstream(dir / "camera-less.gltf")
        << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
              "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
              "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                             "min": [0, 0, 0], "max": [1, 0, 1]}],
              "bufferViews": [{"buffer": 0, "byteLength": 36}],
              "buffers": [{"byteLength": 36,
                           "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/"}]})";
  }
  const std::size_t before = count_files(dir.path());
  auto r = run_example(command, dir);
  EXPECT_EQ(r.status, status) << args << ": " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": " << r.err;
  if (status == 2) {
    EXPECT_NE(r.err.find("usage: soundpaint_embed_example"), std::string::npos) << r.err;
  } else {
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;  // one line
  }
  EXPECT_FALSE(std::filesystem::exists(out)) << args;
  EXPECT_EQ(count_files(dir.path()), before + 2) << args;  // + stdout.txt, stderr.txt: no temporary either
}

TEST(EmbedExample, BadCommandLinesFailCleanly) {
  expect_failure("OUT --bogus", 2, "--bogus");
  expect_failure("OUT --frames many", 2, "--frames");
  expect_failure("OUT --width 0", 2, "--width");
  expect_failure("OUT --backend metal", 2, "--backend");
  expect_failure("--frames 1", 2, "OUT.png");
  expect_failure("/nonexistent/level.gltf OUT --frames 1", 1, "/nonexistent/level.gltf");
  expect_failure("DIR/camera-less.gltf OUT --frames 1", 1, "no camera");
  expect_failure(kLevel + " DIR/missing-dir/out.png --frames 1 --width 16 --height 16", 1, "missing-dir/out.png");
}

// Non-blank lines between "// >>> soundpaint" and "// <<< soundpaint" that
// are not comments alone.
TEST(EmbedExample, TheIntegrationTakesFewerThanThirtyLines) {
  std::ifstream source(SP_EMBED_EXAMPLE_SOURCE);
  ASSERT_TRUE(source.good()) << SP_EMBED_EXAMPLE_SOURCE;
  std::size_t lines = 0, blocks = 0;
  bool inside = false;
  for (std::string line; std::getline(source, line);) {
    const auto first = line.find_first_not_of(" \t");
    const std::string text = first == std::string::npos ? "" : line.substr(first);
    if (text.starts_with("// >>> soundpaint")) {
      EXPECT_FALSE(inside) << "nested marker";
      inside = true;
      ++blocks;
    } else if (text.starts_with("// <<< soundpaint")) {
      EXPECT_TRUE(inside) << "closing marker without an opening one";
      inside = false;
    } else if (inside && !text.empty() && !text.starts_with("//")) {
      ++lines;
    }
  }
  EXPECT_FALSE(inside) << "unclosed marker";
  EXPECT_GT(blocks, 0u);
  EXPECT_GT(lines, 0u);
  EXPECT_LT(lines, 30u) << "soundpaint integration lines in " << SP_EMBED_EXAMPLE_SOURCE;
  std::printf("integration: %zu lines in %zu blocks\n", lines, blocks);
}

}  // namespace
}  // namespace sp
