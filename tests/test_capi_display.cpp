// The display settings through the C API: sp_display_settings and
// sp_draw_options start at the C++ defaults, reach the C++ structs field by
// field, and reject every bad field with a message naming it; on a
// visualizer (the test plays a C host on the shared validation-enabled
// device) they change the picture drawn: hidden categories vanish, size
// scale and per-category caps change the painted area, scene depth clips
// spots, and arrows point at a source behind the camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "capi/display_c.h"
#include "render/render_target.h"
#include "soundpaint/soundpaint_vulkan.h"
#include "sp_types.h"
#include "support/gpu_environment.h"
#include "support/host_commands.h"
#include "support/render_checks.h"
#include "vk/vk_check.h"

namespace sp {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::string last_error() { return sp_last_error_message(); }

void expect_same(const DisplaySettings& a, const DisplaySettings& b) {
  EXPECT_EQ(a.palette, b.palette);
  EXPECT_EQ(a.shapes, b.shapes);
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_EQ(a.outline, b.outline);
  EXPECT_EQ(a.size_scale, b.size_scale);
  EXPECT_EQ(a.opacity_scale, b.opacity_scale);
  EXPECT_EQ(a.min_opacity, b.min_opacity);
  EXPECT_EQ(a.hide_categories, b.hide_categories);
  EXPECT_EQ(a.max_per_category, b.max_per_category);
  EXPECT_EQ(a.offscreen_arrows, b.offscreen_arrows);
}

sp_display_settings defaults() {
  sp_display_settings settings;
  sp_display_settings_init(&settings);
  return settings;
}

TEST(CapiDisplaySettings, InitGivesTheLibraryDefaults) {
  sp_display_settings c;
  std::memset(&c, 0xAB, sizeof c);  // init must overwrite every field
  sp_display_settings_init(&c);
  const DisplaySettings cpp;
  EXPECT_EQ(static_cast<int>(c.palette), static_cast<int>(cpp.palette));
  EXPECT_EQ(c.palette, SP_PALETTE_OKABE_ITO);
  EXPECT_EQ(c.direction, cpp.direction ? 1 : 0);
  EXPECT_EQ(c.outline, cpp.outline ? 1 : 0);
  EXPECT_EQ(c.size_scale, cpp.size_scale);
  EXPECT_EQ(c.opacity_scale, cpp.opacity_scale);
  EXPECT_EQ(c.min_opacity, cpp.min_opacity);
  EXPECT_FALSE(cpp.max_per_category.has_value());
  EXPECT_EQ(c.max_per_category, 0u);  // no cap
  EXPECT_FALSE(cpp.offscreen_arrows.has_value());
  EXPECT_EQ(c.offscreen_arrows, -1);  // the front end decides
  EXPECT_EQ(c.hide_categories, nullptr);
  EXPECT_EQ(c.hide_category_count, 0u);
  EXPECT_EQ(c.shape_categories, nullptr);
  EXPECT_EQ(c.shapes, nullptr);
  EXPECT_EQ(c.shape_count, 0u);
  // And back: the defaults convert to exactly DisplaySettings{}.
  expect_same(capi::display_settings_from(c, "test"), cpp);
  sp_display_settings_init(nullptr);  // a no-op, not a crash
}

TEST(CapiDisplaySettings, EveryFieldReachesTheCppSettingsAndStringsAreCopied) {
  std::string hidden = "footsteps";
  std::string shaped = "alarm";
  const char* hide[] = {hidden.c_str(), "ambience"};
  const char* categories[] = {shaped.c_str(), "door"};
  const std::uint32_t shapes[] = {SP_SHAPE_STAR, SP_SHAPE_CLOVER};
  sp_display_settings c = defaults();
  c.palette = SP_PALETTE_SINGLE_HUE;
  c.direction = 0;
  c.outline = 0;
  c.size_scale = 2.5f;
  c.opacity_scale = 0.0f;  // the lowest allowed
  c.min_opacity = 1.0f;    // the highest allowed
  c.max_per_category = 7;
  c.offscreen_arrows = 1;
  c.hide_categories = hide;
  c.hide_category_count = 2;
  c.shape_categories = categories;
  c.shapes = shapes;
  c.shape_count = 2;
  const DisplaySettings cpp = capi::display_settings_from(c, "test");
  hidden.assign("XXXXXXXXX");  // the caller's buffers may change afterwards
  shaped.assign("XXXXX");
  EXPECT_EQ(cpp.palette, Palette::SingleHue);
  EXPECT_FALSE(cpp.direction);
  EXPECT_FALSE(cpp.outline);
  EXPECT_EQ(cpp.size_scale, 2.5f);
  EXPECT_EQ(cpp.opacity_scale, 0.0f);
  EXPECT_EQ(cpp.min_opacity, 1.0f);
  EXPECT_EQ(cpp.max_per_category, 7u);
  EXPECT_EQ(cpp.offscreen_arrows, true);
  EXPECT_EQ(cpp.hide_categories, (std::vector<std::string>{"footsteps", "ambience"}));
  EXPECT_EQ(cpp.shapes, (std::map<std::string, Shape>{{"alarm", Shape::Star}, {"door", Shape::Clover}}));
  c.offscreen_arrows = 0;
  EXPECT_EQ(capi::display_settings_from(c, "test").offscreen_arrows, false);
  // The public ids are the library's shapes, so a binding can name them.
  EXPECT_EQ(SP_SHAPE_DISC, static_cast<std::uint32_t>(Shape::Disc));
  EXPECT_EQ(SP_SHAPE_CLOVER, static_cast<std::uint32_t>(Shape::Clover));
  EXPECT_EQ(SP_SHAPE_CLOVER + 1, kShapeCount);
}

// One bad field: what to change, and what the message must name.
struct BadSettings {
  const char* names;
  std::function<void(sp_display_settings&)> spoil;
};

// Any int, as a C caller may store it (C++ may not convert it to the enum).
void store(sp_palette& palette, std::underlying_type_t<sp_palette> value) {
  std::memcpy(&palette, &value, sizeof value);
}

const char* const kNullCategory[] = {"a", nullptr};
const char* const kEmptyCategory[] = {""};
const char* const kOneCategory[] = {"x"};
const char* const kRepeated[] = {"x", "x"};
const std::uint32_t kOneShape[] = {SP_SHAPE_RING};
const std::uint32_t kTwoShapes[] = {SP_SHAPE_RING, SP_SHAPE_STAR};
const std::uint32_t kNotAShape[] = {10};

std::vector<BadSettings> bad_settings() {
  return {
      {"settings->palette", [](auto& s) { store(s.palette, 3); }},
      {"settings->palette", [](auto& s) { store(s.palette, static_cast<std::underlying_type_t<sp_palette>>(-1)); }},
      {"settings->direction", [](auto& s) { s.direction = 2; }},
      {"settings->outline", [](auto& s) { s.outline = -1; }},
      {"settings->size_scale", [](auto& s) { s.size_scale = 0.0f; }},
      {"settings->size_scale", [](auto& s) { s.size_scale = kNan; }},
      {"settings->size_scale", [](auto& s) { s.size_scale = kInf; }},
      {"settings->opacity_scale", [](auto& s) { s.opacity_scale = -0.5f; }},
      {"settings->opacity_scale", [](auto& s) { s.opacity_scale = kNan; }},
      {"settings->opacity_scale", [](auto& s) { s.opacity_scale = kInf; }},
      {"settings->min_opacity", [](auto& s) { s.min_opacity = 1.5f; }},
      {"settings->min_opacity", [](auto& s) { s.min_opacity = -0.1f; }},
      {"settings->min_opacity", [](auto& s) { s.min_opacity = kNan; }},
      {"settings->offscreen_arrows", [](auto& s) { s.offscreen_arrows = 2; }},
      {"settings->offscreen_arrows", [](auto& s) { s.offscreen_arrows = -2; }},
      {"settings->hide_categories",
       [](auto& s) {
         s.hide_categories = nullptr;
         s.hide_category_count = 1;
       }},
      {"settings->hide_categories[1]",
       [](auto& s) {
         s.hide_categories = kNullCategory;
         s.hide_category_count = 2;
       }},
      {"settings->hide_categories[0]",
       [](auto& s) {
         s.hide_categories = kEmptyCategory;
         s.hide_category_count = 1;
       }},
      {"settings->shape_categories",
       [](auto& s) {
         s.shapes = kOneShape;
         s.shape_count = 1;
       }},
      {"settings->shapes",
       [](auto& s) {
         s.shape_categories = kOneCategory;
         s.shape_count = 1;
       }},
      {"settings->shapes[0]",
       [](auto& s) {
         s.shape_categories = kOneCategory;
         s.shapes = kNotAShape;
         s.shape_count = 1;
       }},
      {"settings->shape_categories[1]",
       [](auto& s) {
         s.shape_categories = kNullCategory;
         s.shapes = kTwoShapes;
         s.shape_count = 2;
       }},
      {"settings->shape_categories[0]",
       [](auto& s) {
         s.shape_categories = kEmptyCategory;
         s.shapes = kOneShape;
         s.shape_count = 1;
       }},
      {"settings->shape_categories[1]",
       [](auto& s) {
         s.shape_categories = kRepeated;
         s.shapes = kTwoShapes;
         s.shape_count = 2;
       }},
  };
}

TEST(CapiDisplaySettings, EachBadFieldIsRejectedNamingIt) {
  for (const BadSettings& bad : bad_settings()) {
    sp_display_settings settings = defaults();
    bad.spoil(settings);
    try {
      (void)capi::display_settings_from(settings, "fn");
      ADD_FAILURE() << bad.names << ": accepted";
    } catch (const Exception& e) {
      EXPECT_EQ(e.error().code, ErrorCode::InvalidArgument) << e.what();
      EXPECT_NE(std::string(e.what()).find(bad.names), std::string::npos) << bad.names << ": " << e.what();
    }
  }
  // Arrays with a zero count are never read.
  sp_display_settings unread = defaults();
  unread.hide_categories = kNullCategory;
  unread.shape_categories = kEmptyCategory;
  unread.shapes = kNotAShape;
  EXPECT_NO_THROW((void)capi::display_settings_from(unread, "fn"));
}

TEST(CapiDrawOptions, InitGivesTheLibraryDefaults) {
  sp_draw_options c;
  std::memset(&c, 0xAB, sizeof c);
  sp_draw_options_init(&c);
  const DrawOptions cpp;
  EXPECT_EQ(c.area, cpp.area);
  EXPECT_EQ(c.viewport_width, cpp.viewport_width);
  EXPECT_EQ(c.viewport_height, cpp.viewport_height);
  EXPECT_EQ(c.viewport_x, cpp.viewport_x);
  EXPECT_EQ(c.viewport_y, cpp.viewport_y);
  EXPECT_EQ(c.viewport_x, 0u);
  EXPECT_EQ(c.scene_depth, cpp.scene_depth);
  EXPECT_EQ(c.scene_depth, -1);
  sp_draw_options_init(nullptr);
}

TEST(CapiDrawOptions, FieldsAreCheckedAndAnAreaGivesTheViewportSize) {
  const VkRect2D area{{4, 8}, {160, 120}};
  sp_draw_options options;
  sp_draw_options_init(&options);
  options.area = &area;
  DrawOptions cpp = capi::draw_options_from(options, "fn");
  EXPECT_EQ(cpp.area, &area);
  EXPECT_EQ(cpp.viewport_width, 160u);  // 0 x 0 with an area: the area's extent
  EXPECT_EQ(cpp.viewport_height, 120u);
  options.viewport_width = 160;
  options.viewport_height = 120;
  options.viewport_x = 4;  // the area's own offset may be repeated
  options.viewport_y = 8;
  options.scene_depth = 3;
  cpp = capi::draw_options_from(options, "fn");
  EXPECT_EQ(cpp.scene_depth, 3);
  EXPECT_EQ(cpp.viewport_x, 4u);
  EXPECT_EQ(cpp.viewport_y, 8u);
  sp_draw_options split;  // no area: the host's viewport starts where it says
  sp_draw_options_init(&split);
  split.viewport_width = 160;
  split.viewport_height = 240;
  split.viewport_x = 160;
  cpp = capi::draw_options_from(split, "fn");
  EXPECT_EQ(cpp.viewport_x, 160u);
  EXPECT_EQ(cpp.viewport_y, 0u);

  const VkRect2D empty{{0, 0}, {0, 16}};
  const VkRect2D behind{{-4, 0}, {16, 16}};
  const VkRect2D huge{{0, 0}, {70000, 16}};
  const struct {
    const char* names;
    std::function<void(sp_draw_options&)> spoil;
  } cases[] = {
      {"options->viewport_width", [](auto& o) { o.viewport_width = 100; }},
      {"options->viewport_width", [](auto& o) { o.viewport_height = 100; }},
      {"options->area is empty", [&](auto& o) { o.area = &empty; }},
      {"options->viewport_width",
       [&](auto& o) {
         o.area = &area;
         o.viewport_width = 100;
         o.viewport_height = 100;
       }},
      {"options->viewport_x",
       [&](auto& o) {
         o.area = &area;
         o.viewport_x = 5;
       }},
      {"options->viewport_x", [](auto& o) { o.viewport_y = 70000; }},
      {"options->viewport_width",
       [](auto& o) {
         o.viewport_width = 70000;
         o.viewport_height = 10;
       }},
      {"options->area", [&](auto& o) { o.area = &behind; }},
      {"options->area", [&](auto& o) { o.area = &huge; }},
      {"options->scene_depth", [](auto& o) { o.scene_depth = -2; }},
      {"options->scene_depth", [](auto& o) { o.scene_depth = std::numeric_limits<std::int32_t>::min(); }},
  };
  for (const auto& bad : cases) {
    sp_draw_options spoiled;
    sp_draw_options_init(&spoiled);
    bad.spoil(spoiled);
    try {
      (void)capi::draw_options_from(spoiled, "fn");
      ADD_FAILURE() << bad.names << ": accepted";
    } catch (const Exception& e) {
      EXPECT_NE(std::string(e.what()).find(bad.names), std::string::npos) << bad.names << ": " << e.what();
    }
  }
}

// --- On a visualizer ---

constexpr std::uint32_t kWidth = 320;
constexpr std::uint32_t kHeight = 240;

// A quad on the plane z = 1, two metres in front of the camera, facing it
// and the source (rays striking a face's back leave no spot).
const std::vector<float> kQuad = {
    -10, -10, 1, -10, 10, 1, 10, 10,  1,  //
    -10, -10, 1, 10,  10, 1, 10, -10, 1,  //
};
const std::uint32_t kQuadLayers[] = {0, 0};
const char* const kLayerNames[] = {"concrete"};

// A few rays a step, so that the spots seen (about a quarter of the rays)
// seldom overlap; large spots, so that size_scale grows them past the
// minimum on-screen size; a saturated colour of the source's own, whatever
// the palette. Its category is the default, "sound".
// Rays go out uniformly (no guide): a guided step sends most of them where
// the first one's spots were heard, some to centres above the picture.
const char* const kConfig = R"({
  "ray_budget": 16, "max_bounces": 1, "seed": 5, "dt": 0.1, "indicator_size": 0.5,
  "listener": { "position": [0, 0, 0] }, "cues": { "guide_share": 0 },
  "sources": [ { "position": [0, 0, 0], "color": [1.0, 0.2, 0.1] } ]
})";

std::size_t coloured_pixels(const draw::RgbaImage& image) { return test::count_pixels(image, test::is_saturated); }

class CapiDisplay : public test::GpuTest {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    context_ = test::GpuEnvironment::context();
    ASSERT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers, kLayerNames, 1, &scene_), SP_OK) << last_error();
    commands_ = std::make_unique<test::HostCommands>(*context_);
    target_ = std::make_unique<draw::RenderTarget>(*context_, kWidth, kHeight);

    sp_host_vulkan host;
    sp_host_vulkan_init(&host);
    host.instance = context_->instance();
    host.physical_device = context_->physical_device();
    host.device = context_->device();
    host.queue_family = context_->queue_family();
    sp_draw_target formats;
    sp_draw_target_init(&formats);
    formats.color_format = draw::RenderTarget::kColorFormat;
    formats.depth_format = draw::RenderTarget::kDepthFormat;
    ASSERT_EQ(sp_visualizer_create(&host, &formats, scene_, kConfig, SP_BACKEND_GPU, &vis_), SP_OK) << last_error();
    look(glm::vec3(0.0f, 0.0f, 1.0f));
  }
  void TearDown() override {
    if (context_ != nullptr) {
      EXPECT_EQ(vkDeviceWaitIdle(context_->device()), VK_SUCCESS);
      EXPECT_EQ(sp_visualizer_destroy(vis_), SP_OK) << last_error();
      EXPECT_EQ(sp_scene_destroy(scene_), SP_OK) << last_error();
      target_.reset();
      commands_.reset();
    }
    test::GpuTest::TearDown();
  }

  // The camera at (0, 0, -1) looking along `forward`, 90 degrees high.
  void look(glm::vec3 forward) {
    const glm::vec3 eye(0.0f, 0.0f, -1.0f);
    view_ = glm::lookAtRH(eye, eye + forward, glm::vec3(0.0f, 1.0f, 0.0f));
    projection_ = glm::perspectiveRH_ZO(glm::radians(90.0f), float(kWidth) / float(kHeight), 0.05f, 100.0f);
    projection_[1][1] *= -1.0f;  // Vulkan's clip-space y points down
  }

  // What a test's host records besides: into the scene's rendering, and
  // just before the indicators are drawn.
  struct HostSteps {
    std::function<void(VkCommandBuffer)> in_scene;
    std::function<void(VkCommandBuffer)> before_draw;
  };

  // One frame: `dt` seconds of simulation (0: none, but the display
  // settings still apply), the host's rendering cleared to black, then the
  // indicators drawn with `options` (the viewport's size by default) over a
  // read-only depth when `overlays`.
  draw::RgbaImage frame(double dt, const sp_draw_options* options = nullptr, bool overlays = false,
                        const HostSteps& host = {}) {
    sp_draw_options sized;
    sp_draw_options_init(&sized);
    sized.viewport_width = kWidth;
    sized.viewport_height = kHeight;
    VkCommandBuffer cmd = commands_->begin();
    EXPECT_EQ(sp_visualizer_record_simulation(vis_, cmd, dt, nullptr), SP_OK) << last_error();
    const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    target_->begin(cmd, clear);
    if (host.in_scene) host.in_scene(cmd);
    if (overlays) target_->begin_overlays(cmd);
    if (host.before_draw) host.before_draw(cmd);
    EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, glm::value_ptr(view_), glm::value_ptr(projection_),
                                           options != nullptr ? options : &sized),
              SP_OK)
        << last_error();
    target_->end_and_copy(cmd);
    SP_VK_CHECK(vkEndCommandBuffer(cmd));
    commands_->submit_and_wait({cmd});
    return target_->read();
  }

  // Three steps: a dozen spots or so in view, none faded yet.
  void simulate() {
    for (int n = 0; n < 3; ++n) frame(0.1);
  }

  sp_result set(const sp_display_settings& settings) { return sp_visualizer_set_display(vis_, &settings); }

  vk::Context* context_ = nullptr;
  sp_scene* scene_ = nullptr;
  sp_visualizer* vis_ = nullptr;
  std::unique_ptr<test::HostCommands> commands_;
  std::unique_ptr<draw::RenderTarget> target_;
  glm::mat4 view_{1.0f};
  glm::mat4 projection_{1.0f};
};

TEST_F(CapiDisplay, HidingTheOnlyCategoryLeavesNoColouredPixels) {
  simulate();
  const std::size_t shown = coloured_pixels(frame(0.0));
  EXPECT_GT(shown, 500u);

  const char* const sound[] = {"sound"};
  sp_display_settings hide = defaults();
  hide.hide_categories = sound;
  hide.hide_category_count = 1;
  ASSERT_EQ(set(hide), SP_OK) << last_error();
  EXPECT_EQ(coloured_pixels(frame(0.0)), 0u);

  // Another category hidden instead: the spots are back, as they were (but
  // for halos, which overlapping spots lay in the ring's order).
  const char* const other[] = {"footsteps"};
  hide.hide_categories = other;
  ASSERT_EQ(set(hide), SP_OK) << last_error();
  EXPECT_NEAR(double(coloured_pixels(frame(0.0))), double(shown), 0.02 * double(shown));
}

TEST_F(CapiDisplay, SizeScaleAndTheCapChangeThePaintedArea) {
  simulate();
  const std::size_t plain = coloured_pixels(frame(0.0));
  ASSERT_GT(plain, 500u);

  sp_display_settings bigger = defaults();
  bigger.size_scale = 2.0f;
  ASSERT_EQ(set(bigger), SP_OK) << last_error();
  const std::size_t big = coloured_pixels(frame(0.0));
  // Twice the diameter is four times the area, less where spots overlap.
  EXPECT_GT(big, plain * 3 / 2) << plain << " coloured pixels at size_scale 1";

  sp_display_settings capped = defaults();
  capped.max_per_category = 1;
  ASSERT_EQ(set(capped), SP_OK) << last_error();
  const std::size_t one = coloured_pixels(frame(0.0));
  EXPECT_GT(one, 0u);
  EXPECT_LT(one * 3, plain) << "one spot of " << plain << " coloured pixels";
}

// A failed call leaves the settings as they were: the same picture after
// every rejected field as before them.
TEST_F(CapiDisplay, SetDisplayRejectsBadFieldsNamingThemAndKeepsTheSettings) {
  simulate();
  const std::size_t before = coloured_pixels(frame(0.0));
  ASSERT_GT(before, 0u);
  for (const BadSettings& bad : bad_settings()) {
    sp_display_settings settings = defaults();
    // A valid change alongside the bad field, which must not be applied.
    const char* const sound[] = {"sound"};
    settings.hide_categories = sound;
    settings.hide_category_count = 1;
    bad.spoil(settings);
    EXPECT_EQ(set(settings), SP_ERROR_INVALID_ARGUMENT) << bad.names;
    EXPECT_NE(last_error().find(bad.names), std::string::npos) << bad.names << ": " << last_error();
    EXPECT_NE(last_error().find("sp_visualizer_set_display"), std::string::npos) << last_error();
  }
  EXPECT_NEAR(double(coloured_pixels(frame(0.0))), double(before), 0.02 * double(before));

  const sp_display_settings good = defaults();
  EXPECT_EQ(sp_visualizer_set_display(vis_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("settings is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_set_display(nullptr, &good), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("visualizer is NULL"), std::string::npos) << last_error();
}

// The render target's depth holds no scene (cleared to the far plane), so a
// spot clipped to the surface it lies on finds none and is not drawn.
TEST_F(CapiDisplay, SceneDepthClipsSpotsToTheSurfacesInIt) {
  const VkImageView depth = target_->depth_view();
  ASSERT_EQ(sp_visualizer_set_scene_depth(vis_, &depth, 1), SP_OK) << last_error();
  simulate();
  sp_draw_options options;
  sp_draw_options_init(&options);
  options.viewport_width = kWidth;
  options.viewport_height = kHeight;
  EXPECT_GT(coloured_pixels(frame(0.0, &options, true)), 500u);  // not clipped
  options.scene_depth = 0;
  EXPECT_EQ(coloured_pixels(frame(0.0, &options, true)), 0u);
  // Unregistered again: index 0 is no longer a view.
  ASSERT_EQ(sp_visualizer_set_scene_depth(vis_, nullptr, 0), SP_OK) << last_error();
  VkCommandBuffer cmd = commands_->begin();
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, glm::value_ptr(view_), glm::value_ptr(projection_), &options),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("scene_depth"), std::string::npos) << last_error();
}

// Split screen: the indicators drawn into the right half only, whose depth
// holds the quad's plane (the left half's is cleared to the far plane, as
// if a view of nothing). A spot shows only if the scene shows its centre,
// looked up in the depth at the viewport's own origin: from the area's
// offset, or from viewport_x when the host set the viewport itself. Taken
// from (0, 0) instead, every centre would land on the empty left half.
TEST_F(CapiDisplay, SceneDepthIsReadAtTheViewportsOrigin) {
  const VkImageView depth = target_->depth_view();
  ASSERT_EQ(sp_visualizer_set_scene_depth(vis_, &depth, 1), SP_OK) << last_error();
  simulate();
  const glm::vec4 on_quad = projection_ * view_ * glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  const float quad_depth = on_quad.z / on_quad.w;  // the quad faces the camera: one depth everywhere
  const VkRect2D right{{int32_t(kWidth / 2), 0}, {kWidth / 2, kHeight}};

  HostSteps host;
  host.in_scene = [&](VkCommandBuffer cmd) {  // the scene's rendering cleared depth to 1, the far plane
    VkClearAttachment plane{};
    plane.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
    plane.clearValue.depthStencil.depth = quad_depth;
    const VkClearRect rect{right, 0, 1};
    vkCmdClearAttachments(cmd, 1, &plane, 1, &rect);
  };
  HostSteps host_viewport = host;
  host_viewport.before_draw = [&](VkCommandBuffer cmd) {
    const VkViewport viewport{float(right.offset.x), 0.0f, float(right.extent.width), float(kHeight), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &right);
  };
  auto left_half = [](const draw::RgbaImage& image) {
    std::size_t n = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth / 2; ++x) n += test::is_saturated(test::pixel(image, x, y)) ? 1 : 0;
    return n;
  };

  sp_draw_options by_area;
  sp_draw_options_init(&by_area);
  by_area.area = &right;
  by_area.scene_depth = 0;
  const draw::RgbaImage a = frame(0.0, &by_area, true, host);
  EXPECT_GT(coloured_pixels(a), 200u) << "spots on the quad, seen in the right half, should show";
  EXPECT_EQ(left_half(a), 0u);

  sp_draw_options by_host;
  sp_draw_options_init(&by_host);
  by_host.viewport_width = right.extent.width;
  by_host.viewport_height = right.extent.height;
  by_host.viewport_x = right.offset.x;
  by_host.scene_depth = 0;
  const draw::RgbaImage b = frame(0.0, &by_host, true, host_viewport);
  EXPECT_EQ(coloured_pixels(b), coloured_pixels(a)) << "the same viewport, told by viewport_x instead of an area";

  by_host.viewport_x = 0;  // wrong: the centres are looked up in the left half, where nothing is
  EXPECT_EQ(coloured_pixels(frame(0.0, &by_host, true, host_viewport)), 0u);
}

// The camera turned away from the quad: no spot in view, but the source
// behind it is heard, so an arrow at the screen's edge points to it when
// asked for (the visualizer's default is none).
TEST_F(CapiDisplay, OffscreenArrowsPointAtASourceBehindTheCamera) {
  simulate();
  look(glm::vec3(0.0f, 0.0f, -1.0f));
  EXPECT_EQ(coloured_pixels(frame(0.0)), 0u);
  sp_display_settings arrows = defaults();
  arrows.offscreen_arrows = 1;
  ASSERT_EQ(set(arrows), SP_OK) << last_error();
  const draw::RgbaImage with_arrow = frame(0.0);
  EXPECT_GT(coloured_pixels(with_arrow), 50u);
  // Straight behind points down: the arrow lies in the lower half.
  std::size_t upper = 0;
  for (std::uint32_t y = 0; y < kHeight / 2; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) upper += test::is_saturated(test::pixel(with_arrow, x, y)) ? 1 : 0;
  EXPECT_EQ(upper, 0u);
  arrows.offscreen_arrows = 0;
  ASSERT_EQ(set(arrows), SP_OK) << last_error();
  EXPECT_EQ(coloured_pixels(frame(0.0)), 0u);
}

TEST_F(CapiDisplay, DrawExAndSceneDepthRejectMisuse) {
  const VkImageView depth = target_->depth_view();
  const VkImageView null_view = VK_NULL_HANDLE;
  EXPECT_EQ(sp_visualizer_set_scene_depth(vis_, nullptr, 1), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("views is NULL"), std::string::npos) << last_error();
  const VkImageView with_null[] = {depth, null_view};
  EXPECT_EQ(sp_visualizer_set_scene_depth(vis_, with_null, 2), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("views[1]"), std::string::npos) << last_error();
  const std::vector<VkImageView> nine(9, depth);
  EXPECT_EQ(sp_visualizer_set_scene_depth(vis_, nine.data(), 9), SP_ERROR_LIMIT_EXCEEDED);
  EXPECT_EQ(sp_visualizer_set_scene_depth(nullptr, &depth, 1), SP_ERROR_INVALID_ARGUMENT);

  frame(0.1);
  const float* view = glm::value_ptr(view_);
  const float* projection = glm::value_ptr(projection_);
  VkCommandBuffer cmd = commands_->begin();  // nothing is recorded into it below
  sp_draw_options options;
  sp_draw_options_init(&options);
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, view, projection, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("options is NULL"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, VK_NULL_HANDLE, view, projection, &options), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, nullptr, projection, &options), SP_ERROR_INVALID_ARGUMENT);
  float nan_projection[16];
  std::copy(projection, projection + 16, nan_projection);
  nan_projection[5] = kNan;
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, view, nan_projection, &options), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("projection[5]"), std::string::npos) << last_error();
  options.viewport_width = 10;
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, view, projection, &options), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("options->viewport_width"), std::string::npos) << last_error();
  options.viewport_width = 0;
  options.scene_depth = 0;  // nothing registered
  EXPECT_EQ(sp_visualizer_record_draw_ex(vis_, cmd, view, projection, &options), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("scene_depth 0"), std::string::npos) << last_error();

  // After destroy, every new call detects the dead handle.
  sp_visualizer* dead = vis_;
  EXPECT_EQ(vkDeviceWaitIdle(context_->device()), VK_SUCCESS);
  ASSERT_EQ(sp_visualizer_destroy(dead), SP_OK);
  vis_ = nullptr;
  const sp_display_settings good = defaults();
  options.scene_depth = -1;
  EXPECT_EQ(sp_visualizer_set_display(dead, &good), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("not live"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_set_scene_depth(dead, &depth, 1), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_draw_ex(dead, cmd, view, projection, &options), SP_ERROR_INVALID_ARGUMENT);
}

}  // namespace
}  // namespace sp
