// The draw pass's shared structs must have identical layouts in C++ and
// std430 GLSL (storage buffers and push constants alike); every vec3 is
// followed by a 4-byte scalar, so these C++ offsets are the std430 ones.
#pragma once

#include <cstddef>

#include "sp_draw_types.h"

namespace sp::shader {

static_assert(sizeof(SceneTriangle) == 64 && alignof(SceneTriangle) == 4);
static_assert(offsetof(SceneTriangle, shading) == 12 && offsetof(SceneTriangle, v1) == 16 &&
              offsetof(SceneTriangle, layer) == 28 && offsetof(SceneTriangle, v2) == 32 &&
              offsetof(SceneTriangle, color) == 48);
static_assert(sizeof(ScenePush) == 96 && offsetof(ScenePush, eye) == 64 && offsetof(ScenePush, ambient) == 76 &&
              offsetof(ScenePush, light_dir) == 80 && offsetof(ScenePush, fog_distance) == 92);
static_assert(sizeof(IndicatorPush) == 128 && offsetof(IndicatorPush, eye) == 64 &&
              offsetof(IndicatorPush, current_step) == 76 && offsetof(IndicatorPush, dt) == 80 &&
              offsetof(IndicatorPush, lifetime) == 84 && offsetof(IndicatorPush, flags) == 108 &&
              offsetof(IndicatorPush, depth_a) == 112);
static_assert(sizeof(DisplaySource) == 32 && offsetof(DisplaySource, category) == 12 &&
              offsetof(DisplaySource, color) == 16 && offsetof(DisplaySource, shape_flags) == 28);
static_assert(sizeof(DisplayPrepassPush) == 32);
static_assert(sizeof(ArrowPush) == 96 && offsetof(ArrowPush, viewport) == 64 && offsetof(ArrowPush, eye) == 80);
// Vulkan guarantees 128 bytes of push constants on every device.
static_assert(sizeof(ScenePush) <= 128 && sizeof(IndicatorPush) <= 128 && sizeof(ArrowPush) <= 128);

}  // namespace sp::shader
