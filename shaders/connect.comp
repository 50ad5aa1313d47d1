#version 460
// After a step's last wavefront iteration, before admission: casts each
// queued spot's way to the listener and completes what it hears
// (sp_connect.h), and adds what a heard spot is worth to its source's guide
// (sp_guide.h). Resolve queued only the spots worth a cast (the others are
// already marked unheard), so every thread of this dispatch casts.
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_connect.h"
#include "sp_guide.h"
#include "sp_traverse.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < control.connect_count;
  if (valid) {
    uint slot = connect_queue[i];
    Indicator ind = capture[slot];
    SimParams p = step_input.params;
    Connection c = sp_connection(ind, p);
    bool open = !sp_segment_blocked(c.origin, c.dir, 0.0f, c.distance);
    sp_finish_connection(ind, c, open, step_sources[ind.source_slot], p);
    // Only what the connection changed goes back.
    capture[slot].heard = ind.heard;
    capture[slot].toward = ind.toward;
    if (ind.heard > 0.0f) {
      float relative = sp_heard_relative(ind, step_input.inv_indicator_size);
      uint base = sp_guide_base(step_sources[ind.source_slot].source_id);
      atomicAdd(guide[base + SP_GUIDE_PENDING + ind.emit_cell], sp_guide_spot_weight(relative, ind.toward));
    }
  }
  uint casts = subgroupAdd(valid ? 1u : 0u);
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_connections, casts);
}
