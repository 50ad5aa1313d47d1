#version 460
// After a step's last wavefront iteration: casts each queued spot's way to
// the listener and completes what it hears (sp_connect.h), adds what a
// heard spot is worth to its source's guide (sp_guide.h), and counts its
// admission bin (resolve queued only the spots worth a cast and binned the
// others). Its last subgroup (there is always one) then does what follows
// the wavefront once a step: the running totals, each step source's guide
// folded, and the plan of the ring's admission (sp_admission.h); for a step
// of at most kAdmitInlineMax spots, the admission itself
// (admission_passes.glsl), so that admit.comp's two dispatches run no
// group.
#extension GL_GOOGLE_include_directive : require
// The admission run here reads what the other workgroups' connections
// wrote into the capture list (the heard energy): coherent, as the other
// buffers a last subgroup reads are.
#define SP_CAPTURE_COHERENCE coherent
#include "gpu_bindings.glsl"
#include "admission_passes.glsl"
#include "sp_connect.h"
#include "sp_guide.h"
#include "sp_traverse.h"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

void add64(inout uint lo, inout uint hi, uint value) {
  uint sum = lo + value;
  if (sum < lo) hi += 1u;
  lo = sum;
}

// Slots of the ring whose indicator is live at step `now`. Births only grow
// from the oldest slot to the newest, so the first live one is found by
// bisection (the CPU's RingWriter counts the same from its runs).
uint live_slots(uint now) {
  uint capacity = step_input.ring_capacity;
  uint filled = control.ring_filled;
  uint oldest = (control.ring_head + capacity - filled) % capacity;
  uint lo = 0u;
  uint hi = filled;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    uint birth = ring_birth_step((oldest + mid) % capacity);
    if (sp_indicator_live(now, birth, step_input.dt, step_input.lifetime)) hi = mid; else lo = mid + 1u;
  }
  return filled - lo;
}

// The step's totals (what the last prepare dispatch kept).
void add_totals() {
  uint made = control.step_indicators;
  add64(control.total_indicators_lo, control.total_indicators_hi, made);
  add64(control.total_casts_lo, control.total_casts_hi, control.step_casts);
  add64(control.total_cut_short_lo, control.total_cut_short_hi, control.step_cut_short);
  add64(control.total_rays_lo, control.total_rays_hi, step_input.total_rays);
  add64(control.total_connections_lo, control.total_connections_hi, control.step_connections);
  control.max_step_casts = max(control.max_step_casts, control.step_casts);
  control.steps += 1u;
  uint step_counters = step_input.layer_count * SP_COUNTERS_PER_LAYER;
  for (uint k = 0u; k < step_counters; ++k) {
    uint total_index = step_counters + 2u * k;
    add64(counters[total_index], counters[total_index + 1u], counters[k]);
  }
}

void main() {
  // At most kConnectGroupsMax workgroups: each lane takes a spot in turn.
  // The loop's condition is the subgroup's, so that its subgroup operations
  // see every lane.
  uint spots = control.connect_count;
  uint lanes = gl_NumWorkGroups.x * kGroupWidth;
  uint casts = 0u;
  for (uint i = gl_GlobalInvocationID.x; subgroupBallot(i < spots) != uvec4(0u); i += lanes) {
    bool valid = i < spots;
    casts += subgroupAdd(valid ? 1u : 0u);
    if (!valid) continue;
    uint slot = connect_queue[i];
    Indicator ind = load_capture(slot);
    SimParams p = step_input.params;
    Connection c = sp_connection(ind, p);
    bool open = !sp_segment_blocked(c.origin, c.dir, 0.0f, c.distance);
    sp_finish_connection(ind, c, open, load_step_source(ind.source_slot), p);
    // Only what the connection changed goes back.
    store_capture_heard(slot, ind.heard, ind.toward);
    float inv_size = step_input.inv_indicator_size;
    if (ind.heard > 0.0f) {
      uint base = sp_guide_base(step_source_id(ind.source_slot));
      atomicAdd(guide[base + SP_GUIDE_PENDING + ind.emit_cell],
                sp_guide_spot_weight(sp_heard_relative(ind, inv_size), ind.toward));
    }
    uint bin = sp_admission_bin(ind, inv_size);
    atomicAdd(admission_histogram[bin], 1u);
    atomicAdd(admission_histogram[SP_ADMISSION_CLASS_COUNTS + sp_bin_class(bin)], 1u);
  }
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_connections, casts);

  if (!last_subgroup(SP_TICKET_CONNECT)) return;
  // Each step source's guide takes in what its heard spots added.
  for (uint s = gl_SubgroupInvocationID; s < step_input.source_count; s += gl_SubgroupSize)
    sp_guide_fold(sp_guide_base(step_source_id(s)));
  uint listed = control.step_indicators;
  bool admit_here = listed > 0u && listed <= kAdmitInlineMax;
  if (subgroupElect()) {
    add_totals();
    uint live = live_slots(step_input.params.step);
    sp_plan_admission(sp_admission_budget(step_input.ring_quota, step_input.ring_capacity, live));
    if (admit_here) control.admit_group_count_x = 0u;
  }
  if (!admit_here) return;
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  admission_inline(listed);
}
