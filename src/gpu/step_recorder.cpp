#include "gpu/step_recorder.h"

#include <cstddef>
#include <stdexcept>
#include <string>

#include "sp_ring.h"
#include "sp_types.h"
#include "vk/barriers.h"

namespace sp::gpu {
namespace {

void bind(VkCommandBuffer cmd, const GpuResources& r, const vk::ComputePipeline& kernel, std::uint32_t queue_in,
          std::uint32_t finish) {
  shader::WavefrontPush push{queue_in, finish, r.max_rays, r.iterations};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.get());
  vkCmdPushConstants(cmd, kernel.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
}

constexpr std::size_t kStepBegin = offsetof(shader::Control, queues);
constexpr std::size_t kStepEnd = offsetof(shader::Control, ring_head);
static_assert(offsetof(shader::Control, copy_done) < kStepEnd &&
                  offsetof(shader::Control, draw_first_instance) < kStepBegin,
              "the per-step part of the control block is one range, after the draw arguments");

}  // namespace

shader::Control step_start_control(std::uint32_t total_rays, std::uint32_t group_width) {
  shader::Control start{};
  start.queues[0] = shader::sp_queue_args(total_rays, 0, group_width);
  start.queues[1] = shader::sp_queue_args(0, 0, group_width);
  start.connect_group_count_x = start.connect_group_count_y = start.connect_group_count_z = 1;
  start.admit_group_count_y = start.admit_group_count_z = 1;
  return start;
}

void record_step_start(VkCommandBuffer cmd, const GpuResources& r, std::uint32_t total_rays) {
  // The buffers and the dispatch limits were sized for max_rays.
  if (total_rays > r.max_rays)
    throw std::logic_error("a step of " + std::to_string(total_rays) + " rays, more than the " +
                           std::to_string(r.max_rays) + " the buffers hold");
  const shader::Control start = step_start_control(total_rays, r.workgroup_size);
  vk::record_update(cmd, r.control, kStepBegin, reinterpret_cast<const std::byte*>(&start) + kStepBegin,
                    kStepEnd - kStepBegin);
  if (r.layer_count > 0) {
    vkCmdFillBuffer(cmd, r.counters.get(), 0,
                    VkDeviceSize{r.layer_count} * SP_COUNTERS_PER_LAYER * sizeof(std::uint32_t), 0u);
  }
  const VkDeviceSize order_words = SP_ORDER_WORDS(VkDeviceSize{r.max_rays}, VkDeviceSize{r.iterations});
  vkCmdFillBuffer(cmd, r.admission.get(), SP_ORDER_BITMAP * sizeof(std::uint32_t), order_words * sizeof(std::uint32_t),
                  0u);
}

void record_step_dispatches(VkCommandBuffer cmd, const GpuResources& r, std::uint32_t total_rays, StageQueries* stages,
                            RecordCounts* counts) {
  RecordCounts ignored;
  RecordCounts& count = counts != nullptr ? *counts : ignored;
  if (stages != nullptr && stages->next + stage_queries_per_step(r.iterations) > stages->end) stages = nullptr;
  // After the kernels before it have finished (compute-shader stage).
  auto stamp = [&](StageKernel kind) {
    if (stages == nullptr) return;
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, stages->pool, stages->next++);
    stages->kinds.push_back(kind);
  };
  stamp(StageKernel::Start);
  VkDescriptorSet set = r.bindings.set();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.kernels.emit.layout(), 0, 1, &set, 0, nullptr);

  // The first iteration's casts are emit's: its rays are all Active.
  bind(cmd, r, r.kernels.emit, 0, 0);
  ++count.dispatches;
  vkCmdDispatch(cmd, static_cast<std::uint32_t>(workgroups_for(total_rays, r.workgroup_size)), 1, 1);
  stamp(StageKernel::Emit);

  for (std::uint32_t it = 0; it < r.iterations; ++it) {
    const std::uint32_t queue_in = it % 2;
    const VkDeviceSize args = offsetof(shader::Control, queues) + queue_in * sizeof(shader::QueueArgs);
    if (it > 0) {
      // The two write the hits of disjoint rays: no barrier between them.
      bind(cmd, r, r.kernels.trace, queue_in, 0);
      ++count.dispatches;
      vkCmdDispatchIndirect(cmd, r.control.get(), args + offsetof(shader::QueueArgs, active_groups_x));
      bind(cmd, r, r.kernels.trace_matter, queue_in, 0);
      ++count.dispatches;
      vkCmdDispatchIndirect(cmd, r.control.get(), args + offsetof(shader::QueueArgs, resolving_groups_x));
      stamp(StageKernel::Trace);
    }
    // Hits written by trace and trace_matter are read by resolve.
    ++count.barriers;
    vk::compute_to_compute(cmd);
    bind(cmd, r, r.kernels.resolve, queue_in, 0);
    ++count.dispatches;
    vkCmdDispatchIndirect(cmd, r.control.get(), args);
    stamp(StageKernel::Resolve);
    // The output queue and the indirect arguments resolve's last workgroup
    // wrote feed the next iteration (and, after the last, the passes below).
    ++count.barriers;
    vk::compute_to_compute(cmd);
  }

  // The spots resolve queued cast their way to the listener (connect.comp);
  // its last workgroup keeps the totals and plans the admission.
  bind(cmd, r, r.kernels.connect, 0, 0);
  ++count.dispatches;
  vkCmdDispatchIndirect(cmd, r.control.get(), offsetof(shader::Control, connect_group_count_x));
  stamp(StageKernel::Connect);
  ++count.barriers;
  vk::compute_to_compute(cmd);

  // The ring admits its share of the step's indicators (admit.comp): the
  // tie-break pass, then the copy, both over the capture list. A step of
  // at most inline_admission_max indicators was admitted by connect's last
  // subgroup: these then dispatch no group.
  const VkDeviceSize admit_args = offsetof(shader::Control, admit_group_count_x);
  bind(cmd, r, r.kernels.admit, 0, SP_ADMIT_TIEBREAK);
  ++count.dispatches;
  vkCmdDispatchIndirect(cmd, r.control.get(), admit_args);
  ++count.barriers;
  vk::compute_to_compute(cmd);
  bind(cmd, r, r.kernels.admit, 0, SP_ADMIT_COPY);
  ++count.dispatches;
  vkCmdDispatchIndirect(cmd, r.control.get(), admit_args);
  stamp(StageKernel::Admit);
  // The ring, the control block and the guides this step wrote reach the
  // next step's kernels.
  ++count.barriers;
  vk::compute_to_compute(cmd);
}

}  // namespace sp::gpu
