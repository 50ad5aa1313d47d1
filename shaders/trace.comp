#version 460
// Stage (b)/(d): one BVH query per queued ray -- the forward cast of an
// Active ray (closest hit), or the matter query of a ResolvingPenetration ray
// (the nearest faces behind p_in, then where it leaves matter: sp_matter.h).
// Both walk the same BVH, so one dispatch serves both.
#extension GL_GOOGLE_include_directive : require
#include "gpu_bindings.glsl"
#include "sp_traverse.h"
#include "sp_ray_model.h"

layout(local_size_x = SP_WORKGROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  bool valid = i < queue_length(push.queue_in);
  if (valid) {
    uint ray_index = queue_entry(push.queue_in, i);
    RayState r = rays[ray_index];
    CastResult found;
    if (r.state == SP_RAY_RESOLVING) {
      HitList list;
      sp_nearest_hits(r.entry, r.dir, sp_matter_tmin(), step_input.params.max_wall_thickness, list);
      found = sp_find_exit(list, r.entry_triangle);
    } else {
      HitInfo hit = sp_closest_hit(r.origin, r.dir, 0.0f, sp_active_reach(r, step_input.params));
      found = CastResult(hit.t, hit.triangle, 0.0f, 0u);
    }
    hits[ray_index] = found;
  }
  uint casts = subgroupAdd(valid ? 1u : 0u);
  if (subgroupElect() && casts > 0u) atomicAdd(control.step_casts, casts);
}
