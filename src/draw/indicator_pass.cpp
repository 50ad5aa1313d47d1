#include "draw/indicator_pass.h"

#include <algorithm>
#include <string>

#include "arrow.frag.spv.h"
#include "arrow.vert.spv.h"
#include "display/categories.h"
#include "display_prepass.comp.spv.h"
#include "draw/draw_layout_checks.h"
#include "indicator.frag.spv.h"
#include "indicator.vert.spv.h"
#include "indicator_clip.frag.spv.h"
#include "indicator_clip.vert.spv.h"
#include "soundpaint/result.h"
#include "sp_shapes.h"
#include "vk/barriers.h"

namespace sp::draw {
namespace {

constexpr VkBufferUsageFlags kTable = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
// Scene depth views a pass can sample: a swapchain's depth images, or one.
constexpr std::uint32_t kSceneDepthCapacity = 8;
// An off-screen arrow's shape's diameter on screen (its head, marks and
// halo make it 2.6 times as long): well above the shapes' minimum size
// (SP_SHAPE_MIN_PIXELS), to be read at a glance at the edge of sight.
constexpr float kArrowPixels = 44.0f;
// In a smaller viewport (under 587 px on its shorter side) the arrow
// shrinks to this share of that side, down to SP_SHAPE_MIN_PIXELS: then the
// ring holds two places at the top and bottom, for arrows in nearly the
// same direction to stack (sp_arrows.h), from 360 px up.
constexpr float kArrowViewportShare = 0.075f;

float arrow_pixels(glm::vec2 viewport) {
  return std::clamp(kArrowViewportShare * std::min(viewport.x, viewport.y), SP_SHAPE_MIN_PIXELS, kArrowPixels);
}
constexpr std::uint32_t kPrepassGroup = 64;

std::uint32_t groups(std::uint32_t threads) { return (threads + kPrepassGroup - 1) / kPrepassGroup; }

// Two pixel counts in one push-constant word, x | y << 16 (IndicatorPush):
// record_draw refuses viewports beyond kMaxViewportPixels.
std::uint32_t pack_pixels(glm::uvec2 v) {
  const glm::uvec2 c = glm::min(v, glm::uvec2(kMaxViewportPixels));
  return c.x | (c.y << 16);
}

GraphicsPipelineDesc indicator_desc(const DrawTarget& target, VkDescriptorSetLayout set) {
  GraphicsPipelineDesc desc;
  desc.vertex_spirv = sp_spirv_indicator_vert;
  desc.fragment_spirv = sp_spirv_indicator_frag;
  desc.set_layout = set;
  desc.push_constant_bytes = sizeof(shader::IndicatorPush);
  desc.color_format = target.color_format;
  desc.depth_format = target.depth_format;
  desc.stencil_format = target.stencil_format;
  desc.samples = target.samples;
  desc.depth_compare = target.depth_compare;
  // Tested against the scene's depth but not written: overlapping spots
  // blend instead of hiding one another.
  desc.blend = Blend::Alpha;
  desc.depth_write = false;
  desc.name = "indicator pass";
  desc.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;  // SP_INDICATOR_QUAD_VERTICES
  return desc;
}

}  // namespace

IndicatorPass::IndicatorPass(const vk::Context& context, const DrawTarget& target, std::uint32_t source_capacity)
    : context_(&context),
      source_capacity_(std::max(source_capacity, 1u)),
      category_capacity_(source_capacity_ + kBuiltinCategoryCount),
      bindings_(context, SP_DRAW_BINDING_COUNT, "indicator pass bindings"),
      depth_sets_(context, kSceneDepthCapacity),
      sources_(context, sizeof(shader::DisplaySource) * source_capacity_, kTable, vk::MemoryUsage::DeviceLocal,
               "display sources"),
      source_live_(context, sizeof(std::uint32_t) * source_capacity_, kTable, vk::MemoryUsage::DeviceLocal,
                   "display source live counts"),
      source_cues_(context, sizeof(std::uint32_t) * source_capacity_, kTable, vk::MemoryUsage::DeviceLocal,
                   "display source cues"),
      cues_(source_capacity_, 0u),
      categories_(context, sizeof(std::uint32_t) * SP_CATEGORY_STRIDE * category_capacity_, kTable,
                  vk::MemoryUsage::DeviceLocal, "display category caps") {
  bindings_.bind(context, SP_DRAW_BINDING_SOURCES, sources_);
  bindings_.bind(context, SP_DRAW_BINDING_SOURCE_LIVE, source_live_);
  bindings_.bind(context, SP_DRAW_BINDING_SOURCE_CUES, source_cues_);
  bindings_.bind(context, SP_DRAW_BINDING_CATEGORIES, categories_);
  ensure_visible_capacity(1);

  GraphicsPipelineDesc desc = indicator_desc(target, bindings_.layout());
  pipeline_ = GraphicsPipeline(context, desc);
  desc.vertex_spirv = sp_spirv_indicator_clip_vert;
  desc.fragment_spirv = sp_spirv_indicator_clip_frag;
  desc.set_layout_1 = depth_sets_.layout();
  desc.name = "indicator pass, clipped";
  clip_pipeline_ = GraphicsPipeline(context, desc);

  GraphicsPipelineDesc arrows = indicator_desc(target, bindings_.layout());
  arrows.vertex_spirv = sp_spirv_arrow_vert;
  arrows.fragment_spirv = sp_spirv_arrow_frag;
  arrows.push_constant_bytes = sizeof(shader::ArrowPush);
  arrows.depth_test = false;  // an overlay on the picture, never behind the scene
  arrows.name = "off-screen arrows";
  arrows_ = GraphicsPipeline(context, arrows);

  prepass_ = vk::ComputePipeline(context, sp_spirv_display_prepass_comp, bindings_.layout(),
                                 sizeof(shader::DisplayPrepassPush), "display prepass");
}

void IndicatorPass::ensure_visible_capacity(std::uint32_t slots) {
  if (slots <= ring_capacity_ && visible_.get() != VK_NULL_HANDLE) return;
  ring_capacity_ = std::max(slots, 1u);
  visible_ = vk::Buffer(*context_, sizeof(std::uint32_t) * ring_capacity_, kTable, vk::MemoryUsage::DeviceLocal,
                        "display visible slots");
  bindings_.bind(*context_, SP_DRAW_BINDING_VISIBLE, visible_);
}

void IndicatorPass::bind(const gpu::IndicatorView& indicators) {
  if (indicators.ring == VK_NULL_HANDLE || indicators.draw_args == VK_NULL_HANDLE)
    throw Exception(ErrorCode::InvalidArgument, "indicator pass: the indicator view has no ring or draw arguments");
  ensure_visible_capacity(indicators.ring_capacity);
  bindings_.bind(*context_, SP_DRAW_BINDING_RING, indicators.ring);
  bindings_.bind(*context_, SP_DRAW_BINDING_DRAW_ARGS, indicators.draw_args, indicators.draw_args_offset,
                 sizeof(VkDrawIndirectCommand));
  bound_draw_args_ = indicators.draw_args;
  bound_draw_args_offset_ = indicators.draw_args_offset;
}

void IndicatorPass::record_prepare(VkCommandBuffer cmd, std::span<const shader::DisplaySource> sources,
                                   const DisplayFrame& frame, bool graphics_queue) {
  if (sources.size() > source_capacity_)
    throw Exception(ErrorCode::LimitExceeded, "indicator pass: " + std::to_string(sources.size()) +
                                                  " sources, more than the " + std::to_string(source_capacity_) +
                                                  " it was made for");
  const VkPipelineStageFlags2 draw_stages = graphics_queue ? VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT : 0;
  // WAR: earlier frames' draws and prepasses are done with the tables; RAW:
  // the ring's writes (the step's kernels, or the host's upload) reach the
  // prepass.
  vk::memory_barrier(cmd, draw_stages | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  if (!sources.empty()) vk::record_update(cmd, sources_, 0, sources.data(), sources.size_bytes());
  if (cues_changed_) {
    vk::record_update(cmd, source_cues_, 0, cues_.data(), cues_.size() * sizeof(std::uint32_t));
    cues_changed_ = false;
  }
  // RAW: the tables reach the prepass and the draw.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | draw_stages, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);

  const bool caps = frame.settings.max_per_category.has_value();
  shader::DisplayPrepassPush push{};
  push.current_step = frame.current_step;
  push.dt = frame.dt;
  push.lifetime = frame.lifetime;
  push.category_count = std::min(frame.category_count, category_capacity_);
  push.max_per_category = caps ? *frame.settings.max_per_category : 0xFFFFFFFFu;
  push.ring_capacity = ring_capacity_;
  push.inv_indicator_size = frame.inv_indicator_size;
  const VkDescriptorSet set = bindings_.set();
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, prepass_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, prepass_.layout(), 0, 1, &set, 0, nullptr);
  auto phase = [&](std::uint32_t which, std::uint32_t threads) {
    push.phase = which;
    vkCmdPushConstants(cmd, prepass_.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, groups(threads), 1, 1);
    vk::compute_to_compute(cmd);  // each phase reads what the one before wrote
  };
  phase(SP_PREPASS_CLEAR, std::max(source_capacity_, push.category_count * SP_CATEGORY_STRIDE));
  phase(SP_PREPASS_COUNT, ring_capacity_);
  if (caps) {
    phase(SP_PREPASS_THRESHOLD, push.category_count);
    phase(SP_PREPASS_MARK, ring_capacity_);
  }
  // RAW: counts and marks reach the draw's vertex shaders.
  if (graphics_queue)
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void IndicatorPass::record(VkCommandBuffer cmd, const DrawView& view, const DisplayFrame& frame,
                           VkDescriptorSet scene_depth) const {
  shader::IndicatorPush push{};
  push.view_proj = view.view_projection;
  push.eye = view.eye;
  push.current_step = frame.current_step;
  push.dt = frame.dt;
  push.lifetime = frame.lifetime;
  push.pixel_scale = view.pixel_scale;
  push.viewport_size = pack_pixels(glm::uvec2(glm::round(glm::max(view.viewport, glm::vec2(0.0f)))));
  push.viewport_origin = pack_pixels(view.viewport_origin);
  push.size_scale = frame.settings.size_scale;
  push.opacity_scale = frame.settings.opacity_scale;
  push.min_opacity = frame.settings.min_opacity;
  push.flags = (frame.settings.direction ? SP_DRAW_DIRECTION : 0u) | (frame.settings.outline ? SP_DRAW_OUTLINE : 0u) |
               (scene_depth != VK_NULL_HANDLE ? SP_DRAW_CLIP : 0u) |
               (frame.settings.max_per_category ? SP_DRAW_CAPS : 0u);
  push.depth_a = view.depth_a;
  push.depth_b = view.depth_b;
  push.inv_indicator_size = frame.inv_indicator_size;
  const GraphicsPipeline& pipeline = scene_depth != VK_NULL_HANDLE ? clip_pipeline_ : pipeline_;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.get());
  const VkDescriptorSet sets[2] = {bindings_.set(), scene_depth};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout(), 0,
                          scene_depth != VK_NULL_HANDLE ? 2 : 1, sets, 0, nullptr);
  vkCmdPushConstants(cmd, pipeline.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                     &push);
  vkCmdDrawIndirect(cmd, bound_draw_args_, bound_draw_args_offset_, 1, sizeof(VkDrawIndirectCommand));
}

void IndicatorPass::set_source_cues(std::span<const std::uint32_t> cues) {
  if (cues.size() > source_capacity_)
    throw Exception(ErrorCode::LimitExceeded, "indicator pass: cues for " + std::to_string(cues.size()) +
                                                  " sources, more than the " + std::to_string(source_capacity_) +
                                                  " it was made for");
  std::fill(std::copy(cues.begin(), cues.end(), cues_.begin()), cues_.end(), 0u);
  cues_changed_ = true;
}

void IndicatorPass::record_arrows(VkCommandBuffer cmd, const DrawView& view, const DisplayFrame& frame) const {
  if (!frame.offscreen_arrows || frame.source_count == 0) return;
  shader::ArrowPush push{};
  push.view_proj = view.view_projection;
  push.viewport = view.viewport;
  push.arrow_pixels = arrow_pixels(view.viewport);
  push.source_count = std::min(frame.source_count, source_capacity_);
  push.eye = view.eye;
  push.heading = view.heading;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, arrows_.get());
  const VkDescriptorSet set = bindings_.set();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, arrows_.layout(), 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, arrows_.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                     &push);
  vkCmdDraw(cmd, SP_INDICATOR_QUAD_VERTICES, push.source_count, 0, 0);
}

}  // namespace sp::draw
