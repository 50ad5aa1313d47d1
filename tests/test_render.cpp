// The graphics pass, checked by what its pictures must show: indicator
// colours where the simulation put indicators, none without rays, light on
// the listener's side of a wooden wall only when rays can cross it, CPU and
// GPU pictures alike, and a small golden image. Runs on the shared
// validation-enabled context; any validation message fails the test.
#include <algorithm>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "render/renderer.h"
#include "sim/world_geometry.h"
#include "sp_types.h"
#include "support/gpu_environment.h"
#include "support/render_checks.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

using test::Rgb;

const std::string kScenes = SP_SCENES_DIR;

struct Picture {
  draw::RgbaImage image;
  draw::ViewCamera camera;
  std::vector<Indicator> live;  // what the simulation holds when the picture is taken
};

class Render : public test::GpuTest {
 protected:
  Picture render(const Scene& scene, const Config& config, Backend backend, int steps,
                 const draw::RenderSettings& settings, const draw::CameraOverrides& overrides = {}) {
    auto sim = make_simulator(make_world(scene, config).value(), backend);
    draw::Renderer renderer(*test::GpuEnvironment::context(), sim->world(), settings);
    for (int n = 0; n < steps; ++n) EXPECT_TRUE(sim->step().ok());
    Picture picture;
    picture.camera = draw::make_view_camera(scene.camera, sim->world(), overrides, settings.width, settings.height);
    picture.image = renderer.render(picture.camera, *sim);
    picture.live = sim->live_indicators().value();
    return picture;
  }

  static draw::RenderSettings size(std::uint32_t width, std::uint32_t height, bool markers) {
    draw::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.markers = markers;
    return settings;
  }
};

// A concrete floor with low walls and no ceiling, seen from above: a red
// source at x = -4 and a blue one at x = +4. Air attenuation ends every ray
// within ~3 m, so each source's indicators stay on its own half.
Scene open_yard() {
  Scene scene;
  test::add_box(scene, {-8, -0.3f, -4}, {8, 0, 4}, "concrete");
  test::add_box(scene, {-8.3f, -0.3f, -4}, {-8, 1, 4}, "concrete");
  test::add_box(scene, {8, -0.3f, -4}, {8.3f, 1, 4}, "concrete");
  SourceDesc red = test::source_at({-4, 1, 0});
  red.color = {1.0f, 0.05f, 0.05f};
  SourceDesc blue = test::source_at({4, 1, 0});
  blue.color = {0.05f, 0.1f, 1.0f};
  scene.sources = {red, blue};
  return scene;
}

Config yard_config(std::uint32_t ray_budget) {
  Config config;
  config.listener_position = glm::vec3(0, 1, 0);  // equally far from both sources: the same intensity
  config.ray_budget = ray_budget;
  config.air_attenuation = 0.3f;
  config.max_bounces = 1;
  config.indicator_size = 0.6f;
  config.max_indicators = 20000;  // dense: every spot's colour is checked
  config.seed = 5;
  return config;
}

draw::CameraOverrides above_the_yard() {
  draw::CameraOverrides overrides;
  overrides.position = glm::vec3(0, 9, 4);
  overrides.look_at = glm::vec3(0, 0, 0);
  overrides.yfov_degrees = 70.0f;
  return overrides;
}

class RenderBothBackends : public Render, public ::testing::WithParamInterface<Backend> {};

TEST_P(RenderBothBackends, IndicatorsShowTheirSourcesColourWhereTheyLie) {
  const Picture p = render(open_yard(), yard_config(400), GetParam(), 6, size(320, 240, false), above_the_yard());
  std::size_t checked[2] = {0, 0}, matching[2] = {0, 0};
  for (const Indicator& ind : p.live) {
    if (ind.normal.y < 0.9f || ind.size < 0.3f) continue;  // floor spots big enough to cover their centre pixel
    auto pixel = draw::project_to_pixel(p.camera, ind.position, p.image.width, p.image.height);
    if (!pixel || pixel->x < 0 || pixel->y < 0 || pixel->x >= 320 || pixel->y >= 240) continue;
    // Spots overlap, and a neighbour's halo may cover this one's centre:
    // the source's colour must show within 6 px of it (spots are at least
    // 16 px across), the other's nowhere within 3 px.
    const std::uint32_t s = ind.source_id;
    ASSERT_LT(s, 2u);
    checked[s] += 1;
    bool own = false, other = false;
    for (int dy = -6; dy <= 6; ++dy) {
      for (int dx = -6; dx <= 6; ++dx) {
        const int x = std::clamp(static_cast<int>(pixel->x) + dx, 0, 319);
        const int y = std::clamp(static_cast<int>(pixel->y) + dy, 0, 239);
        const Rgb c = test::pixel(p.image, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
        const bool reddish = c.r > c.g + 40 && c.r > c.b + 40;
        const bool bluish = c.b > c.r + 40 && c.b > c.g + 40;
        own = own || (s == 0 ? reddish : bluish);
        other = other || (std::abs(dx) <= 3 && std::abs(dy) <= 3 && (s == 0 ? bluish : reddish));
      }
    }
    if (own && !other) matching[s] += 1;
  }
  for (int s = 0; s < 2; ++s) {
    ASSERT_GT(checked[s], 20u) << "source " << s << ": too few indicators in view to judge";
    EXPECT_GE(matching[s], checked[s] * 9 / 10)
        << "source " << s << ": " << matching[s] << " of " << checked[s] << " indicator centres show its colour";
  }
}

TEST_P(RenderBothBackends, WithoutRaysNoPixelHasAnIndicatorColour) {
  const Picture lit = render(open_yard(), yard_config(400), GetParam(), 6, size(160, 120, false), above_the_yard());
  const Picture dark = render(open_yard(), yard_config(0), GetParam(), 6, size(160, 120, false), above_the_yard());
  EXPECT_TRUE(dark.live.empty());
  EXPECT_EQ(test::count_pixels(dark.image, test::is_saturated), 0u);
  EXPECT_GT(test::count_pixels(lit.image, test::is_saturated), 200u);  // the check can see indicators
}

// One burst of the red source, at step 0, in steps of 1/16 s (exact in
// binary), of 0.3 s spots: the display shows them for its minimum lifetime,
// 1/3 s (SP_MIN_DISPLAY_LIFETIME). After 6 steps they are 5/16 = 0.3125 s
// old, inside it: drawn, and live; after 7, 0.375 s: neither. At full
// opacity while live, so that a faded spot cannot hide the answer.
TEST_P(RenderBothBackends, ASpotIsDrawnExactlyWhileItIsLive) {
  Scene scene = open_yard();
  scene.sources.resize(1);
  scene.sources[0].duration = 0.01;
  scene.sources[0].interval = 1000.0;
  Config config = yard_config(400);
  config.dt = 1.0 / 16.0;
  config.indicator_lifetime = 0.3f;
  config.display.min_opacity = 1.0f;
  const Picture inside = render(scene, config, GetParam(), 6, size(160, 120, false), above_the_yard());
  EXPECT_FALSE(inside.live.empty()) << "drawn at 0.3125 s, so live";
  for (const Indicator& ind : inside.live) EXPECT_EQ(ind.step, 0u);
  EXPECT_GT(test::count_pixels(inside.image, test::is_saturated), 50u) << "live at 0.3125 s, so drawn";
  const Picture after = render(scene, config, GetParam(), 7, size(160, 120, false), above_the_yard());
  EXPECT_TRUE(after.live.empty()) << "past the display's lifetime at 0.375 s";
  EXPECT_EQ(test::count_pixels(after.image, test::is_saturated), 0u) << "past the display's lifetime at 0.375 s";
}

INSTANTIATE_TEST_SUITE_P(Backends, RenderBothBackends, ::testing::Values(Backend::Cpu, Backend::Gpu),
                         [](const auto& param_info) {
                           return std::string(param_info.param == Backend::Cpu ? "Cpu" : "Gpu");
                         });

// two_rooms.gltf: the listener in room A faces the 0.1 m wooden wall; the
// stereo plays in room B behind it. Rays that cross the wall leave exit
// indicators on room A's side -- unless W_max is thinner than the wall.
// The stereo's light blue over brown wood or grey concrete (the scene's
// brick and wood are all reddish).
bool is_stereo_blue(Rgb c) { return c.b > c.r + 25 && c.b > c.g; }

std::size_t stereo_pixels_on_the_wall(const Picture& p) {
  // The divider's room-A face is the plane x = -0.05; its solid parts are
  // z outside the door [-0.5, 0.5]. Above 0.8 m nothing in room A stands in
  // front of it, and away from its edges no other surface shows.
  const glm::mat4 inverse = glm::inverse(p.camera.view_projection());
  std::size_t count = 0;
  std::size_t region = 0;
  for (std::uint32_t y = 0; y < p.image.height; ++y) {
    for (std::uint32_t x = 0; x < p.image.width; ++x) {
      auto hit = test::pixel_ray_hits_plane_x(inverse, x, y, p.image.width, p.image.height, -0.05f);
      if (!hit || hit->y < 0.8f || hit->y > 2.9f) continue;
      const float z = std::abs(hit->z);
      if (z < 0.6f || z > 2.4f) continue;
      region += 1;
      if (is_stereo_blue(test::pixel(p.image, x, y))) count += 1;
    }
  }
  EXPECT_GT(region, p.image.width * p.image.height / 5) << "the wall should fill much of the view";
  return count;
}

TEST_F(Render, SourceBehindAWoodenWallLightsItsFarSide) {
  const Scene scene = load_scene(kScenes + "/two_rooms.gltf").value();
  Config config;
  config.seed = 3;
  const Picture through = render(scene, config, Backend::Gpu, 30, size(240, 135, true));
  config.max_wall_thickness = 0.05f;  // thinner than the wall: every penetration dies inside it
  const Picture blocked = render(scene, config, Backend::Gpu, 30, size(240, 135, true));

  // Exits on the wall's room-A face, away from the door (rays can cut the
  // corners of the door jambs in less than W_max).
  auto exits_on_room_a_side = [](const Picture& p) {
    std::size_t n = 0;
    for (const Indicator& ind : p.live)
      n += ind.kind == SP_INDICATOR_EXIT && std::abs(ind.position.x + 0.05f) < 1e-3f && ind.normal.x < 0.0f &&
           std::abs(ind.position.z) > 0.6f;
    return n;
  };
  EXPECT_GT(exits_on_room_a_side(through), 100u) << "the scenario no longer sends rays through the wall";
  EXPECT_EQ(exits_on_room_a_side(blocked), 0u);

  const std::size_t lit = stereo_pixels_on_the_wall(through);
  const std::size_t dim = stereo_pixels_on_the_wall(blocked);
  std::printf("[          ] stereo-blue wall pixels: %zu through, %zu blocked\n", lit, dim);
  EXPECT_GT(lit, 2000u);
  EXPECT_GT(lit, 4 * dim) << "lit " << lit << " vs blocked " << dim;
}

TEST_F(Render, CpuAndGpuBackendsDrawTheSamePicture) {
  const Scene scene = load_scene(kScenes + "/two_rooms.gltf").value();
  Config config;
  config.seed = 11;
  // Room for every indicator of the run: once the ring wraps, which of the
  // oldest step's indicators survive depends on the order the GPU wrote
  // them in, which is not fixed.
  config.max_indicators = 100000;
  // Where spots overlap, the one drawn last lays its halo over the others,
  // and the GPU's ring order is not fixed; without the halo, overlapping
  // spots of one source blend the same in any order.
  config.display.outline = false;
  const Picture cpu = render(scene, config, Backend::Cpu, 20, size(200, 120, true));
  const Picture gpu = render(scene, config, Backend::Gpu, 20, size(200, 120, true));
  EXPECT_GT(test::count_pixels(cpu.image, is_stereo_blue), 1000u) << "too few indicators to compare";
  const std::size_t differing = test::differing_pixels(cpu.image, gpu.image, 8, nullptr);
  std::printf("[          ] CPU and GPU pictures differ in %zu of %zu pixels\n", differing,
              cpu.image.pixels.size() / 4);
  EXPECT_LE(differing, cpu.image.pixels.size() / 4 / 200) << differing << " pixels differ";
}

// The camera rules of `render` (no device needed).
TEST(ViewCamera, FollowsTheSceneCameraTheListenerAndTheOverrides) {
  Scene scene = open_yard();
  Camera camera;
  glm::mat4 pose(1.0f);
  pose[0] = glm::vec4(0, 0, -1, 0);  // a quarter turn about +Y: local -Z looks down world -X
  pose[2] = glm::vec4(1, 0, 0, 0);
  pose[3] = glm::vec4(3, 2, 1, 1);
  camera.world = pose;
  scene.camera = camera;
  Config config = yard_config(10);
  config.listener_position.reset();
  World world = make_world(scene, config).value();

  draw::ViewCamera view = draw::make_view_camera(scene.camera, world, {}, 320, 240);
  EXPECT_EQ(view.eye, glm::vec3(3, 2, 1));
  EXPECT_NEAR(glm::dot(view.forward, glm::vec3(-1, 0, 0)), 1.0f, 1e-6f);
  // A point straight ahead lands in the middle of the picture; one above it, higher up (smaller y).
  auto centre = draw::project_to_pixel(view, glm::vec3(-5, 2, 1), 320, 240);
  auto above = draw::project_to_pixel(view, glm::vec3(-5, 3, 1), 320, 240);
  ASSERT_TRUE(centre && above);
  EXPECT_NEAR(centre->x, 160.0f, 1e-3f);
  EXPECT_NEAR(centre->y, 120.0f, 1e-3f);
  EXPECT_LT(above->y, centre->y);
  EXPECT_FALSE(draw::project_to_pixel(view, glm::vec3(9, 2, 1), 320, 240));  // behind the eye

  config.listener_position = glm::vec3(-1, 1, 0);  // the camera's view from the listener
  world = make_world(scene, config).value();
  view = draw::make_view_camera(scene.camera, world, {}, 320, 240);
  EXPECT_EQ(view.eye, glm::vec3(-1, 1, 0));
  EXPECT_NEAR(glm::dot(view.forward, glm::vec3(-1, 0, 0)), 1.0f, 1e-6f);

  view = draw::make_view_camera(std::nullopt, world, {}, 320, 240);  // no camera: the scene's centre
  const glm::vec3 centre_of_bounds = 0.5f * (world.geometry->bvh.nodes[0].bmin + world.geometry->bvh.nodes[0].bmax);
  EXPECT_NEAR(glm::dot(view.forward, glm::normalize(centre_of_bounds - view.eye)), 1.0f, 1e-5f);

  draw::CameraOverrides overrides;
  overrides.position = glm::vec3(0, 5, 0);
  overrides.look_at = glm::vec3(0, 0, 0);  // straight down: +Y cannot be up
  overrides.yfov_degrees = 90.0f;
  view = draw::make_view_camera(scene.camera, world, overrides, 320, 240);
  EXPECT_NEAR(glm::dot(view.forward, glm::vec3(0, -1, 0)), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(view.up, view.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(view.yfov, glm::radians(90.0f), 1e-6f);
  overrides.look_at = overrides.position;
  EXPECT_THROW(draw::make_view_camera(scene.camera, world, overrides, 320, 240), Exception);
}

// A small picture compared with tests/data/golden/two_rooms_320x240.png: at
// most 0.5% of pixels may differ by more than 8 in a channel. On failure the
// actual picture and a diff go to the build tree. SP_REBLESS_GOLDEN=1
// (scripts/rebless-golden.sh) rewrites the golden instead.
TEST_F(Render, GoldenTwoRooms) {
  const Scene scene = load_scene(kScenes + "/two_rooms.gltf").value();
  Config config;
  config.seed = 7;
  const Picture p = render(scene, config, Backend::Cpu, 20, size(320, 240, true));
  const std::filesystem::path golden = std::filesystem::path(SP_TEST_DATA_DIR) / "golden" / "two_rooms_320x240.png";
  if (const char* rebless = std::getenv("SP_REBLESS_GOLDEN"); rebless != nullptr && std::string(rebless) == "1") {
    std::filesystem::create_directories(golden.parent_path());
    draw::write_png(golden, p.image);
    GTEST_SKIP() << "reblessed " << golden;
  }
  test::expect_matches_golden(p.image, golden, std::filesystem::path(SP_TEST_OUTPUT_DIR) / "golden-failures");
}

}  // namespace
}  // namespace sp
