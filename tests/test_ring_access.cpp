// An engine that draws the spots itself (Visualizer::indicator_ring): the
// test plays that engine. Its own pipeline (tests/shaders/ring_points.*,
// written from visualizer.h's layout alone) draws one point per live slot
// straight from the exposed buffer with the exposed indirect arguments; a
// copy of the same buffers read on the host says where the points must be.
// Every live slot's point is drawn, and nothing else: a slot past the
// display's lifetime, still in the ring, is not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include <glm/glm.hpp>

#include "draw/graphics_pipeline.h"
#include "render/render_target.h"
#include "render/view_camera.h"
#include "ring_points.frag.spv.h"
#include "ring_points.vert.spv.h"
#include "soundpaint/visualizer.h"
#include "support/gpu_environment.h"
#include "support/host_commands.h"
#include "support/scene_builder.h"
#include "vk/barriers.h"
#include "vk/buffer.h"
#include "vk/handle.h"
#include "vk/vk_check.h"

namespace sp {
namespace {

constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 120;

struct RingPush {  // ring_points.vert's push constants
  glm::mat4 view_projection;
  std::uint32_t current_step;
  float dt;
  float lifetime;
};

// A continuous source in a closed room; at 16 steps a second a spot lives
// 6 steps (5/16 s < 1/3 s, the display's minimum lifetime, <= 6/16 s),
// and the ring keeps every spot of 12 steps, so that half of what it
// holds is dead.
World room() {
  Scene scene = test::closed_room();
  Config config;
  config.listener_position = glm::vec3(-2.0f, 1.5f, 1.5f);
  config.ray_budget = 40;
  config.dt = 1.0 / 16.0;
  config.indicator_lifetime = 0.25f;
  config.max_indicators = 40 * 64;
  config.layers["concrete"] = {1.0f, 5.0f};
  return make_world(scene, config).value();
}

// The engine's side: its pipeline and the ring's descriptor set.
class RingPainter {
 public:
  RingPainter(const vk::Context& context, const IndicatorRing& ring) {
    VkDescriptorSetLayoutBinding binding{};
    binding.binding = 0;
    binding.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    binding.descriptorCount = 1;
    binding.stageFlags = VK_SHADER_STAGE_VERTEX_BIT;
    VkDescriptorSetLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    layout_info.bindingCount = 1;
    layout_info.pBindings = &binding;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    SP_VK_CHECK(vkCreateDescriptorSetLayout(context.device(), &layout_info, nullptr, &layout));
    layout_ = vk::UniqueDescriptorSetLayout(context.device(), layout);

    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    SP_VK_CHECK(vkCreateDescriptorPool(context.device(), &pool_info, nullptr, &pool));
    pool_ = vk::UniqueDescriptorPool(context.device(), pool);

    VkDescriptorSetAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    alloc.descriptorPool = pool_.get();
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    SP_VK_CHECK(vkAllocateDescriptorSets(context.device(), &alloc, &set_));
    const VkDescriptorBufferInfo buffer{ring.buffer, ring.offset, ring.size};
    VkWriteDescriptorSet write{};
    write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    write.dstSet = set_;
    write.dstBinding = 0;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &buffer;
    vkUpdateDescriptorSets(context.device(), 1, &write, 0, nullptr);

    draw::GraphicsPipelineDesc desc;
    desc.vertex_spirv = sp_spirv_ring_points_vert;
    desc.fragment_spirv = sp_spirv_ring_points_frag;
    desc.set_layout = layout;
    desc.push_constant_bytes = sizeof(RingPush);
    desc.color_format = draw::RenderTarget::kColorFormat;
    desc.depth_format = draw::RenderTarget::kDepthFormat;
    desc.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    desc.depth_test = false;
    desc.depth_write = false;
    desc.name = "engine's ring points";
    pipeline_ = draw::GraphicsPipeline(context, desc);
  }

  void record(VkCommandBuffer cmd, const IndicatorRing& ring, const glm::mat4& view_projection) const {
    const VkViewport viewport{0.0f, 0.0f, float(kWidth), float(kHeight), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {kWidth, kHeight}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout(), 0, 1, &set_, 0, nullptr);
    const RingPush push{view_projection, ring.current_step, ring.dt, ring.lifetime};
    vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof push, &push);
    vkCmdDrawIndirect(cmd, ring.draw_args, ring.draw_args_offset, 1, sizeof(VkDrawIndirectCommand));
  }

 private:
  vk::UniqueDescriptorSetLayout layout_;
  vk::UniqueDescriptorPool pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  draw::GraphicsPipeline pipeline_;
};

struct Pixel {
  int x = 0;
  int y = 0;
};

// The pixel a point at `position` lands on, if it is inside the picture.
std::optional<Pixel> project(const glm::mat4& view_projection, const Vec3& position) {
  const glm::vec4 clip = view_projection * glm::vec4(position.x, position.y, position.z, 1.0f);
  if (clip.w <= 0.0f) return std::nullopt;
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  if (std::abs(ndc.x) >= 1.0f || std::abs(ndc.y) >= 1.0f || ndc.z < 0.0f || ndc.z > 1.0f) return std::nullopt;
  return Pixel{int(std::floor((ndc.x * 0.5f + 0.5f) * kWidth)), int(std::floor((ndc.y * 0.5f + 0.5f) * kHeight))};
}

bool lit(const draw::RgbaImage& image, int x, int y) {
  if (x < 0 || y < 0 || x >= int(image.width) || y >= int(image.height)) return false;
  const std::uint8_t* p = image.at(std::uint32_t(x), std::uint32_t(y));
  return p[0] > 0 || p[1] > 0 || p[2] > 0;
}

// A point on a pixel's edge may land on either side of it.
bool lit_near(const draw::RgbaImage& image, Pixel pixel) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (lit(image, pixel.x + dx, pixel.y + dy)) return true;
  return false;
}

class RingAccess : public test::GpuTest {
 protected:
  void SetUp() override {
    test::GpuTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    context_ = test::GpuEnvironment::context();
    commands_ = std::make_unique<test::HostCommands>(*context_);
    target_ = std::make_unique<draw::RenderTarget>(*context_, kWidth, kHeight);
  }

  std::unique_ptr<Visualizer> visualizer(BackendChoice backend) {
    VisualizerSettings settings;
    settings.backend = backend;
    settings.cpu.threads = 2;
    DrawTarget target;
    target.color_format = draw::RenderTarget::kColorFormat;
    target.depth_format = draw::RenderTarget::kDepthFormat;
    return Visualizer::create(test::host_vulkan_of(*context_), target, room(), settings).value();
  }

  vk::Context* context_ = nullptr;
  std::unique_ptr<test::HostCommands> commands_;
  std::unique_ptr<draw::RenderTarget> target_;
};

TEST_F(RingAccess, AnEngineDrawsEveryLiveSlotFromTheExposedBufferAndNoDeadOne) {
  for (BackendChoice backend : {BackendChoice::Cpu, BackendChoice::Gpu}) {
    SCOPED_TRACE(backend == BackendChoice::Cpu ? "cpu" : "gpu");
    std::unique_ptr<Visualizer> vis = visualizer(backend);
    const World& world = vis->scene().world();
    const draw::ViewCamera camera = draw::make_view_camera(std::nullopt, world, {}, kWidth, kHeight);
    const glm::mat4 view_projection = camera.view_projection();

    std::unique_ptr<RingPainter> painter;
    std::vector<Indicator> slots;
    VkDrawIndirectCommand args{};
    IndicatorRing ring;
    draw::RgbaImage image;
    for (int frame = 0; frame < 16 && vis->steps_run() < 12; ++frame) {
      ASSERT_TRUE(vis->wait_for_simulation().ok());
      VkCommandBuffer cmd = commands_->begin();
      ASSERT_TRUE(vis->record_simulation(cmd, world.config.dt).ok());
      Result<IndicatorRing> exposed = vis->indicator_ring();
      ASSERT_TRUE(exposed.ok()) << exposed.error().message;
      ring = exposed.value();
      ASSERT_NE(ring.buffer, VK_NULL_HANDLE);
      ASSERT_NE(ring.draw_args, VK_NULL_HANDLE);
      EXPECT_EQ(ring.stride, 128u);
      EXPECT_EQ(ring.size, VkDeviceSize{ring.capacity} * 128u);
      EXPECT_EQ(ring.capacity, world.config.max_indicators);
      EXPECT_FLOAT_EQ(ring.lifetime, 1.0f / 3.0f) << "indicator_lifetime 0.25 s, shown at least 1/3 s";
      if (!painter) painter = std::make_unique<RingPainter>(*context_, ring);

      // The host reads the same buffers: its own barrier, as documented.
      vk::Buffer ring_copy(*context_, ring.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback,
                           "ring copy");
      vk::Buffer args_copy(*context_, sizeof args, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::Readback,
                           "draw args copy");
      vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      const VkBufferCopy ring_region{ring.offset, 0, ring.size};
      vkCmdCopyBuffer(cmd, ring.buffer, ring_copy.get(), 1, &ring_region);
      const VkBufferCopy args_region{ring.draw_args_offset, 0, sizeof args};
      vkCmdCopyBuffer(cmd, ring.draw_args, args_copy.get(), 1, &args_region);
      vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);

      const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      target_->begin(cmd, clear);
      painter->record(cmd, ring, view_projection);
      target_->end_and_copy(cmd);
      SP_VK_CHECK(vkEndCommandBuffer(cmd));
      commands_->submit_and_wait({cmd});
      image = target_->read();
      std::memcpy(&args, args_copy.mapped(), sizeof args);
      slots.resize(ring.capacity);
      std::memcpy(slots.data(), ring_copy.mapped(), ring.size);
    }
    ASSERT_EQ(vis->steps_run(), 12u);
    EXPECT_EQ(ring.current_step, 11u);
    EXPECT_EQ(args.vertexCount, 4u) << "a quad as a triangle strip";
    EXPECT_EQ(args.firstVertex, 0u);
    EXPECT_EQ(args.firstInstance, 0u);
    ASSERT_LE(args.instanceCount, ring.capacity);

    // Where the engine's points must be: each filled slot that is live by
    // the documented rule. With the numbers above: steps 6 .. 11.
    std::vector<Pixel> expected;
    std::uint32_t live = 0;
    std::uint32_t dead = 0;
    for (std::uint32_t i = 0; i < args.instanceCount; ++i) {
      const Indicator& slot = slots[i];
      ASSERT_LE(slot.step, ring.current_step);
      const bool is_live = float(ring.current_step - slot.step) * ring.dt < ring.lifetime;
      EXPECT_EQ(is_live, slot.step >= 6u) << "slot " << i << " of step " << slot.step;
      if (!is_live) {
        ++dead;
        continue;
      }
      ++live;
      if (std::optional<Pixel> pixel = project(view_projection, slot.position)) expected.push_back(*pixel);
    }
    EXPECT_GT(dead, 100u) << "the ring must hold dead spots for the test to mean anything";
    EXPECT_GT(expected.size(), 100u) << "live spots in view";

    // Every live spot in view is drawn ...
    std::uint32_t missing = 0;
    for (const Pixel& pixel : expected) missing += lit_near(image, pixel) ? 0u : 1u;
    EXPECT_EQ(missing, 0u) << "of " << expected.size() << " live spots in view";
    // ... and nothing else: every lit pixel is a live spot's.
    std::uint32_t stray = 0;
    std::uint32_t lit_pixels = 0;
    for (int y = 0; y < int(kHeight); ++y)
      for (int x = 0; x < int(kWidth); ++x) {
        if (!lit(image, x, y)) continue;
        ++lit_pixels;
        bool explained = false;
        for (const Pixel& pixel : expected)
          explained = explained || (std::abs(pixel.x - x) <= 1 && std::abs(pixel.y - y) <= 1);
        stray += explained ? 0u : 1u;
      }
    EXPECT_GT(lit_pixels, 0u);
    EXPECT_EQ(stray, 0u) << "lit pixels no live spot explains (dead spots drawn?)";
  }
}

TEST_F(RingAccess, TheRingIsAnErrorBeforeTheFirstSimulation) {
  std::unique_ptr<Visualizer> vis = visualizer(BackendChoice::Gpu);
  Result<IndicatorRing> ring = vis->indicator_ring();
  ASSERT_FALSE(ring.ok());
  EXPECT_EQ(ring.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(ring.error().message.find("record_simulation"), std::string::npos) << ring.error().message;
}

}  // namespace
}  // namespace sp
