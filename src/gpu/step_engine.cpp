#include "gpu/step_engine.h"

#include <cstddef>
#include <stdexcept>
#include <cstring>
#include <string>

#include "gpu/step_recorder.h"
#include "sim/indicator_ring.h"
#include "sim/sound_scene_backend.h"
#include "sim/world_geometry.h"
#include "sp_types.h"
#include "vk/barriers.h"

namespace sp::gpu {
namespace {

// Stages that read or write the simulation's buffers: its own transfers and
// kernels, and (on a graphics queue) the indicator draw.
VkPipelineStageFlags2 user_stages(bool graphics) {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                 VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
  if (graphics) stages |= VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
  return stages;
}

}  // namespace

StepEngine::StepEngine(vk::Context& context, const SoundScene& scene)
    : context_(context), resources_(context, scene.world(), scene.source_capacity()) {}

IndicatorView StepEngine::view() {
  IndicatorView v;
  v.context = &context_;
  v.ring = resources_.ring.get();
  v.ring_capacity = resources_.ring_capacity;
  v.draw_args = resources_.control.get();
  v.draw_args_offset = offsetof(shader::Control, draw_vertex_count);
  return v;
}

void StepEngine::record(VkCommandBuffer cmd, SoundScene& scene, std::uint64_t first_step, std::uint32_t count,
                        const RecordOptions& options) {
  RecordCounts ignored;
  RecordCounts& counts = options.counts != nullptr ? *options.counts : ignored;
  const VkPipelineStageFlags2 stages = user_stages(options.graphics_queue);
  if (options.timestamps) {
    vkCmdResetQueryPool(cmd, options.timestamps, 0, 2);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, options.timestamps, 0);
  }
  // WAR/WAW: earlier frames' kernels, copies and indicator draws are done
  // with the buffers before this frame's transfers and kernels touch them.
  ++counts.barriers;
  vk::memory_barrier(cmd, stages, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                         VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const bool first = !uploaded_;
  if (first) record_initial_uploads(cmd);
  const BvhChanges changes = detail::SoundSceneBackend::update_geometry(scene);
  if (first) {
    // WAW: the initial contents land before the moved parts (the rest
    // pose's) and the step start overwrite them.
    ++counts.barriers;
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  }
  record_geometry_changes(cmd, scene.world(), changes);

  for (std::uint32_t i = 0; i < count; ++i) {
    if (i > 0) {
      // WAR and WAW: the previous step's kernels are done with the step
      // input, the control block, the counters and the admission buffer
      // before this step's transfers write them.
      ++counts.barriers;
      vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                         VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    }
    detail::SoundSceneBackend::plan(scene, first_step + i, plan_);
    record_step_input(cmd, scene.world(), first_step + i);
    record_step_start(cmd, resources_, plan_.total_rays);
    // RAW: uploads (the step input and start; BVH and initial contents on
    // the first step, moved parts on any) are visible to the kernels, the
    // tree's texel reads included.
    ++counts.barriers;
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
                           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    record_step_dispatches(cmd, resources_, plan_.total_rays, options.stages, options.counts);
  }

  // RAW: the ring and the draw arguments the admission wrote reach the
  // indicator draw (and the readback copy).
  VkAccessFlags2 readers =
      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT;
  ++counts.barriers;
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, stages, readers);
  if (options.readback_control) {
    const VkBufferCopy region{0, 0, sizeof(shader::Control)};
    vkCmdCopyBuffer(cmd, resources_.control.get(), resources_.control_readback.get(), 1, &region);
    // Device -> host: the copy is visible to host reads after the fence.
    ++counts.barriers;
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
  }
  if (options.timestamps) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, options.timestamps, 1);
}

void StepEngine::record_initial_uploads(VkCommandBuffer cmd) {
  for (const GpuResources::InitialCopy& copy : resources_.initial_copies) {
    const VkBufferCopy region{copy.staging_offset, 0, copy.size};
    vkCmdCopyBuffer(cmd, resources_.initial_staging.get(), copy.destination->get(), 1, &region);
  }
  uploaded_ = true;
}

void StepEngine::record_pending_uploads(VkCommandBuffer cmd) {
  if (uploaded_) return;
  record_initial_uploads(cmd);
  // WAW: the initial contents land before later transfers overwrite them.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

void StepEngine::record_geometry_changes(VkCommandBuffer cmd, const World& world, const BvhChanges& changes) {
  const Bvh& bvh = world.geometry->bvh;
  if (bvh.nodes.size() > resources_.node_capacity)
    throw std::logic_error("a BVH rebuild made " + std::to_string(bvh.nodes.size()) +
                           " nodes, more than the buffer's " + std::to_string(resources_.node_capacity));
  for (const BvhIndexRange& range : changes.nodes) {
    vk::record_update(cmd, resources_.nodes, range.first * sizeof(BvhNode), &bvh.nodes[range.first],
                      (range.last - range.first) * sizeof(BvhNode));
  }
  for (const BvhIndexRange& range : changes.triangles) {
    vk::record_update(cmd, resources_.triangles, range.first * sizeof(BvhTriangle), &bvh.triangles[range.first],
                      (range.last - range.first) * sizeof(BvhTriangle));
  }
  for (const BvhIndexRange& range : changes.edges) {
    vk::record_update(cmd, resources_.edges, range.first * sizeof(shader::TriangleEdges), &bvh.edges[range.first],
                      (range.last - range.first) * sizeof(shader::TriangleEdges));
  }
}

void StepEngine::record_step_input(VkCommandBuffer cmd, const World& world, std::uint64_t step) {
  if (plan_.sources.size() > resources_.source_capacity)
    throw std::logic_error("the step plays more sources than the step input holds");
  shader::StepInput input{};
  input.params = make_sim_params(world.config, step, plan_.listener);
  if ((input.params.diffraction != 0u) != resources_.resolve_diffracts())
    throw std::logic_error("the step's diffraction differs from the one the resolve kernel was built for");
  input.total_rays = plan_.total_rays;
  input.source_count = static_cast<std::uint32_t>(plan_.sources.size());
  input.ring_capacity = resources_.ring_capacity;
  input.layer_count = resources_.layer_count;
  input.ring_quota = ring_quota(world.config);
  input.inv_indicator_size = inverse_indicator_size(world.config);
  input.dt = static_cast<float>(world.config.dt);
  input.lifetime = world.config.indicator_lifetime;
  const std::size_t source_bytes = plan_.sources.size() * sizeof(shader::StepSource);
  step_input_bytes_.resize(sizeof input + source_bytes);
  std::memcpy(step_input_bytes_.data(), &input, sizeof input);
  if (source_bytes > 0) std::memcpy(step_input_bytes_.data() + sizeof input, plan_.sources.data(), source_bytes);
  vk::record_update(cmd, resources_.step_input, 0, step_input_bytes_.data(), step_input_bytes_.size());
}

}  // namespace sp::gpu
