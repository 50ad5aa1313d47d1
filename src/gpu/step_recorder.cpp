#include "gpu/step_recorder.h"

#include <algorithm>
#include <cstddef>

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

}  // namespace

void record_step_dispatches(VkCommandBuffer cmd, const GpuResources& r, std::uint32_t /*source_count*/,
                            StageQueries* stages, RecordCounts* counts) {
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

  bind(cmd, r, r.kernels.emit, 0, 0);
  const std::uint32_t emit_threads = std::max(r.max_rays, r.layer_count * SP_COUNTERS_PER_LAYER);
  ++count.dispatches;
  vkCmdDispatch(cmd, static_cast<std::uint32_t>(workgroups_for(emit_threads, r.workgroup_size)), 1, 1);
  stamp(StageKernel::Emit);
  // Emitted rays, queue 0 and its indirect arguments feed the first trace.
  ++count.barriers;
  vk::compute_to_compute(cmd);

  for (std::uint32_t it = 0; it < r.iterations; ++it) {
    const std::uint32_t queue_in = it % 2;
    const VkDeviceSize args = offsetof(shader::Control, queues) + queue_in * sizeof(shader::QueueArgs);
    bind(cmd, r, r.kernels.trace, queue_in, 0);
    ++count.dispatches;
    vkCmdDispatchIndirect(cmd, r.control.get(), args + offsetof(shader::QueueArgs, active_groups_x));
    // The two write the hits of disjoint rays: no barrier between them. No
    // ray resolves a penetration in the first iteration: every ray there
    // has just been emitted.
    if (it > 0) {
      bind(cmd, r, r.kernels.trace_matter, queue_in, 0);
      ++count.dispatches;
      vkCmdDispatchIndirect(cmd, r.control.get(), args + offsetof(shader::QueueArgs, resolving_groups_x));
    }
    stamp(StageKernel::Trace);
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
