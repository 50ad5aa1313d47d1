// The visualizer through the C API (soundpaint_vulkan.h): the test plays a
// C host, lending the shared validation-enabled context's handles as if
// they were its own, recording into command buffers from its own pool and
// submitting them with its own fences. Steps must advance as recorded, the
// scene controls must work on a visualizer's scene, and misuse must be an
// error code with a message. (Pictures are checked by test_visualizer.)
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "soundpaint/soundpaint_vulkan.h"
#include "sp_types.h"
#include "support/gpu_environment.h"
#include "support/host_commands.h"
#include "vk/handle.h"

namespace sp {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
const float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

std::string last_error() { return sp_last_error_message(); }

// A two-sided quad on the plane z = 1 in front of the source and listener.
const std::vector<float> kQuad = {
    -10, -10, 1, 10, -10, 1, 10,  10, 1,  //
    -10, -10, 1, 10, 10,  1, -10, 10, 1,  //
};
const std::uint32_t kQuadLayers[] = {0, 0};
const char* const kLayerNames[] = {"concrete"};

// dt 0.1 s: a frame of 0.25 s holds two steps with 0.05 s carried over.
const char* const kConfig = R"({
  "ray_budget": 64, "max_bounces": 1, "seed": 3, "dt": 0.1,
  "listener": { "position": [0, 0, 0] },
  "sources": [ { "position": [0, 0, 0] } ]
})";

// The C host: its scene, its command pool, frames submitted and waited for.
class CapiHost : public test::GpuTest {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    context_ = test::GpuEnvironment::context();
    ASSERT_EQ(sp_scene_create(kQuad.data(), 2, kQuadLayers, kLayerNames, 1, &scene_), SP_OK) << last_error();
    commands_ = std::make_unique<test::HostCommands>(*context_);
  }
  void TearDown() override {
    if (context_ != nullptr) {
      // What the host must do before destroying a visualizer: finish its work.
      EXPECT_EQ(vkDeviceWaitIdle(context_->device()), VK_SUCCESS);
      EXPECT_EQ(sp_visualizer_destroy(vis_), SP_OK) << last_error();
      EXPECT_EQ(sp_scene_destroy(scene_), SP_OK) << last_error();
      commands_.reset();
    }
    test::GpuTest::TearDown();
  }

  sp_host_vulkan host() const {
    sp_host_vulkan host;
    sp_host_vulkan_init(&host);
    host.instance = context_->instance();
    host.physical_device = context_->physical_device();
    host.device = context_->device();
    host.queue_family = context_->queue_family();
    return host;
  }
  static sp_draw_target target() {
    sp_draw_target target;
    sp_draw_target_init(&target);
    target.color_format = VK_FORMAT_R8G8B8A8_UNORM;
    target.depth_format = VK_FORMAT_D32_SFLOAT;
    return target;
  }
  sp_result create(sp_backend backend) {
    const sp_host_vulkan h = host();
    const sp_draw_target t = target();
    return sp_visualizer_create(&h, &t, scene_, kConfig, backend, &vis_);
  }

  // One frame's simulation, recorded, submitted and waited for; returns the
  // steps record_simulation reported.
  std::uint32_t frame(double dt) {
    VkCommandBuffer cmd = commands_->begin();
    std::uint32_t steps = 12345;
    EXPECT_EQ(sp_visualizer_record_simulation(vis_, cmd, dt, &steps), SP_OK) << last_error();
    EXPECT_EQ(vkEndCommandBuffer(cmd), VK_SUCCESS);
    commands_->submit_and_wait({cmd});
    return steps;
  }

  std::uint64_t steps_run() {
    std::uint64_t steps = 0;
    EXPECT_EQ(sp_visualizer_steps_run(vis_, &steps), SP_OK) << last_error();
    return steps;
  }

  vk::Context* context_ = nullptr;
  sp_scene* scene_ = nullptr;
  sp_visualizer* vis_ = nullptr;
  std::unique_ptr<test::HostCommands> commands_;
};

TEST_F(CapiHost, GpuBackendRecordsTheStepsThatFitTheFrame) {
  ASSERT_EQ(create(SP_BACKEND_GPU), SP_OK) << last_error();
  sp_backend backend = SP_BACKEND_AUTO;
  ASSERT_EQ(sp_visualizer_backend(vis_, &backend), SP_OK);
  EXPECT_EQ(backend, SP_BACKEND_GPU);
  EXPECT_EQ(steps_run(), 0u);

  EXPECT_EQ(frame(0.1), 1u);
  EXPECT_EQ(steps_run(), 1u);
  EXPECT_EQ(frame(0.25), 2u);  // 0.05 s carried
  EXPECT_EQ(steps_run(), 3u);
  EXPECT_EQ(frame(0.0), 0u);
  EXPECT_EQ(steps_run(), 3u);
}

// sp_visualizer_options.max_steps_per_frame: a frame of 0.25 s holds two
// steps of 0.1 s, and a cap of 1 records one and drops the rest (nothing
// carried: the next empty frame records none). Created in a context whose
// log must stay silent, Vulkan validation relayed to it included.
TEST_F(CapiHost, VisualizerOptionsCapTheStepsOfAFrame) {
  std::vector<std::string> messages;
  sp_context_settings settings;
  sp_context_settings_init(&settings);
  settings.flags = SP_CONTEXT_VULKAN_VALIDATION;
  settings.log_user_data = &messages;
  settings.log = [](void* user_data, sp_log_level, const char* message) {
    static_cast<std::vector<std::string>*>(user_data)->emplace_back(message);
  };
  sp_context* context = nullptr;
  ASSERT_EQ(sp_context_create(&settings, &context), SP_OK) << last_error();
  sp_visualizer_options options;
  sp_visualizer_options_init(&options);
  EXPECT_EQ(options.max_steps_per_frame, 4u);  // sp_visualizer_create's
  options.backend = SP_BACKEND_GPU;
  options.max_steps_per_frame = 1;
  const sp_host_vulkan h = host();
  const sp_draw_target t = target();
  ASSERT_EQ(sp_visualizer_create_in(context, &h, &t, scene_, kConfig, &options, &vis_), SP_OK) << last_error();
  EXPECT_EQ(sp_context_destroy(context), SP_OK);  // the visualizer keeps it
  EXPECT_EQ(frame(0.25), 1u);
  EXPECT_EQ(frame(0.0), 0u);
  EXPECT_EQ(steps_run(), 1u);

  sp_visualizer* refused = nullptr;
  options.max_steps_per_frame = 0;
  EXPECT_EQ(sp_visualizer_create_in(nullptr, &h, &t, scene_, kConfig, &options, &refused), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("context is NULL"), std::string::npos) << last_error();
  EXPECT_TRUE(messages.empty()) << messages.front();
}

// The scene controls act on a visualizer's scene like on a simulation's;
// the recorded steps pick the changes up without validation messages.
TEST_F(CapiHost, SceneControlsWorkOnAVisualizer) {
  ASSERT_EQ(create(SP_BACKEND_GPU), SP_OK) << last_error();
  sp_sound_scene* sound = nullptr;
  ASSERT_EQ(sp_visualizer_scene(vis_, &sound), SP_OK) << last_error();
  sp_sound_scene* again = nullptr;
  ASSERT_EQ(sp_visualizer_scene(vis_, &again), SP_OK);
  EXPECT_EQ(again, sound);
  EXPECT_EQ(frame(0.1), 1u);

  sp_source_desc desc;
  sp_source_desc_init(&desc);
  desc.position[0] = 2.0f;
  desc.color[0] = 0.0f;  // cyan, its own
  desc.color[1] = 1.0f;
  desc.color[2] = 1.0f;
  std::uint32_t id = 0;
  ASSERT_EQ(sp_sound_scene_add_source(sound, &desc, &id), SP_OK) << last_error();
  EXPECT_EQ(id, 1u);
  ASSERT_EQ(sp_sound_scene_move_source(sound, id, -2.0f, 0.0f, 0.0f), SP_OK) << last_error();
  std::uint32_t shot = 0;
  ASSERT_EQ(sp_sound_scene_emit(sound, &desc, 0.15, &shot), SP_OK) << last_error();
  ASSERT_EQ(sp_sound_scene_set_listener(sound, 0.0f, 0.5f, 0.0f), SP_OK) << last_error();
  EXPECT_EQ(frame(0.2), 2u);
  ASSERT_EQ(sp_sound_scene_remove_source(sound, id), SP_OK) << last_error();
  EXPECT_EQ(sp_sound_scene_move_source(sound, id, 0.0f, 0.0f, 0.0f), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(frame(0.2), 2u);
  int live = 1;
  ASSERT_EQ(sp_sound_scene_has_source(sound, shot, &live), SP_OK);
  EXPECT_EQ(live, 0);  // the one-shot ended
  EXPECT_EQ(steps_run(), 5u);
}

// The CPU backend runs each step on worker threads and hands it over in the
// next record_simulation; sp_visualizer_wait makes the hand-over certain.
TEST_F(CapiHost, CpuBackendHandsAStepOverAfterWaiting) {
  ASSERT_EQ(create(SP_BACKEND_CPU), SP_OK) << last_error();
  sp_backend backend = SP_BACKEND_AUTO;
  ASSERT_EQ(sp_visualizer_backend(vis_, &backend), SP_OK);
  EXPECT_EQ(backend, SP_BACKEND_CPU);
  EXPECT_EQ(frame(0.1), 0u);  // started, not finished
  ASSERT_EQ(sp_visualizer_wait(vis_), SP_OK) << last_error();
  EXPECT_EQ(frame(0.0), 1u);
  EXPECT_EQ(steps_run(), 1u);
}

TEST_F(CapiHost, CreateRejectsBadHostObjectsAndFormats) {
  const sp_draw_target good_target = target();
  EXPECT_EQ(sp_visualizer_create(nullptr, &good_target, scene_, kConfig, SP_BACKEND_GPU, &vis_),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("host is NULL"), std::string::npos) << last_error();

  sp_host_vulkan no_device = host();
  no_device.device = VK_NULL_HANDLE;
  EXPECT_EQ(sp_visualizer_create(&no_device, &good_target, scene_, kConfig, SP_BACKEND_GPU, &vis_),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("VkDevice"), std::string::npos) << last_error();

  sp_host_vulkan no_family = host();
  no_family.queue_family = VK_QUEUE_FAMILY_IGNORED;
  EXPECT_EQ(sp_visualizer_create(&no_family, &good_target, scene_, kConfig, SP_BACKEND_GPU, &vis_),
            SP_ERROR_INVALID_ARGUMENT);

  const sp_host_vulkan good_host = host();
  sp_draw_target no_color = target();
  no_color.color_format = VK_FORMAT_UNDEFINED;
  EXPECT_EQ(sp_visualizer_create(&good_host, &no_color, scene_, kConfig, SP_BACKEND_GPU, &vis_),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("color_format"), std::string::npos) << last_error();

  sp_draw_target bad_samples = target();
  bad_samples.samples = static_cast<VkSampleCountFlagBits>(3);
  EXPECT_EQ(sp_visualizer_create(&good_host, &bad_samples, scene_, kConfig, SP_BACKEND_GPU, &vis_),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_create(&good_host, &good_target, scene_, R"({ "dt": -1 })", SP_BACKEND_GPU, &vis_),
            SP_ERROR_INVALID_CONFIG);
  EXPECT_EQ(vis_, nullptr);
}

TEST_F(CapiHost, RecordCallsRejectMisuse) {
  ASSERT_EQ(create(SP_BACKEND_GPU), SP_OK) << last_error();
  VkCommandBuffer cmd = commands_->begin();  // nothing is recorded into it below
  std::uint32_t steps = 77;
  EXPECT_EQ(sp_visualizer_record_simulation(vis_, VK_NULL_HANDLE, 0.1, &steps), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("cmd"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_record_simulation(vis_, cmd, std::numeric_limits<double>::quiet_NaN(), &steps),
            SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_simulation(vis_, cmd, -0.1, &steps), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(steps, 77u);

  // Drawing before any simulation was recorded would read garbage.
  EXPECT_EQ(sp_visualizer_record_draw(vis_, cmd, kIdentity, kIdentity, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("record_simulation"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_record_draw(vis_, VK_NULL_HANDLE, kIdentity, kIdentity, nullptr), SP_ERROR_INVALID_ARGUMENT);
  float nan_view[16];
  std::copy(std::begin(kIdentity), std::end(kIdentity), nan_view);
  nan_view[12] = kNan;
  EXPECT_EQ(sp_visualizer_record_draw(vis_, cmd, nan_view, kIdentity, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("view[12] is not finite"), std::string::npos) << last_error();
  EXPECT_EQ(sp_visualizer_record_draw(vis_, cmd, kIdentity, nan_view, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_draw(vis_, cmd, nullptr, kIdentity, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_draw(vis_, cmd, kIdentity, nullptr, nullptr), SP_ERROR_INVALID_ARGUMENT);
  const VkRect2D empty{{0, 0}, {0, 16}};
  EXPECT_EQ(sp_visualizer_record_draw(vis_, cmd, kIdentity, kIdentity, &empty), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_steps_run(vis_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_backend(vis_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_scene(vis_, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(steps_run(), 0u);
}

TEST_F(CapiHost, UseAfterDestroyIsDetected) {
  ASSERT_EQ(create(SP_BACKEND_GPU), SP_OK) << last_error();
  sp_sound_scene* sound = nullptr;
  ASSERT_EQ(sp_visualizer_scene(vis_, &sound), SP_OK);
  EXPECT_EQ(frame(0.1), 1u);
  sp_visualizer* dead = vis_;
  ASSERT_EQ(sp_visualizer_destroy(dead), SP_OK) << last_error();
  vis_ = nullptr;

  EXPECT_EQ(sp_visualizer_destroy(dead), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("visualizer handle is not live"), std::string::npos) << last_error();
  VkCommandBuffer cmd = commands_->begin();
  std::uint64_t steps = 0;
  EXPECT_EQ(sp_visualizer_record_simulation(dead, cmd, 0.1, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_record_draw(dead, cmd, kIdentity, kIdentity, nullptr), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_wait(dead), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_visualizer_steps_run(dead, &steps), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sp_sound_scene_set_listener(sound, 0, 0, 0), SP_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("scene handle is not live"), std::string::npos) << last_error();
}

}  // namespace
}  // namespace sp
