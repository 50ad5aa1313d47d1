// The descriptor set every soundpaint kernel sees (bindings in sp_gpu_types.h).
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "sp_gpu_types.h"

layout(std430, binding = SP_BINDING_NODES) readonly buffer NodesBuffer { BvhNode bvh_nodes[]; };
layout(std430, binding = SP_BINDING_TRIANGLES) readonly buffer TrianglesBuffer { BvhTriangle bvh_triangles[]; };
// The same two buffers as texels, read by the walks (sp_traverse.h) where
// kBvhTexels: on lavapipe a storage-buffer read at a per-lane address is a
// loop over the lanes, word by word, while a texel fetch is one gather per
// channel (docs/model.md#the-tree-as-texels).
layout(binding = SP_BINDING_NODE_TEXELS) uniform usamplerBuffer bvh_node_texels;
layout(binding = SP_BINDING_TRIANGLE_TEXELS) uniform usamplerBuffer bvh_triangle_texels;
layout(constant_id = SP_SPEC_BVH_TEXELS) const bool kBvhTexels = true;
layout(std430, binding = SP_BINDING_LAYERS) readonly buffer LayersBuffer { LayerAcoustics layers[]; };
layout(std430, binding = SP_BINDING_STEP_INPUT) readonly buffer StepInputBuffer {
  StepInput step_input;
  StepSource step_sources[];
};
layout(std430, binding = SP_BINDING_RAYS) buffer RaysBuffer { RayState rays[]; };
layout(std430, binding = SP_BINDING_HITS) buffer HitsBuffer { CastResult hits[]; };
layout(std430, binding = SP_BINDING_QUEUES) buffer QueuesBuffer { uint queue_entries[]; };
// coherent: the last workgroup of a dispatch reads what the others wrote
// (last_subgroup below); so do the admission's and the guides'.
layout(std430, binding = SP_BINDING_CONTROL) coherent buffer ControlBuffer { Control control; };
layout(std430, binding = SP_BINDING_RING) buffer RingBuffer { Indicator ring[]; };
// A kernel that reads the capture list in the same dispatch that wrote it
// defines SP_CAPTURE_COHERENCE as coherent before including this file.
#ifndef SP_CAPTURE_COHERENCE
#define SP_CAPTURE_COHERENCE
#endif
layout(std430, binding = SP_BINDING_CAPTURE) SP_CAPTURE_COHERENCE buffer CaptureBuffer { Indicator capture[]; };
layout(std430, binding = SP_BINDING_COUNTERS) buffer CountersBuffer { uint counters[]; };
layout(std430, binding = SP_BINDING_ADMISSION) coherent buffer AdmissionBuffer { uint admission_histogram[]; };
layout(std430, binding = SP_BINDING_EDGES) readonly buffer EdgesBuffer { TriangleEdges triangle_edges[]; };
layout(std430, binding = SP_BINDING_GUIDE) coherent buffer GuideBuffer { uint guide[]; };
layout(std430, binding = SP_BINDING_CONNECT) buffer ConnectBuffer { uint connect_queue[]; };

layout(push_constant) uniform Push { WavefrontPush push; };

// The tree as the walks read it (SP_NODE_* and SP_TRIANGLE_* in
// sp_traverse.h). Texel 2i of the nodes holds node i's bmin and
// left_or_first, texel 2i + 1 its bmax and count; texels 4i .. 4i + 3 of the
// triangles hold v0 and layer, v1 and scene_index, v2 and solid, normal and
// padding: BvhNode's and BvhTriangle's own layouts, read 16 bytes at a time.
// Reading the words as uint and the floats back from their bits keeps them
// exact. Where !kBvhTexels the storage buffers are read instead: the
// specialization leaves one of the two reads in the code.
uvec4 sp_bvh_node_texel(uint i, uint half_index) { return texelFetch(bvh_node_texels, int(2u * i + half_index)); }
uvec4 sp_bvh_triangle_texel(uint i, uint quarter) { return texelFetch(bvh_triangle_texels, int(4u * i + quarter)); }
vec3 sp_bvh_node_min(uint i) {
  if (kBvhTexels) return uintBitsToFloat(sp_bvh_node_texel(i, 0u).xyz);
  return bvh_nodes[i].bmin;
}
vec3 sp_bvh_node_max(uint i) {
  if (kBvhTexels) return uintBitsToFloat(sp_bvh_node_texel(i, 1u).xyz);
  return bvh_nodes[i].bmax;
}
uint sp_bvh_node_first(uint i) {
  if (kBvhTexels) return sp_bvh_node_texel(i, 0u).w;
  return bvh_nodes[i].left_or_first;
}
uint sp_bvh_node_count(uint i) {
  if (kBvhTexels) return sp_bvh_node_texel(i, 1u).w;
  return bvh_nodes[i].count;
}
vec3 sp_bvh_triangle_v0(uint i) {
  if (kBvhTexels) return uintBitsToFloat(sp_bvh_triangle_texel(i, 0u).xyz);
  return bvh_triangles[i].v0;
}
vec3 sp_bvh_triangle_v1(uint i) {
  if (kBvhTexels) return uintBitsToFloat(sp_bvh_triangle_texel(i, 1u).xyz);
  return bvh_triangles[i].v1;
}
vec3 sp_bvh_triangle_v2(uint i) {
  if (kBvhTexels) return uintBitsToFloat(sp_bvh_triangle_texel(i, 2u).xyz);
  return bvh_triangles[i].v2;
}
uint sp_bvh_triangle_scene_index(uint i) {
  if (kBvhTexels) return sp_bvh_triangle_texel(i, 1u).w;
  return bvh_triangles[i].scene_index;
}
uint sp_bvh_triangle_solid(uint i) {
  if (kBvhTexels) return sp_bvh_triangle_texel(i, 2u).w;
  return bvh_triangles[i].solid;
}
vec3 sp_bvh_triangle_normal(uint i) {
  if (kBvhTexels) return uintBitsToFloat(sp_bvh_triangle_texel(i, 3u).xyz);
  return bvh_triangles[i].normal;
}

// Entries of queue `queue` (see QueueArgs): Active rays, then resolving ones.
uint queue_length(uint queue) { return control.queues[queue].active_count + control.queues[queue].resolving_count; }
uint queue_entry(uint queue, uint i) {
  uint front = control.queues[queue].active_count;
  uint slot = i < front ? i : push.max_rays - 1u - (i - front);
  return queue_entries[queue * push.max_rays + slot];
}

// The kernels' width (local_size_x_id = SP_SPEC_WORKGROUP_SIZE), as the
// code reads it: a scalar constant the host specializes to the same value
// (lavapipe, Mesa 22.3, does not specialize gl_WorkGroupSize in the code).
layout(constant_id = SP_SPEC_GROUP_WIDTH) const uint kGroupWidth = SP_WORKGROUP_SIZE;

// Whether this subgroup is the last of its dispatch to finish, with every
// other invocation's writes visible: each subgroup makes its writes
// available, then takes a ticket for its invocations from a counter; the
// one whose tickets end the dispatch does what a one-thread dispatch after
// this one would have, saving a dispatch and a barrier. No workgroup
// barrier: on lavapipe each one splits the kernel into resumed pieces,
// which cost more than the dispatch saved. Reached by every invocation
// (uniform control flow, no early return before it). GLSL passes the
// counter by copy, so it is named by index: SP_TICKET_*.
#define SP_TICKET_RESOLVE 0u
#define SP_TICKET_CONNECT 1u
#define SP_TICKET_TIEBREAK 2u
#define SP_TICKET_COPY 3u
bool last_subgroup(uint ticket) {
  memoryBarrierBuffer();
  uint mine = subgroupAdd(1u);
  uint taken = 0u;
  if (subgroupElect()) {
    if (ticket == SP_TICKET_RESOLVE) taken = atomicAdd(control.resolve_done, mine);
    else if (ticket == SP_TICKET_CONNECT) taken = atomicAdd(control.connect_done, mine);
    else if (ticket == SP_TICKET_TIEBREAK) taken = atomicAdd(control.tiebreak_done, mine);
    else taken = atomicAdd(control.copy_done, mine);
  }
  taken = subgroupBroadcastFirst(taken);
  memoryBarrierBuffer();
  return taken + mine == gl_NumWorkGroups.x * kGroupWidth;
}

// Appends `value` to queue `queue` when `append`: at its front when
// `resolving` is false, at its back when true; one atomic per subgroup and
// end. Must be reached by the whole subgroup (uniform control flow).
void append_to_queue(uint queue, bool append, bool resolving, uint value) {
  uvec4 front = subgroupBallot(append && !resolving);
  uvec4 back = subgroupBallot(append && resolving);
  uint front_total = subgroupBallotBitCount(front);
  uint back_total = subgroupBallotBitCount(back);
  uint front_base = 0u;
  uint back_base = 0u;
  if (subgroupElect()) {
    if (front_total > 0u) front_base = atomicAdd(control.queues[queue].active_count, front_total);
    if (back_total > 0u) back_base = atomicAdd(control.queues[queue].resolving_count, back_total);
  }
  front_base = subgroupBroadcastFirst(front_base);
  back_base = subgroupBroadcastFirst(back_base);
  if (append && !resolving) {
    queue_entries[queue * push.max_rays + front_base + subgroupBallotExclusiveBitCount(front)] = value;
  }
  if (append && resolving) {
    uint j = back_base + subgroupBallotExclusiveBitCount(back);
    queue_entries[queue * push.max_rays + push.max_rays - 1u - j] = value;
  }
}
