#version 460
// After a step: admits the ring's share of the step's indicators (sp_ring.h)
// in six dispatches, chosen by push.finish (SP_ADMIT_*):
// - histogram: each indicator's way to the listener is cast and what it
//   hears completed (sp_connect.h), what it is worth added to its source's
//   guide (sp_guide.h), and its admission bin counted;
// - select: the budget (the quota, or the ring's free room) and the
//   threshold bins (one thread, which also clears the histogram), while
//   the other threads fold each step source's guide;
// - the same two for the tie-break bins of the bin where a share runs out;
// - the copy of the admitted indicators into the ring;
// - the ring's new head and size (one thread).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_admission.h"
#include "sp_connect.h"
#include "sp_guide.h"
#include "sp_traverse.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

void clear_histogram() {
  for (uint b = 0u; b < SP_ADMISSION_BINS; ++b) admission_histogram[b] = 0u;
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
    uint birth = ring[(oldest + mid) % capacity].step;
    if (sp_indicator_live(now, birth, float(step_input.dt), step_input.lifetime)) hi = mid; else lo = mid + 1u;
  }
  return filled - lo;
}

// Completes what `ind` hears at the listener; returns 1 when it cast.
uint connect(inout Indicator ind) {
  SimParams p = step_input.params;
  Connection c = sp_connection(ind, p);
  bool open = false;
  if (c.candidate != 0u) {
    HitInfo hit = sp_closest_hit(c.origin, c.dir, 0.0f, c.distance);
    open = hit.triangle == SP_INVALID && hit.cut_short == 0u;
  }
  sp_finish_connection(ind, c, open, step_sources[ind.source_slot], p);
  return c.candidate;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint phase = push.finish;
  uint capacity = step_input.ring_capacity;
  if (phase == SP_ADMIT_SELECT) {
    if (i < step_input.source_count) sp_guide_fold(sp_guide_base(step_sources[i].source_id));
    if (i != 0u) return;
    uint live = live_slots(step_input.params.step);
    sp_plan_admission(sp_admission_budget(step_input.ring_quota, capacity, live));
    clear_histogram();
    return;
  }
  if (phase == SP_ADMIT_TIEBREAK_SELECT) {
    if (i != 0u) return;
    sp_plan_tiebreak(SP_ADMISSION_CLASSES);
    clear_histogram();
    return;
  }
  if (phase == SP_ADMIT_FINISH) {
    if (i != 0u) return;
    uint admitted = control.admit_count;
    control.ring_head = (control.ring_head + admitted) % capacity;
    control.ring_filled = min(capacity, control.ring_filled + admitted);
    control.draw_instance_count = control.ring_filled;
    return;
  }
  // The histograms and the copy run over the capture list; the copy and
  // the counts reach the subgroup operations below in uniform control flow.
  bool valid = i < control.step_indicators;
  Indicator ind;
  uint bin = 0u;
  if (phase == SP_ADMIT_HISTOGRAM) {
    uint connected = 0u;
    if (valid) {
      ind = capture[i];
      connected = connect(ind);
      capture[i] = ind;
      if (ind.heard > 0.0f) {
        float relative = sp_heard_relative(ind, step_input.inv_indicator_size);
        uint base = sp_guide_base(step_sources[ind.source_slot].source_id);
        atomicAdd(guide[base + SP_GUIDE_PENDING + ind.emit_cell], sp_guide_spot_weight(relative, ind.toward));
      }
      atomicAdd(admission_histogram[sp_admission_bin(ind, step_input.inv_indicator_size)], 1u);
    }
    uint casts = subgroupAdd(connected);
    if (subgroupElect() && casts > 0u) atomicAdd(control.step_connections, casts);
    return;
  }
  if (valid) {
    ind = capture[i];
    bin = sp_admission_bin(ind, step_input.inv_indicator_size);
  }
  uint tiebreak = valid ? sp_admission_tiebreak(ind) : 0u;
  if (phase == SP_ADMIT_TIEBREAK_HISTOGRAM) {
    if (valid && sp_in_tiebreak_bin(bin)) atomicAdd(admission_histogram[tiebreak], 1u);
    return;
  }
  bool admit = valid && sp_admitted(bin, tiebreak);
  uvec4 ballot = subgroupBallot(admit);
  uint total = subgroupBallotBitCount(ballot);
  if (total == 0u) return;
  uint base = 0u;
  if (subgroupElect()) base = atomicAdd(control.admit_count, total);
  base = subgroupBroadcastFirst(base);
  // At most the budget <= capacity are admitted, so no two share a slot.
  if (admit) ring[(control.ring_head + base + subgroupBallotExclusiveBitCount(ballot)) % capacity] = ind;
}
