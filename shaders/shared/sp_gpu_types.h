// Layouts used only by the GPU backend's buffers, shared with C++ for the
// static_asserts and for the host's reads and writes.
#ifndef SP_GPU_TYPES_H
#define SP_GPU_TYPES_H

#include "sp_types.h"

// Storage-buffer bindings of the one descriptor set all kernels share.
#define SP_BINDING_NODES 0
#define SP_BINDING_TRIANGLES 1
#define SP_BINDING_LAYERS 2
#define SP_BINDING_STEP_INPUT 3
#define SP_BINDING_RAYS 4
#define SP_BINDING_HITS 5
#define SP_BINDING_QUEUES 6
#define SP_BINDING_CONTROL 7
#define SP_BINDING_RING 8
#define SP_BINDING_CAPTURE 9
#define SP_BINDING_COUNTERS 10
#define SP_BINDING_ADMISSION 11
#define SP_BINDING_EDGES 12
#define SP_BINDING_GUIDE 13
#define SP_BINDING_CONNECT 14
#define SP_BINDING_COUNT 15
// Uniform texel buffers after them: the tree's nodes and triangles again,
// as RGBA32UI texels (two a node, four a triangle), for the walks.
#define SP_BINDING_NODE_TEXELS 15
#define SP_BINDING_TRIANGLE_TEXELS 16
#define SP_TEXEL_BINDING_COUNT 2

// Per-layer counters: SP_COUNTERS_PER_LAYER per layer per step, in the slot
// order below, then 2 * SP_COUNTERS_PER_LAYER per layer of 64-bit totals as
// (lo, hi) pairs.
#define SP_COUNTER_HITS 0u
#define SP_COUNTER_REFLECTIONS 1u
#define SP_COUNTER_PENETRATIONS 2u
#define SP_COUNTER_NO_WAY_OUT 3u
#define SP_COUNTER_BACK_FACE_HITS 4u
#define SP_COUNTER_DIFFRACTIONS 5u
#define SP_COUNTERS_PER_LAYER 6u

SP_BEGIN_NAMESPACE

// A work queue's lengths and the three VkDispatchIndirectCommands over it.
// A queue holds Active rays from its front and ResolvingPenetration rays
// from its back: entry i < active_count is slot i, entry active_count + j is
// slot max_rays - 1 - j. The trace kernel runs over the Active rays and the
// matter kernel over the resolving ones, so neither carries the other's
// registers and each subgroup holds rays of one kind; resolve runs over
// all. The resolve kernel appends by bumping one count; its last subgroup
// turns the counts into the next iteration's group counts (sp_queue_args).
struct QueueArgs {
  uint group_count_x;  // resolve: every entry
  uint group_count_y;
  uint group_count_z;
  uint active_count;
  uint active_groups_x;  // trace: the Active entries
  uint active_groups_y;
  uint active_groups_z;
  uint resolving_count;
  uint resolving_groups_x;  // trace_matter: the resolving entries
  uint resolving_groups_y;
  uint resolving_groups_z;
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(QueueArgs) == 48 && offsetof(QueueArgs, active_groups_x) == 16 && offsetof(QueueArgs, resolving_groups_x) == 32);

// Workgroups of `width` invocations that `invocations` need.
SP_INLINE uint sp_group_count(uint invocations, uint width) { return (invocations + width - 1u) / width; }

// A queue holding `active_rays` Active and `resolving` resolving rays, with its
// dispatches' arguments for kernels `width` invocations wide: what the host
// writes for queue 0 and 1 before a step (gpu::step_start_control) and
// resolve's last subgroup for the next iteration.
SP_INLINE QueueArgs sp_queue_args(uint active_rays, uint resolving, uint width) {
  QueueArgs q;
  q.group_count_x = sp_group_count(active_rays + resolving, width);
  q.group_count_y = 1u;
  q.group_count_z = 1u;
  q.active_count = active_rays;
  q.active_groups_x = sp_group_count(active_rays, width);
  q.active_groups_y = 1u;
  q.active_groups_z = 1u;
  q.resolving_count = resolving;
  q.resolving_groups_x = sp_group_count(resolving, width);
  q.resolving_groups_y = 1u;
  q.resolving_groups_z = 1u;
  q.pad0 = 0u;
  return q;
}

// GPU-written state of the simulation. draw_* is a VkDrawIndirectCommand the
// indicator draw instances from.
struct Control {
  // First, so that a draw pass can bind it from offset 0 whatever the
  // device's storage-buffer offset alignment.
  uint draw_vertex_count;
  uint draw_instance_count;
  uint draw_first_vertex;
  uint draw_first_instance;
  // The step's own counts and dispatch arguments, from queues up to
  // ring_head: the host writes what they hold before a step's first kernel
  // (gpu::step_start_control), so that no kernel has to reset them first.
  QueueArgs queues[2];
  uint step_indicators;   // indicators the current step created (its capture list)
  uint step_casts;        // casts of the current step
  uint step_cut_short;    // casts that ended at SP_MAX_CAST_PACKETS
  uint step_connections;  // casts from spots to the listener (sp_connect.h)
  // The connect kernel's dispatch over the step's spots worth casting (the
  // connect queue, which resolve fills), and their count.
  uint connect_group_count_x;
  uint connect_group_count_y;
  uint connect_group_count_z;
  uint connect_count;
  // Admission of the step's indicators to the ring (sp_ring.h): a dispatch
  // over the capture list, and how many were admitted
  // (the plan lives in the admission buffer, sp_admission.h).
  uint admit_group_count_x;
  uint admit_group_count_y;
  uint admit_group_count_z;
  uint admit_count;
  uint tiebreak_count;  // indicators in a class's overflowing bin, listed for the tie-break
  // Invocations of the running pass that have finished: the last subgroup
  // does what a dispatch of one thread after it did (last_subgroup in
  // gpu_bindings.glsl). Resolve's counts per iteration and resets itself.
  uint resolve_done;
  uint connect_done;
  uint tiebreak_done;
  uint copy_done;
  // The run's state, kept from step to step.
  uint ring_head;    // next ring slot at the start of a step
  uint ring_filled;  // slots holding an indicator, <= capacity
  uint total_indicators_lo;
  uint total_indicators_hi;
  uint total_casts_lo;
  uint total_casts_hi;
  uint max_step_casts;
  uint steps;
  uint total_rays_lo;
  uint total_rays_hi;
  uint total_cut_short_lo;
  uint total_cut_short_hi;
  uint total_connections_lo;
  uint total_connections_hi;
  uint pad0;
};
SP_CHECK_LAYOUT(sizeof(Control) == 240 && offsetof(Control, draw_vertex_count) == 0 && offsetof(Control, queues) == 16 && offsetof(Control, connect_group_count_x) == 128 && offsetof(Control, admit_group_count_x) == 144 && offsetof(Control, ring_head) == 180);

// Written by the host before each step's submit.
struct StepInput {
  SimParams params;
  uint total_rays;     // rays emitted this step
  uint source_count;   // entries used in the step's source table
  uint ring_capacity;  // max_indicators
  uint layer_count;
  uint ring_quota;           // indicators the ring admits per step (sp_ring.h)
  float inv_indicator_size;  // 1 / indicator_size, 0 when it is 0
  float dt;                  // seconds per step, as the liveness rule takes it
  float lifetime;            // indicator_lifetime, as the liveness rule takes it
};
SP_CHECK_LAYOUT(sizeof(StepInput) == 112 && sizeof(StepInput) % 16 == 0);

// The admission kernel's two passes (admit.comp), chosen by push.finish: the tie-break pass (whose last workgroup also marks the
// admitted and orders them), then the copy into the ring (whose last
// workgroup moves the ring's head). admit.comp says how.
#define SP_ADMIT_TIEBREAK 0u
#define SP_ADMIT_COPY 1u

// Push constants of the wavefront kernels.
struct WavefrontPush {
  uint queue_in;    // 0 or 1: which queue this iteration consumes
  uint finish;      // prepare: 1 on the step's last iteration; admit: its phase
  uint max_rays;    // capacity of each queue
  uint iterations;  // wavefront iterations a step records
};
SP_CHECK_LAYOUT(sizeof(WavefrontPush) == 16);

SP_END_NAMESPACE

#endif  // SP_GPU_TYPES_H
