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
  uvec4 step_source_words[];  // StepSource: 3 each (load_step_source)
};
// The per-ray, per-spot records are read and written 16 bytes at a time
// (load_ray, store_capture, ... below), in their sp_types.h layouts: on
// lavapipe every storage-buffer access at a per-lane address is a loop over
// the lanes, so a record moved member by member costs a loop a member, and
// one moved as uvec4s a loop per 16 bytes (docs/model.md#records-16-bytes-at-a-time).
layout(std430, binding = SP_BINDING_RAYS) buffer RaysBuffer { uvec4 ray_words[]; };  // RayState: 6 each
layout(std430, binding = SP_BINDING_HITS) buffer HitsBuffer { uvec4 hit_words[]; };  // CastResult: 1 each
layout(std430, binding = SP_BINDING_QUEUES) buffer QueuesBuffer { uint queue_entries[]; };
// coherent: the last workgroup of a dispatch reads what the others wrote
// (last_subgroup below); so do the admission's and the guides'.
layout(std430, binding = SP_BINDING_CONTROL) coherent buffer ControlBuffer { Control control; };
layout(std430, binding = SP_BINDING_RING) buffer RingBuffer { uvec4 ring_words[]; };  // Indicator: 8 each
// A kernel that reads the capture list in the same dispatch that wrote it
// defines SP_CAPTURE_COHERENCE as coherent before including this file.
#ifndef SP_CAPTURE_COHERENCE
#define SP_CAPTURE_COHERENCE
#endif
layout(std430, binding = SP_BINDING_CAPTURE) SP_CAPTURE_COHERENCE buffer CaptureBuffer { uvec4 capture_words[]; };  // Indicator: 8 each
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
// A whole triangle, as resolve reads the one a ray struck.
BvhTriangle sp_bvh_triangle(uint i) {
  if (!kBvhTexels) return bvh_triangles[i];
  uvec4 w0 = sp_bvh_triangle_texel(i, 0u);
  uvec4 w1 = sp_bvh_triangle_texel(i, 1u);
  uvec4 w2 = sp_bvh_triangle_texel(i, 2u);
  uvec4 w3 = sp_bvh_triangle_texel(i, 3u);
  return BvhTriangle(uintBitsToFloat(w0.xyz), w0.w, uintBitsToFloat(w1.xyz), w1.w, uintBitsToFloat(w2.xyz), w2.w,
                     uintBitsToFloat(w3.xyz), w3.w);
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

// The records as uvec4s. Each constructor names every member, so a member
// added to RayState, CastResult or Indicator fails to compile here until
// it is given its place; the layouts themselves are checked in sp_types.h.
const uint kRayWords = 6u;        // sizeof(RayState) / 16
const uint kIndicatorWords = 8u;  // sizeof(Indicator) / 16

RayState ray_from_words(uvec4 w0, uvec4 w1, uvec4 w2, uvec4 w3, uvec4 w4, uvec4 w5) {
  return RayState(uintBitsToFloat(w0.xyz), uintBitsToFloat(w0.w), uintBitsToFloat(w1.xyz), uintBitsToFloat(w1.w),
                  uintBitsToFloat(w2.xyz), w2.w, w3.x, w3.y, w3.z, w3.w, w4.x, w4.y, uintBitsToFloat(w4.z),
                  uintBitsToFloat(w4.w), w5.x, w5.y, w5.z, w5.w);
}
RayState load_ray(uint i) {
  uint at = i * kRayWords;
  return ray_from_words(ray_words[at], ray_words[at + 1u], ray_words[at + 2u], ray_words[at + 3u], ray_words[at + 4u],
                        ray_words[at + 5u]);
}
void store_ray(uint i, RayState r) {
  uint at = i * kRayWords;
  ray_words[at] = uvec4(floatBitsToUint(r.origin), floatBitsToUint(r.energy));
  ray_words[at + 1u] = uvec4(floatBitsToUint(r.dir), floatBitsToUint(r.travelled));
  ray_words[at + 2u] = uvec4(floatBitsToUint(r.entry), r.entry_layer);
  ray_words[at + 3u] = uvec4(r.state, r.bounces, r.penetrations, r.ray_index);
  ray_words[at + 4u] = uvec4(r.source, r.casts, floatBitsToUint(r.max_distance), floatBitsToUint(r.loudness));
  ray_words[at + 5u] = uvec4(r.entry_triangle, r.diffractions, r.emit_cell, r.pad1);
}

const uint kStepSourceWords = 3u;  // sizeof(StepSource) / 16
StepSource load_step_source(uint i) {
  uint at = i * kStepSourceWords;
  uvec4 w2 = step_source_words[at + 2u];
  return StepSource(uintBitsToFloat(step_source_words[at].xyz), uintBitsToFloat(step_source_words[at].w),
                    uintBitsToFloat(step_source_words[at + 1u].xyz), uintBitsToFloat(step_source_words[at + 1u].w),
                    uintBitsToFloat(w2.x), w2.y, w2.z, w2.w);
}
// StepSource::first_ray and ::source_id of step source i.
uint step_source_first_ray(uint i) { return step_source_words[i * kStepSourceWords + 2u].y; }
uint step_source_id(uint i) { return step_source_words[i * kStepSourceWords + 2u].w; }

CastResult load_hit(uint i) {
  uvec4 w = hit_words[i];
  return CastResult(uintBitsToFloat(w.x), w.y, uintBitsToFloat(w.z), w.w);
}
void store_hit(uint i, CastResult c) {
  hit_words[i] = uvec4(floatBitsToUint(c.t), c.triangle, floatBitsToUint(c.matter_loss), c.flags);
}

Indicator indicator_from_words(uvec4 w0, uvec4 w1, uvec4 w2, uvec4 w3, uvec4 w4, uvec4 w5, uvec4 w6, uvec4 w7) {
  return Indicator(uintBitsToFloat(w0.xyz), uintBitsToFloat(w0.w), uintBitsToFloat(w1.xyz), uintBitsToFloat(w1.w),
                   uintBitsToFloat(w2.xyz), uintBitsToFloat(w2.w), uintBitsToFloat(w3.xyz), uintBitsToFloat(w3.w), w4.x,
                   w4.y, w4.z, w4.w, w5.x, w5.y, w5.z, w5.w, uintBitsToFloat(w6.xyz), uintBitsToFloat(w6.w), w7.x, w7.y,
                   uintBitsToFloat(w7.z), w7.w);
}
// Word k of an indicator (k < kIndicatorWords).
uvec4 indicator_word(Indicator ind, uint k) {
  if (k == 0u) return uvec4(floatBitsToUint(ind.position), floatBitsToUint(ind.energy));
  if (k == 1u) return uvec4(floatBitsToUint(ind.normal), floatBitsToUint(ind.size));
  if (k == 2u) return uvec4(floatBitsToUint(ind.color), floatBitsToUint(ind.intensity));
  if (k == 3u) return uvec4(floatBitsToUint(ind.dir), floatBitsToUint(ind.path_length));
  if (k == 4u) return uvec4(ind.kind, ind.source_id, ind.bounces, ind.penetrations);
  if (k == 5u) return uvec4(ind.diffractions, ind.step, ind.ray_index, ind.iteration);
  if (k == 6u) return uvec4(floatBitsToUint(ind.arrival), floatBitsToUint(ind.heard));
  return uvec4(ind.emit_cell, ind.source_slot, floatBitsToUint(ind.toward), ind.pad0);
}
Indicator load_capture(uint slot) {
  uint at = slot * kIndicatorWords;
  return indicator_from_words(capture_words[at], capture_words[at + 1u], capture_words[at + 2u],
                              capture_words[at + 3u], capture_words[at + 4u], capture_words[at + 5u],
                              capture_words[at + 6u], capture_words[at + 7u]);
}
void store_capture(uint slot, Indicator ind) {
  for (uint k = 0u; k < kIndicatorWords; ++k) capture_words[slot * kIndicatorWords + k] = indicator_word(ind, k);
}
// What the cast to the listener completes (Indicator::heard, ::toward).
void store_capture_heard(uint slot, float heard, float toward) {
  capture_words[slot * kIndicatorWords + 6u].w = floatBitsToUint(heard);
  capture_words[slot * kIndicatorWords + 7u].z = floatBitsToUint(toward);
}
void store_ring(uint slot, Indicator ind) {
  for (uint k = 0u; k < kIndicatorWords; ++k) ring_words[slot * kIndicatorWords + k] = indicator_word(ind, k);
}
// Indicator::step of ring slot `slot`: the step it was born in.
uint ring_birth_step(uint slot) { return ring_words[slot * kIndicatorWords + 5u].y; }

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
// The most workgroups the connect pass runs (gpu::connect_groups_max).
layout(constant_id = SP_SPEC_CONNECT_GROUPS_MAX) const uint kConnectGroupsMax = 0xFFFFFFFFu;

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
