#version 460
// Stage (b)/(d): one closest-hit query per queued ray -- the forward cast of
// an Active ray or the backcast of a ResolvingPenetration ray (both are the
// same BVH query on a different segment, so one dispatch serves both).
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_traverse.h"
#include "sp_ray_model.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < control.queues[push.queue_in].count;
  if (valid) {
    uint ray_index = queue_entries[push.queue_in * push.max_rays + i];
    RayState r = rays[ray_index];
    hits[ray_index] = sp_closest_hit(sp_cast_origin(r), r.dir, sp_cast_tmin(r), sp_cast_tmax(r, step_input.params));
  }
  uint casts = subgroupAdd(valid ? 1u : 0u);
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_casts, casts);
}
