#version 460
// After the casts to the listener, whose last subgroup planned the step's
// admission (sp_admission.h): the ring's share of the step's indicators
// goes in, in two passes over the capture list (push.finish, SP_ADMIT_*;
// admission_passes.glsl says what each does). Each pass's last subgroup
// does what follows it: the tie-break's plans the tie-breaks and the
// places, the copy's moves the ring's head. A step of at most
// kAdmitInlineMax spots dispatches no group here: connect.comp's last
// subgroup ran both passes.
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "admission_passes.glsl"

layout(local_size_x = SP_WORKGROUP_SIZE, local_size_x_id = SP_SPEC_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < control.step_indicators;
  if (push.finish == SP_ADMIT_TIEBREAK) {
    admission_tiebreak_entry(i, valid);
    if (last_subgroup(SP_TICKET_TIEBREAK)) admission_decide_tiebreaks();
    return;
  }
  admission_copy_entry(i, valid);
  if (last_subgroup(SP_TICKET_COPY) && subgroupElect()) admission_finish_copy();
}
