// The descriptor set every soundpaint kernel sees (bindings in sp_gpu_types.h).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "sp_gpu_types.h"

layout(std430, binding = SP_BINDING_NODES) readonly buffer NodesBuffer { BvhNode bvh_nodes[]; };
layout(std430, binding = SP_BINDING_TRIANGLES) readonly buffer TrianglesBuffer { BvhTriangle bvh_triangles[]; };
layout(std430, binding = SP_BINDING_LAYERS) readonly buffer LayersBuffer { LayerAcoustics layers[]; };
layout(std430, binding = SP_BINDING_STEP_INPUT) readonly buffer StepInputBuffer {
  StepInput step_input;
  StepSource step_sources[];
};
layout(std430, binding = SP_BINDING_RAYS) buffer RaysBuffer { RayState rays[]; };
layout(std430, binding = SP_BINDING_HITS) buffer HitsBuffer { HitInfo hits[]; };
layout(std430, binding = SP_BINDING_QUEUES) buffer QueuesBuffer { uint queue_entries[]; };
layout(std430, binding = SP_BINDING_CONTROL) buffer ControlBuffer { Control control; };
layout(std430, binding = SP_BINDING_RING) writeonly buffer RingBuffer { Indicator ring[]; };
layout(std430, binding = SP_BINDING_CAPTURE) writeonly buffer CaptureBuffer { Indicator capture[]; };
layout(std430, binding = SP_BINDING_COUNTERS) buffer CountersBuffer { uint counters[]; };

layout(push_constant) uniform Push { WavefrontPush push; };

// Appends `value` to queue `queue` when `append`, with one atomic per
// subgroup. Must be reached by the whole subgroup (uniform control flow).
void append_to_queue(uint queue, bool append, uint value) {
  uvec4 ballot = subgroupBallot(append);
  uint total = subgroupBallotBitCount(ballot);
  if (total == 0u) return;
  uint base = 0u;
  if (subgroupElect()) base = atomicAdd(control.queues[queue].count, total);
  base = subgroupBroadcastFirst(base);
  if (append) queue_entries[queue * push.max_rays + base + subgroupBallotExclusiveBitCount(ballot)] = value;
}
