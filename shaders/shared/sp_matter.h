// Matter: where a penetrating ray leaves the solids it entered, shared by
// GLSL and C++ (docs/model.md#matter-where-a-penetrating-ray-leaves).
//
// The paper's backcast takes the first surface behind the entry point as the
// way out (docs/model.md#why-the-papers-backcast-fails-on-real-levels). Real
// levels are built from solids that touch and overlap (a wall standing on a
// floor slab, brushes stacked by a level editor, a trim laid on a floor) and
// from open render meshes, where that surface is often the face of the next
// solid. Here the ray counts what it crosses instead: a face whose front
// (counter-clockwise side) faces against the ray puts it inside one more solid,
// a face whose front faces along the ray takes it out of one, and it leaves
// matter at the first face after which it is inside none.
//
// Buffers: C++ passes `const BvhTriangle* bvh_triangles, const
// LayerAcoustics* layers` through SP_MATTER_ARGS_DECL; GLSL declares storage
// buffers with those names before including this file.
#ifndef SP_MATTER_H
#define SP_MATTER_H

#include "sp_traverse.h"
#include "sp_types.h"

#ifdef __cplusplus
#define SP_MATTER_ARGS_DECL const BvhTriangle *bvh_triangles, const LayerAcoustics *layers,
#define SP_MATTER_ARGS bvh_triangles, layers,
#else
#define SP_MATTER_ARGS_DECL
#define SP_MATTER_ARGS
#endif

SP_BEGIN_NAMESPACE

// Removes `layer` from the stack of the layers of the solids the ray is
// inside: the innermost entry of that layer, else (winding that disagrees)
// the innermost one.
SP_INLINE void sp_matter_pop(SP_INOUT(uint) stack_size, SP_INOUT(uint) s0, SP_INOUT(uint) s1, SP_INOUT(uint) s2,
                             SP_INOUT(uint) s3, uint layer) {
  if (stack_size == 0u) return;
  uint at = stack_size - 1u;
  if (stack_size >= 4u && s3 == layer) at = 3u;
  else if (stack_size >= 3u && s2 == layer) at = 2u;
  else if (stack_size >= 2u && s1 == layer) at = 1u;
  else if (s0 == layer) at = 0u;
  // Close the gap: entries above `at` move down one.
  if (at == 0u) s0 = s1;
  if (at <= 1u) s1 = s2;
  if (at <= 2u) s2 = s3;
  stack_size -= 1u;
}

// Where a ray that penetrated `entry_triangle` at p_in leaves matter, given
// `list`: the nearest faces along its direction from p_in, with t in
// (-SP_CONTACT_TOLERANCE, W_max] (sp_nearest_hits). Rules (docs/model.md):
//  - faces within SP_CONTACT_TOLERANCE of the first face of a group are
//    crossed together; each solid (BvhTriangle::solid) in a group crosses
//    once: in when it has only entering faces there, out when only leaving
//    ones, not at all when both (an edge grazed, or a solid thinner than the
//    tolerance). The entry face opens the first group, at t = 0; sheets and
//    faces seen edge-on are not crossed, and the list holds no leaving
//    face behind p_in;
//  - the ray leaves matter after the first group that has a leaving face and
//    leaves it inside no solid (or fewer than none: winding that disagrees);
//    the exit face is that group's farthest leaving face;
//  - each stretch between groups loses its length times the attenuation of
//    the solid it lies in; where solids overlap, the largest of theirs
//    (SP_MATTER_STACK solids remembered);
//  - a full list whose last group may continue past it, or no exit in the
//    list: no way out (triangle SP_INVALID), the ray is absorbed.
// Members of a group are the list's entries [g, end) and, in the first
// group, the entry face (member index -1).
SP_INLINE CastResult sp_find_exit(SP_MATTER_ARGS_DECL HitList list, uint entry_triangle) {
  BvhTriangle entry = bvh_triangles[entry_triangle];
  uint entry_key = entry.solid * 4u + SP_CROSSING_ENTER;
  // Entries the walk does not cross: the entry face again, sheets, edge-on.
  // The list holds no leaving face behind p_in (sp_hit_list_offer drops
  // them): the ray came to p_in through air, so it left no solid there.
  // Such a face is the far side of a concave corner struck within the
  // look-back (the ceiling over a wall entered a fraction of a millimetre
  // below it), or the face the ray just left or was reflected from; counted
  // with the entry face it would cancel it as an edge grazed and let the
  // ray through the wall.
  uint skip = 0u;
  for (uint i = 0u; i < list.count; ++i) {
    bool crossed = list.triangle[i] != entry_triangle && (list.key[i] & 3u) != SP_CROSSING_NONE &&
                   !(layers[bvh_triangles[list.triangle[i]].layer].sheet_thickness > 0.0f);
    if (!crossed) skip |= 1u << i;
  }
  bool full = list.count == SP_MATTER_MAX_HITS;
  float last_t = list.t[SP_MATTER_MAX_HITS - 1u];

  CastResult result;
  result.t = 0.0f;
  result.triangle = SP_INVALID;
  result.matter_loss = 0.0f;
  result.flags = 0u;
  // A walk cut short saw only part of the faces: no way out is known.
  if (list.cut_short != 0u) {
    result.flags = SP_CAST_CUT_SHORT;
    return result;
  }
  // Layers of the solids the ray is inside (s0 .. s3).
  uint stack_size = 0u;
  uint s0 = 0u;
  uint s1 = 0u;
  uint s2 = 0u;
  uint s3 = 0u;
  int depth = 0;
  SP_PRECISE float loss = 0.0f;
  float position = 0.0f;
  uint g = 0u;
  bool first = true;
  while (first || g < list.count) {
    float group_t = first ? 0.0f : list.t[g];
    SP_PRECISE float group_end = group_t + SP_CONTACT_TOLERANCE;
    // Faces beyond a full list may still belong to this group.
    if (full && group_end >= last_t) break;
    uint end = first ? 0u : g + 1u;
    while (end < list.count && list.t[end] <= group_end) end += 1u;

    if (depth > 0 && group_t > position) {  // the stretch of matter before the group
      // The largest attenuation of the solids the stretch lies in, so that
      // where solids overlap the result does not depend on which was
      // entered first (brushes with flush faces are entered at once).
      float alpha = layers[stack_size > 0u ? s0 : entry.layer].attenuation;
      if (stack_size > 1u) alpha = max(alpha, layers[s1].attenuation);
      if (stack_size > 2u) alpha = max(alpha, layers[s2].attenuation);
      if (stack_size > 3u) alpha = max(alpha, layers[s3].attenuation);
      SP_PRECISE float stretch_loss = (group_t - position) * alpha;
      loss = loss + stretch_loss;
      position = group_t;
    }

    bool any_leaving = false;
    int delta = 0;
    int first_member = first ? -1 : int(g);
    // Solids left before solids entered, so that where one touches the next
    // a full stack has room for the second.
    for (uint pass = 0u; pass < 2u; ++pass) {
      for (int m = first_member; m < int(end); ++m) {
        if (m >= 0 && ((skip >> uint(m)) & 1u) != 0u) continue;
        uint solid = (m < 0 ? entry_key : list.key[m]) >> 2u;
        bool first_of_solid = true;
        for (int k = first_member; k < m; ++k) {
          bool counted = k < 0 || ((skip >> uint(k)) & 1u) == 0u;
          if (counted && ((k < 0 ? entry_key : list.key[k]) >> 2u) == solid) first_of_solid = false;
        }
        if (!first_of_solid) continue;
        int enter_member = -2;  // none
        int leave_member = -2;
        for (int k = m; k < int(end); ++k) {
          if (k >= 0 && ((skip >> uint(k)) & 1u) != 0u) continue;
          uint key = k < 0 ? entry_key : list.key[k];
          if ((key >> 2u) != solid) continue;
          if ((key & 3u) == SP_CROSSING_ENTER && enter_member == -2) enter_member = k;
          if ((key & 3u) == SP_CROSSING_LEAVE && leave_member == -2) leave_member = k;
        }
        bool enters = enter_member != -2;
        bool leaves = leave_member != -2;
        if (pass == 0u && leaves) {
          any_leaving = true;
          if (!enters) {
            delta -= 1;
            sp_matter_pop(stack_size, s0, s1, s2, s3, bvh_triangles[list.triangle[leave_member]].layer);
          }
        }
        if (pass == 1u && enters && !leaves) {
          delta += 1;
          uint layer = enter_member < 0 ? entry.layer : bvh_triangles[list.triangle[enter_member]].layer;
          if (stack_size == 0u) s0 = layer;
          else if (stack_size == 1u) s1 = layer;
          else if (stack_size == 2u) s2 = layer;
          else if (stack_size == 3u) s3 = layer;
          stack_size = min(stack_size + 1u, uint(SP_MATTER_STACK));
        }
      }
    }
    depth += delta;
    if (depth <= 0 && any_leaving) {
      // The group's farthest leaving face: every face of the group lies
      // behind it, so the ray goes on from there in air.
      uint exit_entry = 0u;
      for (uint k = first ? 0u : g; k < end; ++k) {
        if (((skip >> k) & 1u) == 0u && (list.key[k] & 3u) == SP_CROSSING_LEAVE) exit_entry = k;
      }
      result.t = max(list.t[exit_entry], 0.0f);
      result.triangle = list.triangle[exit_entry];
      result.matter_loss = loss;
      return result;
    }
    first = false;
    g = end;
  }
  return result;
}

SP_END_NAMESPACE

#endif  // SP_MATTER_H
