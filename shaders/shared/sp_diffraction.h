// Diffraction at exposed edges, shared by GLSL and C++
// (docs/model.md#diffraction).
//
// A ray that strikes a face within `reach` of one of its exposed edges may
// turn round that edge into the geometric shadow behind it, instead of
// reflecting or penetrating: the struck-edge form of the uncertainty-
// relation deflection. The nearer the edge, the likelier the turn
// (probability 1 - a / reach) and the wider the angle (width sigma(a) =
// min(pi/2, 1 / (2 k a))). The angle into the shadow is drawn with
// P(theta > x) = sigma / (sigma + x), so what reaches the shadow falls with
// the angle. One ray in, one ray out: nothing is spawned, and the turned ray
// carries at most the energy it had.
//
// Only +, -, *, / and sqrt are used (sin and cos are fixed polynomials), so
// that both backends make bit-identical decisions.
#ifndef SP_DIFFRACTION_H
#define SP_DIFFRACTION_H

#include "sp_random.h"
#include "sp_types.h"

// Distances to an edge below this count as this (the width would diverge).
#define SP_DIFFRACTION_MIN_DISTANCE 1.0e-3f
// A turned ray starts this far out from the edge along the wedge's outer
// bisector, so that it never strikes the two faces that meet there.
#define SP_DIFFRACTION_OFFSET 1.0e-3f
#define SP_HALF_PI 1.57079633f

SP_BEGIN_NAMESPACE

// (sin x, cos x) for x in [0, pi], by Taylor polynomials about pi/2 (error
// below 1e-7): GPU and CPU sin/cos differ in their last bits, these do not.
SP_INLINE vec2 sp_sin_cos(float x) {
  SP_PRECISE float y = x - SP_HALF_PI;
  SP_PRECISE float y2 = y * y;
  SP_PRECISE float s =
      y * (1.0f + y2 * (-0.16666667f +
                        y2 * (0.0083333333f + y2 * (-0.00019841270f + y2 * (2.7557319e-6f + y2 * -2.5052108e-8f)))));
  SP_PRECISE float c =
      1.0f +
      y2 * (-0.5f + y2 * (0.041666667f +
                          y2 * (-0.0013888889f + y2 * (2.4801587e-5f + y2 * (-2.7557319e-7f + y2 * 2.0876757e-9f)))));
  return vec2(c, -s);  // sin(y + pi/2) = cos y, cos(y + pi/2) = -sin y
}

SP_INLINE vec3 sp_triangle_corner(BvhTriangle tri, uint i) { return i == 0u ? tri.v0 : (i == 1u ? tri.v1 : tri.v2); }

// The exposed edge of `tri` nearest `position` that diffracts under `p`
// (its surface turns by at least the edge angle), or SP_INVALID. `front`:
// the ray struck the front; at the back of a sheet only free boundaries
// count (every other exposed edge is concave from that side).
SP_INLINE uint sp_nearest_diffracting_edge(BvhTriangle tri, TriangleEdges edges, vec3 position, bool front, SimParams p,
                                           SP_OUT(float) distance, SP_OUT(vec3) nearest) {
  uint best = SP_INVALID;
  distance = SP_FAR;
  nearest = position;
  for (uint i = 0u; i < 3u; ++i) {
    if (((edges.exposed >> i) & 1u) == 0u) continue;
    float turn_cos = edges.turn_cos[int(i)];  // int: glm indexes with int (GLSL takes either)
    if (!(turn_cos <= p.edge_cos_max)) continue;
    if (!front && turn_cos > -1.0f) continue;
    vec3 a = sp_triangle_corner(tri, i);
    vec3 b = sp_triangle_corner(tri, (i + 1u) % 3u);
    SP_PRECISE vec3 ab = b - a;
    SP_PRECISE float len2 = dot(ab, ab);
    if (!(len2 > 0.0f)) continue;
    SP_PRECISE float along = clamp(dot(position - a, ab) / len2, 0.0f, 1.0f);
    SP_PRECISE vec3 q = a + ab * along;
    SP_PRECISE vec3 gap = position - q;
    SP_PRECISE float d = sqrt(dot(gap, gap));
    if (d < distance) {
      distance = d;
      best = i;
      nearest = q;
    }
  }
  return best;
}

// Turns `r`, which struck `tri` at `position` (normal: facing the ray), round
// an exposed edge when the draw says so. `random`: the interaction's hash,
// whose .x is the reflect/penetrate decision; .y decides whether to turn and
// .z draws the angle. Returns SP_OUTCOME_DIFFRACT when the ray turned (it
// may then be dead for want of energy). Returns 0 with `absorbed` false when
// it was too far from an edge or the draw said no: the caller goes on to
// reflect or penetrate. Returns 0 with `absorbed` true, the ray dead, when
// the angle drawn runs into the wedge: that share is lost, never created.
SP_INLINE uint sp_try_diffract(SP_INOUT(RayState) r, BvhTriangle tri, TriangleEdges edges, vec3 position, vec3 normal,
                               bool front, SimParams p, uvec4 random, SP_OUT(bool) absorbed) {
  absorbed = false;
  float a;
  vec3 q;
  uint edge = sp_nearest_diffracting_edge(tri, edges, position, front, p, a, q);
  if (edge == SP_INVALID || !(a < p.diffraction_reach)) return 0u;
  SP_PRECISE float chance = 1.0f - a / p.diffraction_reach;
  if (!(sp_unit_float(random.y) < chance)) return 0u;

  vec3 corner_a = sp_triangle_corner(tri, edge);
  vec3 corner_b = sp_triangle_corner(tri, (edge + 1u) % 3u);
  SP_PRECISE vec3 ab = corner_b - corner_a;
  SP_PRECISE vec3 along = ab / sqrt(dot(ab, ab));
  SP_PRECISE vec3 out_of_face = cross(along, tri.normal);  // in the face's plane, across the edge, outwards
  float turn_cos = edges.turn_cos[int(edge)];
  float turn_sin = edges.turn_sin[int(edge)];
  SP_PRECISE vec3 far_normal = turn_cos <= -1.0f ? -normal : tri.normal * turn_cos + out_of_face * turn_sin;

  // Keller's cone: the part along the edge stays; the part across it turns
  // by theta from the shadow boundary (the incoming direction) towards
  // -out_of_face, round the edge.
  SP_PRECISE float d_along = dot(r.dir, along);
  SP_PRECISE vec3 across = r.dir - along * d_along;
  SP_PRECISE float across_len = sqrt(dot(across, across));
  if (!(across_len > 1.0e-6f)) return 0u;  // running along the edge: no shadow to turn into
  SP_PRECISE vec3 u = across / across_len;
  SP_PRECISE vec3 v = cross(along, u);
  if (dot(v, out_of_face) > 0.0f) v = -v;

  SP_PRECISE float sigma = min(SP_HALF_PI, p.diffraction_width / max(a, SP_DIFFRACTION_MIN_DISTANCE));
  SP_PRECISE float draw = sp_unit_float(random.z);
  SP_PRECISE float theta = sigma * draw / (1.0f - draw);
  if (!(theta < SP_PI)) {
    absorbed = true;
  } else {
    vec2 sc = sp_sin_cos(theta);
    SP_PRECISE vec3 turned = (u * sc.y + v * sc.x) * across_len + along * d_along;
    SP_PRECISE vec3 dir = turned / sqrt(dot(turned, turned));
    if (!(dot(dir, far_normal) > 0.0f)) {
      absorbed = true;  // into the wedge
    } else {
      SP_PRECISE vec3 bisector = normal + far_normal;
      SP_PRECISE float bisector_len = sqrt(dot(bisector, bisector));
      SP_PRECISE vec3 outwards = bisector_len > 1.0e-3f ? bisector / bisector_len : out_of_face;
      SP_PRECISE vec3 to_edge = q - position;
      SP_PRECISE float travelled = r.travelled + sqrt(dot(to_edge, to_edge));
      SP_PRECISE float energy = r.energy * p.diffraction_gain;
      r.travelled = travelled;
      r.energy = energy;
      r.dir = dir;
      r.origin = q + outwards * SP_DIFFRACTION_OFFSET;
    }
  }
  r.diffractions += 1u;
  if (absorbed || r.energy <= p.min_energy) r.state = SP_RAY_DEAD;
  return absorbed ? 0u : SP_OUTCOME_DIFFRACT;
}

SP_END_NAMESPACE

#endif  // SP_DIFFRACTION_H
