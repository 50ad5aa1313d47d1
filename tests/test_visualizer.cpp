// The Visualizer on a device it does not own: the test plays the host,
// lending the shared validation-enabled context's handles, recording into
// its own command buffers and submitting them itself. The pictures of the
// GPU and CPU backends must agree (the backends are bit-identical), frames
// in flight must be valid Vulkan, and misuse must be an error.
#include <gtest/gtest.h>
#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <utility>

#include <glm/glm.hpp>

#include "render/render_target.h"
#include "render/view_camera.h"
#include "soundpaint/visualizer.h"
#include "sp_types.h"
#include "support/gpu_environment.h"
#include "support/host_commands.h"
#include "support/render_checks.h"
#include "support/scene_builder.h"
#include "vk/handle.h"
#include "vk/vk_check.h"

namespace sp {
namespace {

constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 120;

World mirror_room() {
  Scene scene = test::closed_room();
  Config config;
  config.listener_position = glm::vec3(-2.0f, 1.5f, 1.5f);
  config.ray_budget = 150;
  config.layers["concrete"] = {1.0f, 5.0f};
  return make_world(scene, config).value();
}

HostVulkan host_of(const vk::Context& context) { return test::host_vulkan_of(context); }

DrawTarget target_formats() {
  DrawTarget target;
  target.color_format = draw::RenderTarget::kColorFormat;
  target.depth_format = draw::RenderTarget::kDepthFormat;
  return target;
}

// The host's side: a command pool, a render target, and frames recorded,
// submitted and waited for as a renderer would.
class Host : public test::GpuTest {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    context_ = test::GpuEnvironment::context();
    commands_ = std::make_unique<test::HostCommands>(*context_);
    target_ = std::make_unique<draw::RenderTarget>(*context_, kWidth, kHeight);
    camera_ = draw::make_view_camera(std::nullopt, mirror_room(), {}, kWidth, kHeight);
  }

  std::unique_ptr<Visualizer> visualizer(BackendChoice backend, World world = mirror_room()) {
    VisualizerSettings settings;
    settings.backend = backend;
    settings.cpu.threads = 2;
    return Visualizer::create(host_of(*context_), target_formats(), std::move(world), settings).value();
  }

  VkCommandBuffer begin() { return commands_->begin(); }
  void submit_and_wait(std::initializer_list<VkCommandBuffer> cmds) { commands_->submit_and_wait(cmds); }

  // One frame: simulation, then the host's rendering with the indicators
  // drawn into it, then the read-back.
  draw::RgbaImage frame(Visualizer& visualizer, double dt) {
    VkCommandBuffer cmd = begin();
    EXPECT_TRUE(visualizer.record_simulation(cmd, dt).ok());
    const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    target_->begin(cmd, clear);
    const VkRect2D area{{0, 0}, {kWidth, kHeight}};
    EXPECT_TRUE(visualizer.record_draw(cmd, camera_.view, camera_.projection, &area).ok());
    target_->end_and_copy(cmd);
    SP_VK_CHECK(vkEndCommandBuffer(cmd));
    submit_and_wait({cmd});
    return target_->read();
  }

  vk::Context* context_ = nullptr;
  std::unique_ptr<test::HostCommands> commands_;
  std::unique_ptr<draw::RenderTarget> target_;
  draw::ViewCamera camera_;
};

// Host allocation callbacks that count what passes through them.
struct CountingAllocator {
  std::atomic<int> live{0};
  std::atomic<int> total{0};

  static void* allocate(void* user, std::size_t size, std::size_t alignment, VkSystemAllocationScope) {
    alignment = std::max<std::size_t>(alignment, alignof(std::max_align_t));
    void* p = std::aligned_alloc(alignment, (std::max<std::size_t>(size, 1) + alignment - 1) / alignment * alignment);
    if (p != nullptr) {
      static_cast<CountingAllocator*>(user)->live += 1;
      static_cast<CountingAllocator*>(user)->total += 1;
    }
    return p;
  }
  static void* reallocate(void* user, void* old, std::size_t size, std::size_t alignment,
                          VkSystemAllocationScope scope) {
    if (old == nullptr) return allocate(user, size, alignment, scope);
    if (size == 0) {
      release(user, old);
      return nullptr;
    }
    void* p = allocate(user, size, alignment, scope);
    if (p == nullptr) return nullptr;
    std::memcpy(p, old, std::min(size, malloc_usable_size(old)));
    release(user, old);
    return p;
  }
  static void release(void* user, void* p) {
    if (p == nullptr) return;
    static_cast<CountingAllocator*>(user)->live -= 1;
    std::free(p);
  }

  VkAllocationCallbacks callbacks() {
    VkAllocationCallbacks c{};
    c.pUserData = this;
    c.pfnAllocation = allocate;
    c.pfnReallocation = reallocate;
    c.pfnFree = release;
    return c;
  }
};

std::size_t coloured_pixels(const draw::RgbaImage& image) { return test::count_pixels(image, test::is_saturated); }

TEST_F(Host, GpuAndCpuBackendsDrawTheSamePicture) {
  const double dt = mirror_room().config.dt;
  auto gpu = visualizer(BackendChoice::Gpu);
  auto cpu = visualizer(BackendChoice::Cpu);
  ASSERT_EQ(gpu->backend(), Backend::Gpu);
  ASSERT_EQ(cpu->backend(), Backend::Cpu);
  // Overlapping spots of one source blend alike in any order without their
  // halo, which the spot drawn last lays over the others; the GPU's ring
  // order is not fixed.
  DisplaySettings plain = gpu->display();
  plain.outline = false;
  ASSERT_TRUE(gpu->set_display(plain).ok());
  ASSERT_TRUE(cpu->set_display(plain).ok());

  // Steps 0..4 on each. The CPU backend hands a step over one frame after
  // starting it; waiting makes each hand-over certain for the comparison.
  draw::RgbaImage gpu_image;
  for (int n = 0; n < 5; ++n) gpu_image = frame(*gpu, dt);
  draw::RgbaImage cpu_image = frame(*cpu, dt);
  EXPECT_EQ(coloured_pixels(cpu_image), 0u);  // nothing handed over yet
  for (int n = 0; n < 5; ++n) {
    ASSERT_TRUE(cpu->wait_for_simulation().ok());
    cpu_image = frame(*cpu, dt);
  }
  EXPECT_EQ(gpu->steps_run(), 5u);
  EXPECT_EQ(cpu->steps_run(), 5u);
  EXPECT_GT(coloured_pixels(gpu_image), 200u);
  // Same indicators but for the rare ray whose path diverged (division and
  // sqrt round as each device likes, test_gpu_parity.cpp), which changes a
  // spot or two, each at least 16 px across: up to 2 % of the pixels.
  EXPECT_LT(test::differing_pixels(gpu_image, cpu_image, 8, nullptr), kWidth * kHeight / 50);
}

// mirror_room's source in one burst, at step 0, in steps of 1/16 s (exact
// in binary), of 0.3 s spots drawn at full opacity while live: the display
// shows them for its minimum lifetime, 1/3 s (SP_MIN_DISPLAY_LIFETIME).
World burst_room() {
  Scene scene = test::closed_room();
  scene.sources[0].duration = 0.01;
  scene.sources[0].interval = 1000.0;
  Config config = mirror_room().config;
  config.ray_budget = 600;
  config.dt = 1.0 / 16.0;
  config.indicator_lifetime = 0.3f;
  config.display.min_opacity = 1.0f;
  return make_world(scene, config).value();
}

// Both visualizers draw a spot while it is live (sp_indicator_live), as
// live_indicators() returns it: 5/16 = 0.3125 s after the burst, and no
// longer 0.375 s after it.
TEST_F(Host, ASpotIsDrawnForTheDisplaysLifetimeThenNot) {
  for (BackendChoice choice : {BackendChoice::Cpu, BackendChoice::Gpu}) {
    auto vis = visualizer(choice, burst_room());
    const double dt = vis->scene().world().config.dt;
    draw::RgbaImage image;
    // The CPU backend hands a step over one frame after starting it.
    for (int n = 0; n < 10 && vis->steps_run() < 6; ++n) {
      ASSERT_TRUE(vis->wait_for_simulation().ok());
      image = frame(*vis, dt);
    }
    ASSERT_EQ(vis->steps_run(), 6u);
    EXPECT_GT(coloured_pixels(image), 50u) << "the burst is 0.3125 s old: live and drawn";
    ASSERT_TRUE(vis->wait_for_simulation().ok());
    image = frame(*vis, dt);
    ASSERT_EQ(vis->steps_run(), 7u);
    EXPECT_EQ(coloured_pixels(image), 0u) << "the burst is 0.375 s old: past the display's lifetime";
  }
}

// record_totals: what a host's panel shows. The totals after some frames
// are those of a simulator of the same backend run for the same steps.
TEST_F(Host, TotalsAreThoseOfASimulatorRunForTheSameSteps) {
  for (BackendChoice choice : {BackendChoice::Cpu, BackendChoice::Gpu}) {
    auto vis = visualizer(choice);
    const double dt = vis->scene().world().config.dt;
    vk::Buffer buffer(*context_, sizeof(SimulationTotals), VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback,
                      "totals");
    for (int frame = 0; frame < 6; ++frame) {
      VkCommandBuffer cmd = begin();
      ASSERT_TRUE(vis->record_simulation(cmd, dt).ok());
      ASSERT_TRUE(vis->record_totals(cmd, buffer.get(), 0).ok());
      SP_VK_CHECK(vkEndCommandBuffer(cmd));
      submit_and_wait({cmd});
      // The CPU backend hands a step over once its worker has finished it:
      // wait for that, so the count does not depend on the machine's speed.
      ASSERT_TRUE(vis->wait_for_simulation().ok());
    }
    SimulationTotals totals;
    std::memcpy(&totals, buffer.mapped(), sizeof totals);
    ASSERT_GE(totals.steps, 4u);
    EXPECT_EQ(totals.steps, vis->steps_run());
    auto sim = make_simulator(mirror_room(), choice == BackendChoice::Cpu ? Backend::Cpu : Backend::Gpu);
    for (std::uint64_t n = 0; n < totals.steps; ++n) ASSERT_TRUE(sim->step().ok());
    const SimulationStats stats = sim->stats().value();
    EXPECT_EQ(totals.casts, stats.casts);
    EXPECT_EQ(totals.rays_emitted, stats.rays_emitted);
    EXPECT_EQ(totals.indicators, stats.indicators);
    EXPECT_GT(totals.ring_filled, 0u);
    EXPECT_LE(totals.ring_filled, vis->scene().world().config.max_indicators);
    EXPECT_FALSE(vis->record_totals(VK_NULL_HANDLE, buffer.get(), 0).ok());
    EXPECT_FALSE(vis->record_totals(begin(), VK_NULL_HANDLE, 0).ok());
  }
}

// stage_timings: where a frame's simulation time went, for a host's panel.
TEST_F(Host, StageTimingsAreMeasuredOnceAFrameHasRun) {
  for (BackendChoice choice : {BackendChoice::Cpu, BackendChoice::Gpu}) {
    auto vis = visualizer(choice);
    EXPECT_FALSE(vis->stage_timings().measured);
    const double dt = vis->scene().world().config.dt;
    for (int frame = 0; frame < 4; ++frame) {
      VkCommandBuffer cmd = begin();
      ASSERT_TRUE(vis->record_simulation(cmd, 2.0 * dt).ok());
      SP_VK_CHECK(vkEndCommandBuffer(cmd));
      submit_and_wait({cmd});
      ASSERT_TRUE(vis->wait_for_simulation().ok());
    }
    const StageTimings t = vis->stage_timings();
    ASSERT_TRUE(t.measured);
    if (choice == BackendChoice::Gpu) {
      EXPECT_EQ(t.steps, 2u);  // the newest frame's two steps
      EXPECT_GT(t.trace_ms, 0.0);
      EXPECT_GT(t.resolve_ms, 0.0);
      for (double ms : {t.emit_ms, t.prepare_ms, t.admit_ms}) EXPECT_GE(ms, 0.0);
      // Each stage is a part of the frame: none can exceed a whole second.
      EXPECT_LT(t.emit_ms + t.trace_ms + t.resolve_ms + t.prepare_ms + t.admit_ms, 1000.0);
    } else {
      EXPECT_GT(t.cpu_step_ms, 0.0);
    }
  }
}

TEST_F(Host, FrameTimesBecomeFixedStepsCappedPerFrame) {
  auto gpu = visualizer(BackendChoice::Gpu);
  const double dt = mirror_room().config.dt;
  std::uint32_t steps[4] = {};
  VkCommandBuffer cmd = begin();
  steps[0] = gpu->record_simulation(cmd, 0.5 * dt).value();
  steps[1] = gpu->record_simulation(cmd, 0.5 * dt).value();
  steps[2] = gpu->record_simulation(cmd, 100 * dt).value();  // a hitch: at most 4
  steps[3] = gpu->record_simulation(cmd, 0.0).value();
  SP_VK_CHECK(vkEndCommandBuffer(cmd));
  submit_and_wait({cmd});
  EXPECT_EQ(steps[0], 0u);
  EXPECT_EQ(steps[1], 1u);
  EXPECT_EQ(steps[2], 4u);
  EXPECT_EQ(steps[3], 0u);  // the hitch's excess was dropped, not carried
  EXPECT_EQ(gpu->steps_run(), 5u);
}

TEST_F(Host, TwoFramesInFlightRecordedBeforeEitherRuns) {
  for (BackendChoice backend : {BackendChoice::Gpu, BackendChoice::Cpu}) {
    auto vis = visualizer(backend);
    const double dt = mirror_room().config.dt;
    VkCommandBuffer first = begin();
    ASSERT_TRUE(vis->record_simulation(first, dt).ok());
    SP_VK_CHECK(vkEndCommandBuffer(first));
    ASSERT_TRUE(vis->wait_for_simulation().ok());
    // A moving source between the frames changes only what the second records.
    ASSERT_TRUE(vis->scene().move_source(0, {1.0f, 1.0f, 1.0f}).ok());
    VkCommandBuffer second = begin();
    ASSERT_TRUE(vis->record_simulation(second, dt).ok());
    SP_VK_CHECK(vkEndCommandBuffer(second));
    submit_and_wait({first, second});
    EXPECT_GE(vis->steps_run(), 1u);
  }
}

// Both backends, each object soundpaint makes (vk/objects.h passes the
// context's allocator to every create and destroy): the host's callbacks
// hold allocations while the visualizer lives and none once it is gone, and
// the validation layer finds no create/destroy pair whose allocators differ.
TEST_F(Host, HostAllocatorServesEveryObjectAndAPipelineCacheIsAccepted) {
  VkPipelineCacheCreateInfo cache_info{};
  cache_info.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO;
  VkPipelineCache cache = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreatePipelineCache(context_->device(), &cache_info, nullptr, &cache));
  for (BackendChoice backend : {BackendChoice::Gpu, BackendChoice::Cpu}) {
    SCOPED_TRACE(backend == BackendChoice::Gpu ? "GPU backend" : "CPU backend");
    CountingAllocator counter;
    const VkAllocationCallbacks callbacks = counter.callbacks();
    HostVulkan host = host_of(*context_);
    host.allocator = &callbacks;
    host.pipeline_cache = cache;
    VisualizerSettings settings;
    settings.backend = backend;
    settings.cpu.threads = 2;
    {
      auto vis = Visualizer::create(host, target_formats(), mirror_room(), settings).value();
      const int created = counter.live.load();
      EXPECT_GT(created, 0);  // the objects soundpaint made are alive
      // The CPU backend hands a step over only once its worker has finished
      // it; waiting makes that certain on a loaded machine (CI saw 0 pixels).
      for (int n = 0; n < 2; ++n) {
        frame(*vis, mirror_room().config.dt);
        ASSERT_TRUE(vis->wait_for_simulation().ok());
      }
      EXPECT_GT(coloured_pixels(frame(*vis, mirror_room().config.dt)), 0u);
      EXPECT_GE(counter.live.load(), created);  // nothing soundpaint made was freed elsewhere
    }
    EXPECT_GT(counter.total.load(), 0);
    EXPECT_EQ(counter.live.load(), 0);  // and every one was freed through the callbacks
  }
  vkDestroyPipelineCache(context_->device(), cache, nullptr);
}

TEST_F(Host, MisuseIsAnErrorNotACrash) {
  HostVulkan host = host_of(*context_);
  World world = mirror_room();
  HostVulkan no_device = host;
  no_device.device = VK_NULL_HANDLE;
  EXPECT_EQ(Visualizer::create(no_device, target_formats(), world).error().code, ErrorCode::InvalidArgument);
  HostVulkan no_family = host;
  no_family.queue_family = VK_QUEUE_FAMILY_IGNORED;
  EXPECT_FALSE(Visualizer::create(no_family, target_formats(), world).ok());
  HostVulkan bad_family = host;
  bad_family.queue_family = 99;
  EXPECT_FALSE(Visualizer::create(bad_family, target_formats(), world).ok());
  DrawTarget no_colour = target_formats();
  no_colour.color_format = VK_FORMAT_UNDEFINED;
  EXPECT_NE(Visualizer::create(host, no_colour, world).error().message.find("color_format"), std::string::npos);
  DrawTarget odd_samples = target_formats();
  odd_samples.samples = static_cast<VkSampleCountFlagBits>(3);
  EXPECT_FALSE(Visualizer::create(host, odd_samples, world).ok());
  VisualizerSettings zero_steps;
  zero_steps.max_steps_per_frame = 0;
  EXPECT_FALSE(Visualizer::create(host, target_formats(), world, zero_steps).ok());
  // A player's config whose worst step could not fit the host's budget.
  for (BackendChoice backend : {BackendChoice::Gpu, BackendChoice::Cpu}) {
    World greedy = world;
    greedy.config.ray_budget = 1u << 20;
    greedy.config.max_bounces = 64;
    VisualizerSettings budget;
    budget.backend = backend;
    budget.cpu.memory_budget_bytes = std::uint64_t{256} << 20;
    Result<std::unique_ptr<Visualizer>> too_big = Visualizer::create(host, target_formats(), greedy, budget);
    ASSERT_FALSE(too_big.ok());
    EXPECT_EQ(too_big.error().code, ErrorCode::LimitExceeded);
    EXPECT_NE(too_big.error().message.find("ray_budget"), std::string::npos) << too_big.error().message;
  }

  // A device created without the features soundpaint needs.
  VkPhysicalDeviceVulkan13Features without{};
  without.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  without.dynamicRendering = VK_TRUE;
  HostVulkan lacking = host;
  lacking.enabled_features = &without;
  Result<std::unique_ptr<Visualizer>> refused = Visualizer::create(lacking, target_formats(), world);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::Vulkan);
  EXPECT_NE(refused.error().message.find("synchronization2"), std::string::npos) << refused.error().message;
  EXPECT_EQ(refused.error().message.find("dynamicRendering"), std::string::npos) << refused.error().message;

  auto vis = visualizer(BackendChoice::Gpu);
  VkCommandBuffer cmd = begin();
  EXPECT_FALSE(vis->record_draw(cmd, camera_.view, camera_.projection).ok());  // before any simulation
  EXPECT_FALSE(vis->record_simulation(VK_NULL_HANDLE, 0.01).ok());
  EXPECT_FALSE(vis->record_simulation(cmd, -1.0).ok());
  EXPECT_FALSE(vis->record_simulation(cmd, std::nan("")).ok());
  glm::mat4 nan_view = camera_.view;
  nan_view[0][0] = std::nanf("");
  ASSERT_TRUE(vis->record_simulation(cmd, 0.0).ok());
  EXPECT_FALSE(vis->record_draw(cmd, nan_view, camera_.projection).ok());
  // The viewport travels to the shaders as 16-bit halves: each misuse named.
  const struct {
    const char* names;
    VkRect2D area;
    bool with_area;
    DrawOptions options;
  } bad_viewports[] = {
      {"offset must not be negative", {{-1, 0}, {8, 8}}, true, {}},
      {"viewport_x and viewport_y must be 0 or the area's offset", {{4, 4}, {8, 8}}, true, {.viewport_x = 5}},
      {"at most 65535 pixels a side", {}, false, {.viewport_width = 70000, .viewport_height = 8}},
      {"viewport_x and viewport_y must be at most 65535", {}, false, {.viewport_y = 70000}},
  };
  for (const auto& bad : bad_viewports) {
    DrawOptions options = bad.options;
    if (bad.with_area) options.area = &bad.area;
    const Result<bool> refused_draw = vis->record_draw(cmd, camera_.view, camera_.projection, options);
    ASSERT_FALSE(refused_draw.ok()) << bad.names;
    EXPECT_EQ(refused_draw.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(refused_draw.error().message.find(bad.names), std::string::npos) << refused_draw.error().message;
  }
  SP_VK_CHECK(vkEndCommandBuffer(cmd));
  submit_and_wait({cmd});
}

}  // namespace
}  // namespace sp
