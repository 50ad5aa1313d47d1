// Closest-hit ray queries over the flattened BVH, shared by GLSL and C++.
//
// Triangle test: Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection",
// JCGT 2(1), 2013 -- two-sided, without its double-precision fallback (an
// edge exactly hit by both neighbours counts for both, which is still
// watertight). Box test: slab test with the conservative far-distance scaling
// of Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013.
//
// Buffers: C++ passes `const BvhNode* bvh_nodes, const BvhTriangle*
// bvh_triangles` through SP_BVH_ARGS_DECL; GLSL includes gpu_bindings.glsl,
// whose accessors read the tree, before this file and defines
// SP_BVH_ARGS_DECL empty.
#ifndef SP_TRAVERSE_H
#define SP_TRAVERSE_H

#include "sp_types.h"

#ifdef __cplusplus
#define SP_BVH_ARGS_DECL const BvhNode *bvh_nodes, const BvhTriangle *bvh_triangles,
#define SP_BVH_ARGS bvh_nodes, bvh_triangles,
#define SP_NODE_ARGS_DECL const BvhNode *bvh_nodes,  // for what reads the nodes only
#define SP_NODE_ARGS bvh_nodes,
#else
#define SP_BVH_ARGS_DECL
#define SP_BVH_ARGS
#define SP_NODE_ARGS_DECL
#define SP_NODE_ARGS
#endif

// The walks read the tree through these accessors. C++ reads the arrays;
// GLSL calls gpu_bindings.glsl's functions, which read uniform texel
// buffers where the device allows (docs/model.md#the-tree-as-texels). A
// node's children are tested before it is entered, and the test reads the
// two texels that also hold the child's first index and count: the walks
// keep those of the node they enter, and read them again only for a node
// popped from the stack. They read the entered child's two fields as
// `enter_left ? FIELD(left) : FIELD(left + 1u)`, not at a chosen index, so
// that the fetches are the box tests' own.
#ifdef __cplusplus
#define SP_NODE_MIN(i) bvh_nodes[i].bmin
#define SP_NODE_MAX(i) bvh_nodes[i].bmax
#define SP_NODE_FIRST(i) bvh_nodes[i].left_or_first
#define SP_NODE_COUNT(i) bvh_nodes[i].count
#define SP_TRIANGLE_V0(i) bvh_triangles[i].v0
#define SP_TRIANGLE_V1(i) bvh_triangles[i].v1
#define SP_TRIANGLE_V2(i) bvh_triangles[i].v2
#define SP_TRIANGLE_SCENE_INDEX(i) bvh_triangles[i].scene_index
#define SP_TRIANGLE_SOLID(i) bvh_triangles[i].solid
#define SP_TRIANGLE_NORMAL(i) bvh_triangles[i].normal
#else
#define SP_NODE_MIN(i) sp_bvh_node_min(i)
#define SP_NODE_MAX(i) sp_bvh_node_max(i)
#define SP_NODE_FIRST(i) sp_bvh_node_first(i)
#define SP_NODE_COUNT(i) sp_bvh_node_count(i)
#define SP_TRIANGLE_V0(i) sp_bvh_triangle_v0(i)
#define SP_TRIANGLE_V1(i) sp_bvh_triangle_v1(i)
#define SP_TRIANGLE_V2(i) sp_bvh_triangle_v2(i)
#define SP_TRIANGLE_SCENE_INDEX(i) sp_bvh_triangle_scene_index(i)
#define SP_TRIANGLE_SOLID(i) sp_bvh_triangle_solid(i)
#define SP_TRIANGLE_NORMAL(i) sp_bvh_triangle_normal(i)
#endif

SP_BEGIN_NAMESPACE

// Per-ray constants of the watertight test and the slab test.
// Local to one traversal, never in a buffer: no layout to agree on.
struct RayQuery {
  vec3 origin;
  float tmin;  // hits must lie in (tmin, tmax]
  vec3 dir;
  float tmax;
  vec3 inv_dir;
  int kx;      // int, not uint: GLM indexes with int, and clang's -Wconversion
  vec3 shear;  // Sx, Sy, Sz of Woop et al.
  int ky;      // would flag every unsigned index
  int kz;
  uint parallel_axes;  // bit i: |dir[i]| <= 1e-20, the slab test needs care
};

SP_INLINE float sp_safe_inverse(float d) {
  // Avoids 0 * inf = NaN in the slab test for axis-parallel rays.
  SP_PRECISE float safe = abs(d) > 1.0e-20f ? d : (d < 0.0f ? -1.0e-20f : 1.0e-20f);
  return 1.0f / safe;
}

SP_INLINE RayQuery sp_make_query(vec3 origin, vec3 dir, float tmin, float tmax) {
  RayQuery q;
  q.origin = origin;
  q.dir = dir;
  q.tmin = tmin;
  q.tmax = tmax;
  q.inv_dir = vec3(sp_safe_inverse(dir.x), sp_safe_inverse(dir.y), sp_safe_inverse(dir.z));
  q.parallel_axes =
      (abs(dir.x) <= 1.0e-20f ? 1u : 0u) | (abs(dir.y) <= 1.0e-20f ? 2u : 0u) | (abs(dir.z) <= 1.0e-20f ? 4u : 0u);
  vec3 a = abs(dir);
  int kz = (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = (kz + 1) % 3;
  int ky = (kx + 1) % 3;
  if (dir[kz] < 0.0f) {  // keep the winding, as Woop et al. do
    int tmp = kx;
    kx = ky;
    ky = tmp;
  }
  q.kx = kx;
  q.ky = ky;
  q.kz = kz;
  q.shear = vec3(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0f / dir[kz]);
  return q;
}

// Returns the hit distance, or SP_FAR when the ray misses the triangle's plane
// region. The caller applies the (tmin, tmax] window.
SP_INLINE float sp_intersect_triangle(RayQuery q, vec3 v0, vec3 v1, vec3 v2) {
  SP_PRECISE vec3 a = v0 - q.origin;
  SP_PRECISE vec3 b = v1 - q.origin;
  SP_PRECISE vec3 c = v2 - q.origin;
  SP_PRECISE float ax = a[q.kx] - q.shear.x * a[q.kz];
  SP_PRECISE float ay = a[q.ky] - q.shear.y * a[q.kz];
  SP_PRECISE float bx = b[q.kx] - q.shear.x * b[q.kz];
  SP_PRECISE float by = b[q.ky] - q.shear.y * b[q.kz];
  SP_PRECISE float cx = c[q.kx] - q.shear.x * c[q.kz];
  SP_PRECISE float cy = c[q.ky] - q.shear.y * c[q.kz];
  SP_PRECISE float u = cx * by - cy * bx;
  SP_PRECISE float v = ax * cy - ay * cx;
  SP_PRECISE float w = bx * ay - by * ax;
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return SP_FAR;
  SP_PRECISE float det = u + v + w;
  if (det == 0.0f) return SP_FAR;
  SP_PRECISE float az = q.shear.z * a[q.kz];
  SP_PRECISE float bz = q.shear.z * b[q.kz];
  SP_PRECISE float cz = q.shear.z * c[q.kz];
  SP_PRECISE float t_scaled = u * az + v * bz + w * cz;
  return t_scaled / det;
}

// A box's exit distance moved away from its entry by the rounding of both,
// so that the box test stays conservative: the slab distances carry a
// relative error of gamma(3) each (Ize 2013, whose argument takes
// 0 <= tnear <= tfar). A positive exit is scaled by 1 + 2 * gamma(3). A
// negative one (a box behind the origin, which the matter query's
// look-back of SP_CONTACT_TOLERANCE reaches) must move towards zero
// instead: scaled up it would shrink, and a flat box (the leaf of one
// axis-aligned face), whose entry and exit coincide, would miss. It needs
// x * (1 - gamma(3)) / (1 + gamma(3)) = x * (1 - 6u) after the multiply's
// own rounding, u = 2^-24: SP_BOX_MARGIN_BEHIND is 1 - 7u, one u to spare
// for that rounding (1 - 6u would fall short by it).
#define SP_BOX_MARGIN 1.0000004f
#define SP_BOX_MARGIN_BEHIND 0.9999996f
SP_INLINE float sp_box_far_margin(float tfar) { return tfar * (tfar < 0.0f ? SP_BOX_MARGIN_BEHIND : SP_BOX_MARGIN); }

// Entry distance of the ray into the box, or SP_FAR when it misses the box
// within [tmin, tmax].
SP_INLINE float sp_intersect_box(RayQuery q, vec3 bmin, vec3 bmax, float tmax) {
  SP_PRECISE vec3 t0 = (bmin - q.origin) * q.inv_dir;
  SP_PRECISE vec3 t1 = (bmax - q.origin) * q.inv_dir;
  vec3 tlo = min(t0, t1);
  vec3 thi = max(t0, t1);
  // sp_safe_inverse saturates: for a ray parallel to a slab, (b - o) * inv_dir
  // underestimates the exit (0 on a face plane), yet a ray inside the slab
  // never leaves it.
  if (q.parallel_axes != 0u) {
    for (int i = 0; i < 3; ++i) {
      bool parallel = (q.parallel_axes & (1u << uint(i))) != 0u;
      if (parallel && q.origin[i] >= bmin[i] && q.origin[i] <= bmax[i]) thi[i] = SP_FAR;
    }
  }
  float tnear = max(max(tlo.x, tlo.y), max(tlo.z, q.tmin));
  float tfar = sp_box_far_margin(min(min(thi.x, thi.y), min(thi.z, tmax)));
  return tnear <= tfar ? tnear : SP_FAR;
}

// sp_intersect_box's answer for a box it reached at entry distance `entry`
// under a far limit, now that the limit has shrunk to `tmax`: the walks'
// limits only shrink, and sp_box_far_margin is monotonic, so the earlier
// test's margin(min(exit, limit)) >= entry leaves only the new limit to
// check. The same answer without reading the box again: a waiting node
// costs no memory traffic when it is popped (on lavapipe each buffer read
// of a divergent address is a loop over the lanes).
SP_INLINE bool sp_box_still_reached(float entry, float tmax) { return entry <= sp_box_far_margin(tmax); }

// Is (t, scene_index) a better hit than (best_t, best_scene)? Closest wins;
// equal distances go to the triangle first in scene order
// (docs/model.md#closest-hit).
SP_INLINE bool sp_better_hit(float t, uint scene_index, float best_t, uint best_scene) {
  return t < best_t || (t == best_t && scene_index < best_scene);
}

// Which child a walk enters once its box tests gave the entry distances
// t_left and t_right, at least one of them reached (< SP_FAR): the nearer,
// the left one on a tie.
SP_INLINE bool sp_enter_left(float t_left, float t_right) {
  return t_right == SP_FAR || (t_left != SP_FAR && t_left <= t_right);
}

// A walk's step down the inner node whose children start at `left`: their
// box tests under the far limit `limit`, then, when at least one is
// reached, the child entered (sp_enter_left), read as the box tests read
// it, and the other, which waits on the stack when it was reached too.
struct SpDescent {
  uint reached;  // 0: neither child is, the walk pops
  uint node_count;
  uint node_first;
  uint waiting;  // pushed when `pushes` is 1, with its entry distance
  float waiting_entry;
  uint pushes;
};

SP_INLINE SpDescent sp_descend(SP_NODE_ARGS_DECL RayQuery q, uint left, float limit) {
  float t_left = sp_intersect_box(q, SP_NODE_MIN(left), SP_NODE_MAX(left), limit);
  float t_right = sp_intersect_box(q, SP_NODE_MIN(left + 1u), SP_NODE_MAX(left + 1u), limit);
  bool enter_left = sp_enter_left(t_left, t_right);
  SpDescent d;
  d.reached = t_left != SP_FAR || t_right != SP_FAR ? 1u : 0u;
  d.node_count = enter_left ? SP_NODE_COUNT(left) : SP_NODE_COUNT(left + 1u);
  d.node_first = enter_left ? SP_NODE_FIRST(left) : SP_NODE_FIRST(left + 1u);
  d.waiting = enter_left ? left + 1u : left;
  d.waiting_entry = enter_left ? t_right : t_left;
  d.pushes = t_left != SP_FAR && t_right != SP_FAR ? 1u : 0u;
  return d;
}

// Closest hit with distance in (tmin, tmax]. Two-sided triangles. A walk
// whose next leaf would take it past SP_MAX_CAST_PACKETS ends there with no
// hit and cut_short set.
SP_INLINE HitInfo sp_closest_hit(SP_BVH_ARGS_DECL vec3 origin, vec3 dir, float tmin, float tmax) {
  RayQuery q = sp_make_query(origin, dir, tmin, tmax);
  HitInfo best;
  best.t = tmax;
  best.triangle = SP_INVALID;
  best.cut_short = 0u;
  uint best_scene = SP_INVALID;  // lets a hit at exactly tmax through

  uint stack[SP_BVH_MAX_DEPTH];
  float stack_entry[SP_BVH_MAX_DEPTH];  // each waiting node's entry distance
  uint stack_size = 0u;
  uint node_count = SP_NODE_COUNT(0u);
  uint node_first = SP_NODE_FIRST(0u);
  uint packets = 0u;  // work done: SP_MAX_CAST_PACKETS bounds it
  if (sp_intersect_box(q, SP_NODE_MIN(0u), SP_NODE_MAX(0u), best.t) == SP_FAR) return best;

  for (;;) {
    // Down the inner nodes to a leaf: into the nearer child reached, the
    // farther, if reached too, waiting on the stack; stopped where neither
    // child is reached. The inner nodes have a loop of their own, so that
    // lanes walking side by side run the leaf's code together, once they
    // have all reached a leaf (docs/model.md#the-walks-loops); each walk
    // visits the same nodes in the same order as with one loop.
    bool at_leaf = true;
    while (node_count == 0u) {
      SpDescent down = sp_descend(SP_NODE_ARGS q, node_first, best.t);
      if (down.reached == 0u) {
        at_leaf = false;
        break;
      }
      if (down.pushes != 0u) {
        stack[stack_size] = down.waiting;
        stack_entry[stack_size] = down.waiting_entry;
        stack_size += 1u;
      }
      node_count = down.node_count;
      node_first = down.node_first;
    }
    if (at_leaf) {
      packets += SP_LEAF_PACKETS(node_count);
      if (packets > SP_MAX_CAST_PACKETS) {
        best.t = tmax;
        best.triangle = SP_INVALID;
        best.cut_short = 1u;
        return best;
      }
      for (uint i = node_first; i < node_first + node_count; ++i) {
        float t = sp_intersect_triangle(q, SP_TRIANGLE_V0(i), SP_TRIANGLE_V1(i), SP_TRIANGLE_V2(i));
        // t == SP_FAR is the triangle test's "miss", whatever tmax is.
        if (t < SP_FAR && t > q.tmin && t <= q.tmax &&
            sp_better_hit(t, SP_TRIANGLE_SCENE_INDEX(i), best.t, best_scene)) {
          best.t = t;
          best.triangle = i;
          best_scene = SP_TRIANGLE_SCENE_INDEX(i);
        }
      }
    }
    // Pop, skipping nodes that a closer hit has since ruled out: the box
    // test again with the smaller far limit, without reading the box
    // (sp_box_still_reached).
    bool found = false;
    uint popped = 0u;
    while (stack_size > 0u && !found) {
      stack_size -= 1u;
      popped = stack[stack_size];
      found = sp_box_still_reached(stack_entry[stack_size], best.t);
    }
    if (!found) break;
    node_count = SP_NODE_COUNT(popped);
    node_first = SP_NODE_FIRST(popped);
  }
  return best;
}

// Whether anything lies on the segment from `origin` along `dir` with
// distance in (tmin, tmax]: the occlusion query of a spot's way to the
// listener (sp_connect.h), with sp_closest_hit's acceptance (t in (tmin,
// tmax]). It walks the tree as sp_closest_hit does with nothing found yet
// and stops at the first triangle it meets, so it is blocked exactly when
// sp_closest_hit finds a hit or runs out of work. A walk that
// would pass SP_MAX_CAST_PACKETS counts as blocked: the way is not known
// to be open.
SP_INLINE bool sp_segment_blocked(SP_BVH_ARGS_DECL vec3 origin, vec3 dir, float tmin, float tmax) {
  RayQuery q = sp_make_query(origin, dir, tmin, tmax);
  uint stack[SP_BVH_MAX_DEPTH];
  uint stack_size = 0u;
  uint node_count = SP_NODE_COUNT(0u);
  uint node_first = SP_NODE_FIRST(0u);
  uint packets = 0u;
  if (sp_intersect_box(q, SP_NODE_MIN(0u), SP_NODE_MAX(0u), tmax) == SP_FAR) return false;
  for (;;) {
    bool at_leaf = true;
    while (node_count == 0u) {
      SpDescent down = sp_descend(SP_NODE_ARGS q, node_first, tmax);
      if (down.reached == 0u) {
        at_leaf = false;
        break;
      }
      if (down.pushes != 0u) stack[stack_size++] = down.waiting;
      node_count = down.node_count;
      node_first = down.node_first;
    }
    if (at_leaf) {
      packets += SP_LEAF_PACKETS(node_count);
      if (packets > SP_MAX_CAST_PACKETS) return true;
      for (uint i = node_first; i < node_first + node_count; ++i) {
        float t = sp_intersect_triangle(q, SP_TRIANGLE_V0(i), SP_TRIANGLE_V1(i), SP_TRIANGLE_V2(i));
        if (t < SP_FAR && t > q.tmin && t <= q.tmax) return true;
      }
    }
    if (stack_size == 0u) break;
    stack_size -= 1u;
    uint popped = stack[stack_size];
    node_count = SP_NODE_COUNT(popped);
    node_first = SP_NODE_FIRST(popped);
  }
  return false;
}

// SP_CROSSING_* of a face with unit front normal `normal` for a ray along
// `dir`: entering when its front faces the ray.
SP_INLINE uint sp_crossing(vec3 normal, vec3 dir) {
  SP_PRECISE float s = normal.x * dir.x + normal.y * dir.y + normal.z * dir.z;
  return s < 0.0f ? SP_CROSSING_ENTER : (s > 0.0f ? SP_CROSSING_LEAVE : SP_CROSSING_NONE);
}

// Inserts (t, triangle, key) into the sorted list when it is among the
// SP_MATTER_MAX_HITS nearest by (t, triangle); the farthest falls off a full
// list. (Ties go by leaf order, not scene order as for the closest hit: faces
// at one distance are crossed together anyway, and the list holds a word
// less per entry; both backends share the tree, so they agree.) A face crossed like a listed one of the same solid within
// SP_CONTACT_TOLERANCE of it is that face's twin across a shared edge (or a
// fold thinner than the tolerance): it is left out. So is a leaving face
// behind the origin (t < 0, the look-back): a ray that penetrated came to
// p_in through air and left no solid there (sp_find_exit). Dropped here,
// it takes no place in the list and cannot stand in as the twin of a
// leaving face just ahead.
SP_INLINE void sp_hit_list_offer(SP_INOUT(HitList) list, float t, uint triangle, uint key) {
  if (t < 0.0f && (key & 3u) == SP_CROSSING_LEAVE) return;
  if ((key & 3u) != SP_CROSSING_NONE) {
    for (uint e = 0u; e < list.count; ++e) {
      SP_PRECISE float gap = abs(list.t[e] - t);
      if (list.key[e] == key && gap <= SP_CONTACT_TOLERANCE) return;
    }
  }
  uint at = list.count;
  if (at == SP_MATTER_MAX_HITS) {
    if (!sp_better_hit(t, triangle, list.t[at - 1u], list.triangle[at - 1u])) return;
    at -= 1u;
  } else {
    list.count += 1u;
  }
  while (at > 0u && sp_better_hit(t, triangle, list.t[at - 1u], list.triangle[at - 1u])) {
    list.t[at] = list.t[at - 1u];
    list.triangle[at] = list.triangle[at - 1u];
    list.key[at] = list.key[at - 1u];
    at -= 1u;
  }
  list.t[at] = t;
  list.triangle[at] = triangle;
  list.key[at] = key;
}

// Far limit of the boxes still worth visiting: the worst listed hit once the
// list is full (a hit exactly there may still win on leaf order), else tmax.
SP_INLINE float sp_hit_list_limit(uint count, float worst, float tmax) {
  return count == SP_MATTER_MAX_HITS ? worst : tmax;
}

// The SP_MATTER_MAX_HITS nearest hits with distance in (tmin, tmax], sorted
// by (t, leaf order), twins across shared edges once (sp_hit_list_offer);
// tmin may be negative. The same walk as sp_closest_hit with the list's
// limit in place of the best hit; written out twice because GLSL has no
// templates, and the closest hit, every ray's hot path, must not carry the
// list's registers.
SP_INLINE void sp_nearest_hits(SP_BVH_ARGS_DECL vec3 origin, vec3 dir, float tmin, float tmax, SP_OUT(HitList) list) {
  RayQuery q = sp_make_query(origin, dir, tmin, tmax);
  list.count = 0u;
  list.cut_short = 0u;
  list.t[SP_MATTER_MAX_HITS - 1u] = tmax;  // read by the limit before the list is full
  uint stack[SP_BVH_MAX_DEPTH];
  float stack_entry[SP_BVH_MAX_DEPTH];  // each waiting node's entry distance
  uint stack_size = 0u;
  uint node_count = SP_NODE_COUNT(0u);
  uint node_first = SP_NODE_FIRST(0u);
  uint packets = 0u;  // work done: SP_MAX_CAST_PACKETS bounds it
  if (sp_intersect_box(q, SP_NODE_MIN(0u), SP_NODE_MAX(0u), tmax) == SP_FAR) return;

  for (;;) {
    bool at_leaf = true;
    while (node_count == 0u) {
      float limit = sp_hit_list_limit(list.count, list.t[SP_MATTER_MAX_HITS - 1u], tmax);
      SpDescent down = sp_descend(SP_NODE_ARGS q, node_first, limit);
      if (down.reached == 0u) {
        at_leaf = false;
        break;
      }
      if (down.pushes != 0u) {
        stack[stack_size] = down.waiting;
        stack_entry[stack_size] = down.waiting_entry;
        stack_size += 1u;
      }
      node_count = down.node_count;
      node_first = down.node_first;
    }
    if (at_leaf) {
      packets += SP_LEAF_PACKETS(node_count);
      if (packets > SP_MAX_CAST_PACKETS) {
        list.cut_short = 1u;
        return;
      }
      for (uint i = node_first; i < node_first + node_count; ++i) {
        float t = sp_intersect_triangle(q, SP_TRIANGLE_V0(i), SP_TRIANGLE_V1(i), SP_TRIANGLE_V2(i));
        if (t < SP_FAR && t > q.tmin && t <= q.tmax)
          sp_hit_list_offer(list, t, i, SP_TRIANGLE_SOLID(i) * 4u + sp_crossing(SP_TRIANGLE_NORMAL(i), q.dir));
      }
    }
    bool found = false;
    uint popped = 0u;
    while (stack_size > 0u && !found) {
      stack_size -= 1u;
      popped = stack[stack_size];
      found = sp_box_still_reached(stack_entry[stack_size],
                                   sp_hit_list_limit(list.count, list.t[SP_MATTER_MAX_HITS - 1u], tmax));
    }
    if (!found) break;
    node_count = SP_NODE_COUNT(popped);
    node_first = SP_NODE_FIRST(popped);
  }
}

SP_END_NAMESPACE

#endif  // SP_TRAVERSE_H
