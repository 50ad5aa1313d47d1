// The two passes of the ring's admission over a step's capture list
// (sp_admission.h has the rule), each written for one capture entry per
// invocation:
// - tie-break: an indicator at or above its class's threshold bin is
//   admitted and marked in a bitmap of canonical keys; one in the bin just
//   below (where the class's share runs out) counts its tie-break bin and
//   is listed. Then one subgroup plans the tie-breaks, marks the listed
//   ones they admit, and writes the running counts of the bitmap's words:
//   each admitted indicator's place, so that the ring holds a step's spots
//   in canonical order, as the CPU's does;
// - copy: the admitted indicators into the ring at their places, and what
//   the histograms counted cleared for the next step; then one invocation
//   moves the ring's head.
// admit.comp runs them as two dispatches over the list; a step of at most
// kAdmitInlineMax spots has them run by connect.comp's last subgroup
// instead (admission_inline), which saves two dispatches and their round
// trips.
// Every function is reached by whole subgroups (uniform control flow):
// they use subgroup operations.
#include "sp_admission.h"

// A step with at most this many indicators is admitted by connect.comp's
// last subgroup, the admit dispatches then dispatching no group
// (gpu::inline_admission_max: one workgroup's worth on a GPU, every step
// on a CPU device).
layout(constant_id = SP_SPEC_ADMIT_INLINE_MAX) const uint kAdmitInlineMax = SP_WORKGROUP_SIZE;

// The canonical key of an indicator of this step: (iteration, ray, kind).
uint order_key(Indicator ind) { return (ind.iteration * push.max_rays + ind.ray_index) * 2u + ind.kind; }

void mark(Indicator ind) {
  uint key = order_key(ind);
  atomicOr(admission_histogram[SP_ORDER_BITMAP + key / 32u], 1u << (key % 32u));
}

// Capture entry i and its admission bin when valid; bin 0 otherwise.
uint capture_entry(uint i, bool valid, out Indicator ind) {
  if (!valid) return 0u;
  ind = load_capture(i);
  return sp_admission_bin(ind, step_input.inv_indicator_size);
}

// The tie-break pass for capture entry i (valid: i is in the list).
void admission_tiebreak_entry(uint i, bool valid) {
  Indicator ind;
  uint bin = capture_entry(i, valid, ind);
  uint threshold = admission_histogram[SP_ADMISSION_PLAN_THRESHOLD + sp_bin_class(bin)];
  if (valid && bin >= threshold) mark(ind);
  bool tied = valid && bin + 1u == threshold;
  if (tied) atomicAdd(admission_histogram[SP_ADMISSION_TIEBREAKS + sp_admission_tiebreak(ind)], 1u);
  uvec4 ballot = subgroupBallot(tied);
  uint total = subgroupBallotBitCount(ballot);
  uint at = 0u;
  if (subgroupElect() && total > 0u) at = atomicAdd(control.tiebreak_count, total);
  at = subgroupBroadcastFirst(at) + subgroupBallotExclusiveBitCount(ballot);
  if (tied) admission_histogram[SP_TIEBREAK_LIST(push.max_rays, push.iterations) + at] = i;
}

// After the tie-break pass, by one subgroup: the tie-break thresholds, the
// listed indicators they admit, then the running count of admitted keys
// before each bitmap word (stored after the bitmap), a subgroup's width of
// words at a time.
void admission_decide_tiebreaks() {
  if (subgroupElect()) sp_plan_tiebreak(SP_ADMISSION_CLASSES);
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  uint lane = gl_SubgroupInvocationID;
  uint listed = control.tiebreak_count;
  uint list = SP_TIEBREAK_LIST(push.max_rays, push.iterations);
  for (uint k = lane; k < listed; k += gl_SubgroupSize) {
    Indicator ind = load_capture(admission_histogram[list + k]);
    uint c = sp_bin_class(sp_admission_bin(ind, step_input.inv_indicator_size));
    if (sp_admission_tiebreak(ind) >= admission_histogram[SP_ADMISSION_PLAN_TIEBREAK + c]) mark(ind);
  }
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  uint words = SP_ORDER_WORDS(push.max_rays, push.iterations);
  uint before = 0u;
  for (uint first = 0u; first < words; first += gl_SubgroupSize) {
    uint w = first + lane;
    uint here = w < words ? bitCount(admission_histogram[SP_ORDER_BITMAP + w]) : 0u;
    if (w < words) admission_histogram[SP_ORDER_BITMAP + words + w] = before + subgroupExclusiveAdd(here);
    before += subgroupAdd(here);
  }
}

// The copy pass for capture entry i (valid: i is in the list).
void admission_copy_entry(uint i, bool valid) {
  Indicator ind;
  uint bin = capture_entry(i, valid, ind);
  uint tiebreak = valid ? sp_admission_tiebreak(ind) : 0u;
  bool admit = valid && sp_admitted(bin, tiebreak);
  // Only the bins and classes of this step's indicators can be non-zero;
  // the plan and the order, read below, are not cleared.
  if (valid) {
    admission_histogram[bin] = 0u;
    admission_histogram[SP_ADMISSION_TIEBREAKS + tiebreak] = 0u;
    admission_histogram[SP_ADMISSION_CLASS_COUNTS + sp_bin_class(bin)] = 0u;
  }
  uint total = subgroupAdd(admit ? 1u : 0u);
  if (subgroupElect() && total > 0u) atomicAdd(control.admit_count, total);
  if (admit) {
    // Its place: how many admitted keys come before it. At most the
    // budget <= capacity are admitted, so no two share a slot.
    uint key = order_key(ind);
    uint word = key / 32u;
    uint words = SP_ORDER_WORDS(push.max_rays, push.iterations);
    uint rank = admission_histogram[SP_ORDER_BITMAP + words + word] +
                bitCount(admission_histogram[SP_ORDER_BITMAP + word] & ((1u << (key % 32u)) - 1u));
    store_ring((control.ring_head + rank) % step_input.ring_capacity, ind);
  }
}

// After the copy pass, by one invocation: the ring's head moves past what
// it admitted.
void admission_finish_copy() {
  uint capacity = step_input.ring_capacity;
  uint admitted = atomicAdd(control.admit_count, 0u);
  control.ring_head = (control.ring_head + admitted) % capacity;
  control.ring_filled = min(capacity, control.ring_filled + admitted);
  control.draw_instance_count = control.ring_filled;
}

// Both passes by one subgroup over a list of at most kAdmitInlineMax
// indicators, once the admission is planned.
void admission_inline(uint listed) {
  for (uint first = 0u; first < listed; first += gl_SubgroupSize)
    admission_tiebreak_entry(first + gl_SubgroupInvocationID, first + gl_SubgroupInvocationID < listed);
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  admission_decide_tiebreaks();
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  for (uint first = 0u; first < listed; first += gl_SubgroupSize)
    admission_copy_entry(first + gl_SubgroupInvocationID, first + gl_SubgroupInvocationID < listed);
  subgroupMemoryBarrierBuffer();
  subgroupBarrier();
  if (subgroupElect()) admission_finish_copy();
}
