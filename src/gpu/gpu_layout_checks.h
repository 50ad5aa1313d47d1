// The shared structs must have identical layouts in C++ and std430 GLSL.
// std430 aligns vec3 to 16 bytes; every vec3 in the shared headers is
// followed by a 4-byte scalar, so the C++ offsets below are the std430 ones.
#pragma once

#include <cstddef>

#include "sp_gpu_types.h"
#include "sp_types.h"

namespace sp::shader {

static_assert(sizeof(BvhNode) == 32 && offsetof(BvhNode, left_or_first) == 12 && offsetof(BvhNode, bmax) == 16 &&
              offsetof(BvhNode, count) == 28);
static_assert(sizeof(BvhTriangle) == 64 && offsetof(BvhTriangle, layer) == 12 && offsetof(BvhTriangle, v1) == 16 &&
              offsetof(BvhTriangle, scene_index) == 28 && offsetof(BvhTriangle, v2) == 32 &&
              offsetof(BvhTriangle, solid) == 44 && offsetof(BvhTriangle, normal) == 48);
static_assert(sizeof(LayerAcoustics) == 16 && offsetof(LayerAcoustics, sheet_thickness) == 8);
static_assert(sizeof(SimParams) == 64 && offsetof(SimParams, diffraction) == 32 &&
              offsetof(SimParams, diffraction_gain) == 48);
static_assert(sizeof(TriangleEdges) == 32 && offsetof(TriangleEdges, exposed) == 12 &&
              offsetof(TriangleEdges, turn_sin) == 16);
static_assert(sizeof(StepSource) == 48 && offsetof(StepSource, color) == 16 && offsetof(StepSource, intensity) == 32 &&
              offsetof(StepSource, source_id) == 44);
static_assert(sizeof(RayState) == 96 && offsetof(RayState, dir) == 16 && offsetof(RayState, entry) == 32 &&
              offsetof(RayState, entry_layer) == 44 && offsetof(RayState, state) == 48 &&
              offsetof(RayState, loudness) == 76 && offsetof(RayState, entry_triangle) == 80);
static_assert(sizeof(Indicator) == 96 && offsetof(Indicator, normal) == 16 && offsetof(Indicator, color) == 32 &&
              offsetof(Indicator, dir) == 48 && offsetof(Indicator, path_length) == 60 &&
              offsetof(Indicator, kind) == 64 && offsetof(Indicator, iteration) == 92);
static_assert(sizeof(HitInfo) == 8);
static_assert(sizeof(CastResult) == 16 && offsetof(CastResult, matter_loss) == 8);
static_assert(sizeof(QueueArgs) == 48 && offsetof(QueueArgs, active_groups_x) == 16 &&
              offsetof(QueueArgs, resolving_groups_x) == 32);
static_assert(sizeof(Control) == 192 && offsetof(Control, draw_vertex_count) == 0 && offsetof(Control, queues) == 16 &&
              offsetof(Control, ring_head) == 112 && offsetof(Control, admit_group_count_x) == 160);
// StepSource[] follows StepInput in one buffer; std430 places it at the
// array's alignment (16, from vec3), which sizeof(StepInput) already is.
static_assert(sizeof(StepInput) == 96 && sizeof(StepInput) % 16 == 0);
static_assert(sizeof(WavefrontPush) == 16);
static_assert(alignof(BvhNode) == 4 && alignof(Indicator) == 4);

}  // namespace sp::shader
