// Off-screen arrows tell a source's bearing (docs/accessibility.md,
// "Off-screen arrows"): read as a measuring tool reads them, an arrow's
// angle about the picture's centre, clockwise from straight up, taken from
// the unweighted centroid of its pixels (halo included), is the source's
// bearing right of the view direction. Expectations are derived by hand
// from where each source is put: at bearing b and elevation e, d metres
// from an eye that looks along -Z, it lies at eye + d (sin b cos e, sin e,
// -cos b cos e). Arrow pixels are those that differ from the same picture
// with arrows off; each connected group of them is one arrow.
// Runs on the shared validation-enabled context; any validation message
// fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "draw/display_frame.h"
#include "render/host_indicators.h"
#include "render/renderer.h"
#include "sp_arrows.h"
#include "sp_draw_types.h"
#include "support/gpu_environment.h"
#include "support/render_checks.h"
#include "support/scene_builder.h"

namespace sp {
namespace {

// Large enough for three arrows to stack at the sides (sp_arrows.h).
constexpr std::uint32_t kWidth = 960;
constexpr std::uint32_t kHeight = 720;
const glm::vec3 kEye(0.0f, 1.6f, 0.0f);
constexpr float kDistance = 10.0f;  // metres from the eye to every source
constexpr float kToleranceDegrees = 2.0f;

float radians(float degrees) { return degrees * SP_PI / 180.0f; }
float degrees(float radians) { return radians * 180.0f / SP_PI; }

// Where a source at `bearing` right of -Z and `elevation` above eye level lies.
glm::vec3 at_bearing(float bearing_degrees, float elevation_degrees = 0.0f) {
  const float b = radians(bearing_degrees), e = radians(elevation_degrees);
  return kEye + kDistance * glm::vec3(std::sin(b) * std::cos(e), std::sin(e), -std::cos(b) * std::cos(e));
}

// The signed difference a - b, in (-180, 180].
float angle_difference(float a, float b) {
  float d = std::fmod(a - b, 360.0f);
  if (d > 180.0f) d -= 360.0f;
  if (d <= -180.0f) d += 360.0f;
  return d;
}

struct Blob {
  std::size_t pixels = 0;
  glm::dvec2 centroid{0.0};
  double min_radius = 1e9;  // pixels from the picture's centre, nearest pixel
  double max_radius = 0.0;  // farthest pixel

  // The tool's reading: atan2(cx - W/2, -(cy - H/2)), degrees clockwise from up.
  float angle() const { return degrees(float(std::atan2(centroid.x - kWidth / 2.0, -(centroid.y - kHeight / 2.0)))); }
  double radius() const { return glm::length(centroid - glm::dvec2(kWidth / 2.0, kHeight / 2.0)); }
};

// 8-connected groups of the pixels where `with` differs from `without`.
std::vector<Blob> arrow_blobs(const draw::RgbaImage& with, const draw::RgbaImage& without) {
  const std::size_t n = std::size_t(kWidth) * kHeight;
  std::vector<char> mask(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) mask[i] |= with.pixels[4 * i + c] != without.pixels[4 * i + c];
  std::vector<Blob> blobs;
  std::vector<std::size_t> stack;
  for (std::size_t start = 0; start < n; ++start) {
    if (!mask[start]) continue;
    Blob blob;
    glm::dvec2 sum(0.0);
    mask[start] = 0;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      const int x = int(i % kWidth), y = int(i / kWidth);
      const glm::dvec2 centre(x + 0.5, y + 0.5);
      const double r = glm::length(centre - glm::dvec2(kWidth / 2.0, kHeight / 2.0));
      blob.pixels += 1;
      sum += centre;
      blob.min_radius = std::min(blob.min_radius, r);
      blob.max_radius = std::max(blob.max_radius, r);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= int(kWidth) || ny >= int(kHeight)) continue;
          const std::size_t j = std::size_t(ny) * kWidth + std::size_t(nx);
          if (mask[j]) {
            mask[j] = 0;
            stack.push_back(j);
          }
        }
    }
    blob.centroid = sum / double(blob.pixels);
    blobs.push_back(blob);
  }
  return blobs;
}

class Arrows : public test::GpuTest {
 protected:
  // The arrows of sources at `positions` (each heard: one live spot, far
  // below the view), seen from kEye along -Z, with `cues` per source id.
  std::vector<Blob> arrows(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& cues = {}) {
    const draw::RgbaImage with = draw(positions, cues, true);
    const draw::RgbaImage without = draw(positions, cues, false);
    return arrow_blobs(with, without);
  }

  draw::RgbaImage draw(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& cues, bool arrows) {
    // Only a floor 50 m below, out of sight: the picture is the clear
    // colour wherever there is no arrow.
    Scene scene;
    test::add_box(scene, {-100, -50.3f, -100}, {100, -50, 100}, "concrete");
    std::vector<shader::Indicator> spots;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      SourceDesc source = test::source_at(positions[i]);
      source.color = Vec3{1.0f, 0.6f, 0.1f};
      source.category = "alarm";  // a triangle: mirror-symmetric about its radial line only, unlike a disc
      scene.sources.push_back(source);
      shader::Indicator spot{};
      spot.position = glm::vec3(positions[i].x, -50.0f, positions[i].z);
      spot.normal = glm::vec3(0, 1, 0);
      spot.dir = glm::vec3(0, -1, 0);
      spot.size = 0.5f;
      spot.energy = spot.intensity = 1.0f;
      spot.kind = SP_INDICATOR_HIT;
      spot.source_id = std::uint32_t(i);
      spot.color = glm::vec3(1.0f, 0.6f, 0.1f);
      spots.push_back(spot);
    }
    Config config;
    config.listener_position = kEye;
    config.display.offscreen_arrows = arrows;
    const World world = make_world(scene, config).value();

    vk::Context& context = *test::GpuEnvironment::context();
    draw::RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.markers = false;
    draw::Renderer renderer(context, world, settings);
    renderer.set_source_cues(cues);
    draw::HostIndicators ring(context);
    ring.upload(spots);
    draw::CameraOverrides overrides;
    overrides.position = kEye;
    overrides.look_at = kEye + glm::vec3(0, 0, -1);
    overrides.yfov_degrees = 50.0f;
    const draw::ViewCamera camera = draw::make_view_camera(std::nullopt, world, overrides, kWidth, kHeight);
    return renderer.render(camera, ring.view(), world, /*steps_run=*/19);  // faded in, 0.3 s old
  }
};

void expect_angle(const Blob& blob, float bearing, const std::string& what) {
  std::printf("  %s: bearing %.1f deg, arrow at %.2f deg, %zu px, %.0f px from the centre\n", what.c_str(), bearing,
              blob.angle(), blob.pixels, blob.radius());
  EXPECT_LE(std::abs(angle_difference(blob.angle(), bearing)), kToleranceDegrees) << what;
}

// Level with the eye, all round: the arrow's angle is the bearing, and it
// sits on the ring near the edge, not by the centre.
TEST_F(Arrows, AnArrowsAngleIsItsSourcesBearing) {
  for (float bearing : {90.0f, 135.0f, -135.0f, 180.0f, -90.0f, 60.0f, -60.0f}) {
    const std::vector<Blob> blobs = arrows({at_bearing(bearing)});
    ASSERT_EQ(blobs.size(), 1u) << "bearing " << bearing;
    EXPECT_GT(blobs[0].pixels, 400u) << "an arrow, not a speck";
    expect_angle(blobs[0], bearing, "bearing " + std::to_string(int(bearing)));
    EXPECT_GT(blobs[0].radius(), 0.6 * kHeight / 2) << "on the ring by the edge";
    if (bearing == 180.0f) {  // straight behind: straight down, centred
      EXPECT_NEAR(blobs[0].centroid.x, kWidth / 2.0, 1.0);
      EXPECT_GT(blobs[0].centroid.y, kHeight / 2.0);
    }
  }
}

// Out of view straight ahead, 60 degrees up: at the top.
TEST_F(Arrows, ASourceAheadAndHighPointsStraightUp) {
  const std::vector<Blob> blobs = arrows({at_bearing(0.0f, 60.0f)});
  ASSERT_EQ(blobs.size(), 1u);
  expect_angle(blobs[0], 0.0f, "ahead, 60 deg up");
  EXPECT_LT(blobs[0].centroid.y, kHeight / 2.0);
}

// 30 degrees above or below eye level: a mark on the radial line, beyond
// the head (the arrow reaches further out than a level one) or behind the
// shape (further in); the angle stays the bearing. The arrow's place does
// not move with it.
TEST_F(Arrows, ElevationAddsAMarkWithoutTurningTheArrow) {
  const std::vector<Blob> level = arrows({at_bearing(90.0f)});
  const std::vector<Blob> above = arrows({at_bearing(90.0f, 30.0f)});
  const std::vector<Blob> below = arrows({at_bearing(90.0f, -30.0f)});
  ASSERT_EQ(level.size(), 1u);
  ASSERT_EQ(above.size(), 1u) << "the mark is joined to its arrow";
  ASSERT_EQ(below.size(), 1u) << "the mark is joined to its arrow";
  expect_angle(level[0], 90.0f, "level");
  expect_angle(above[0], 90.0f, "30 deg above");
  expect_angle(below[0], 90.0f, "30 deg below");
  // The bar reaches 0.65 units (14 px at this size) past the tip, or 1.26
  // (28 px) behind the triangle's back.
  EXPECT_GT(above[0].max_radius, level[0].max_radius + 8.0);
  EXPECT_NEAR(above[0].min_radius, level[0].min_radius, 1.5);
  EXPECT_LT(below[0].min_radius, level[0].min_radius - 8.0);
  EXPECT_NEAR(below[0].max_radius, level[0].max_radius, 1.5);
  // 10 degrees is level (the marks start at SP_ARROW_MARK_DEGREES, 15).
  const std::vector<Blob> slight = arrows({at_bearing(90.0f, 10.0f)});
  ASSERT_EQ(slight.size(), 1u);
  EXPECT_EQ(slight[0].pixels, level[0].pixels);
}

// Two sources 2 degrees apart: two arrows, apart, each at its own bearing
// (the second stacked inwards). Also across the seam behind the eye.
TEST_F(Arrows, ArrowsInNearlyTheSameDirectionStackAndKeepTheirAngles) {
  for (auto [a, b] : {std::pair{88.0f, 90.0f}, std::pair{179.0f, -179.0f}, std::pair{-45.0f, -43.0f}}) {
    const std::vector<Blob> blobs = arrows({at_bearing(a), at_bearing(b)});
    ASSERT_EQ(blobs.size(), 2u) << a << " and " << b << " should not touch";
    // Told apart by angle alone they are within the tolerance of both: the
    // one nearer each bearing is its arrow.
    const bool first_is_a =
        std::abs(angle_difference(blobs[0].angle(), a)) <= std::abs(angle_difference(blobs[1].angle(), a));
    expect_angle(blobs[first_is_a ? 0 : 1], a, "pair " + std::to_string(int(a)) + "/" + std::to_string(int(b)));
    expect_angle(blobs[first_is_a ? 1 : 0], b, "pair " + std::to_string(int(a)) + "/" + std::to_string(int(b)));
    EXPECT_GT(std::abs(blobs[0].radius() - blobs[1].radius()), 50.0) << "one steps inwards";
  }
}

// Three in a row, 6 degrees apart. On the ring at the side the arrows'
// inner ends lie 480 - 4 - 2 * 57.2 = 362 px from the centre (half the
// width less the edge gap and twice the arrow's half-length, 2.6 units of
// 22 px), 2 * 362 * sin(3 deg) = 38 px apart for neighbours, under the
// 60 px two arrows need side by side (2 * 1.28 units and a 4 px gap), and
// 76 px for the outer two: the third is near the second only, yet must not
// land on the second's place (a count of the near arrows before it would
// say 1).
TEST_F(Arrows, ARunOfThreeTakesThreePlaces) {
  std::vector<Blob> blobs = arrows({at_bearing(84.0f), at_bearing(90.0f), at_bearing(96.0f)});
  ASSERT_EQ(blobs.size(), 3u);
  // In angle order they are the sources in bearing order.
  std::sort(blobs.begin(), blobs.end(), [](const Blob& a, const Blob& b) { return a.angle() < b.angle(); });
  expect_angle(blobs[0], 84.0f, "run of three");
  expect_angle(blobs[1], 90.0f, "run of three");
  expect_angle(blobs[2], 96.0f, "run of three");
  std::vector<double> radii = {blobs[0].radius(), blobs[1].radius(), blobs[2].radius()};
  std::sort(radii.begin(), radii.end());
  EXPECT_GT(radii[1] - radii[0], 50.0);
  EXPECT_GT(radii[2] - radii[1], 50.0);
}

// A source in view gets no arrow (its spots are its cue), unless the
// simulation found it occluded: then its arrow is on the same ring at its
// bearing, head out, so a player facing a hidden source still sees where.
TEST_F(Arrows, AnOccludedSourceInViewGetsItsArrow) {
  const std::vector<glm::vec3> in_view = {at_bearing(10.0f), at_bearing(-15.0f)};
  EXPECT_TRUE(arrows(in_view).empty()) << "no flags: both are seen";
  const std::vector<Blob> hidden = arrows(in_view, {0u, SP_SOURCE_CUE_OCCLUDED});
  ASSERT_EQ(hidden.size(), 1u) << "only source 1 is occluded";
  expect_angle(hidden[0], -15.0f, "in view, occluded");
  EXPECT_GT(hidden[0].radius(), 0.6 * kHeight / 2) << "on the ring, as the arrows out of view";
  // An occluded source out of view has its one arrow, as before.
  const std::vector<Blob> behind = arrows({at_bearing(170.0f)}, {SP_SOURCE_CUE_OCCLUDED});
  ASSERT_EQ(behind.size(), 1u);
  expect_angle(behind[0], 170.0f, "behind, occluded");
}

// offscreen_arrows off hides every arrow, the occluded ones too: the
// picture is the clear colour throughout.
TEST_F(Arrows, ArrowsOffHidesThemAll) {
  const std::vector<glm::vec3> sources = {at_bearing(10.0f), at_bearing(120.0f)};
  const std::vector<std::uint32_t> occluded = {SP_SOURCE_CUE_OCCLUDED, SP_SOURCE_CUE_OCCLUDED};
  EXPECT_EQ(arrows(sources, occluded).size(), 2u);
  const draw::RgbaImage off = draw(sources, occluded, false);
  const test::Rgb clear = test::pixel(off, 0, 0);
  EXPECT_EQ(test::count_pixels(off, [&](test::Rgb c) { return c.r != clear.r || c.g != clear.g || c.b != clear.b; }),
            0u);
}

// The heading arrows measure bearings from: the view direction in the
// horizontal plane, however far the camera pitches.
TEST(ArrowHeading, IsTheViewDirectionInTheHorizontalPlane) {
  auto heading = [](glm::vec3 eye, glm::vec3 target, glm::vec3 up) {
    const glm::mat4 view = glm::lookAtRH(eye, target, up);
    return draw::DrawView::from(view, glm::mat4(1.0f), glm::vec2(100.0f)).heading;
  };
  auto expect_near = [](glm::vec2 a, glm::vec2 b) {
    EXPECT_NEAR(a.x, b.x, 1e-5f);
    EXPECT_NEAR(a.y, b.y, 1e-5f);
  };
  // Level, along -Z and along +X: (x, z) of the view direction.
  expect_near(heading({0, 0, 0}, {0, 0, -1}, {0, 1, 0}), {0, -1});
  expect_near(heading({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), {1, 0});
  // Pitched 60 degrees down or 80 up towards +X: still +X.
  expect_near(heading({0, 0, 0}, {1, -1.732f, 0}, {0, 1, 0}), {1, 0});
  expect_near(heading({0, 5, 0}, {0.176f, 6, 0}, {0, 1, 0}), {1, 0});
  // Straight down with the picture's top towards -Z: -Z.
  expect_near(draw::view_heading({0, -1, 0}, {0, 0, -1}), {0, -1});
  // Straight up, head tipped back from facing -Z (the picture's top is +Z):
  // -Z, where the player was facing.
  expect_near(draw::view_heading({0, 1, 0}, {0, 0, 1}), {0, -1});
  // Rolled 30 degrees while level: the roll does not turn the heading.
  expect_near(draw::view_heading({0, 0, -1}, {0.5f, 0.866f, 0}), {0, -1});
}

// The ring keeps every arrow's quad on screen at every angle, in wide,
// square and tall viewports; at the top of a 720-high one the anchor is
// half the height less the arrow's half-length (from its lowest mark to its
// highest: 2.6 units of 22 px) and the edge's margin (4 px).
TEST(ArrowRing, KeepsEveryArrowOnScreen) {
  for (glm::vec2 viewport : {glm::vec2(960, 720), glm::vec2(1920, 1080), glm::vec2(400, 400), glm::vec2(360, 800)}) {
    const float scale = 22.0f;
    const glm::vec2 half = 0.5f * viewport;
    for (int step = 0; step < 3600; ++step) {
      const float theta = radians(float(step) * 0.1f);
      const float r = shader::sp_arrow_ring_distance(theta, half, scale);
      ASSERT_GT(r, 0.0f);
      const glm::vec2 way = shader::sp_arrow_direction(theta);
      const glm::vec2 side(-way.y, way.x);
      const glm::vec2 anchor = way * r;
      const float reach = shader::sp_arrow_half_length() * scale;
      for (float along : {-reach, reach})
        for (float across : {-SP_ARROW_HALF_WIDTH * scale, SP_ARROW_HALF_WIDTH * scale}) {
          const glm::vec2 corner = anchor + way * along + side * across;
          ASSERT_LE(std::abs(corner.x), half.x - SP_ARROW_EDGE_PIXELS + 1e-3f) << viewport.x << " at " << step;
          ASSERT_LE(std::abs(corner.y), half.y - SP_ARROW_EDGE_PIXELS + 1e-3f) << viewport.x << " at " << step;
        }
    }
  }
  const float half_length = 0.5f * (SP_ARROW_HIGH - SP_ARROW_LOW);
  EXPECT_NEAR(shader::sp_arrow_ring_distance(0.0f, glm::vec2(480, 360), 22.0f),
              360.0f - half_length * 22.0f - SP_ARROW_EDGE_PIXELS, 1e-3f);
}

}  // namespace
}  // namespace sp
