// Test kernel for tests/test_vk.cpp: data[i] = value + i for i < count.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "sp_types.h"

// kFillGroupSize in tests/test_vk.cpp.
layout(local_size_x = SP_WORKGROUP_SIZE) in;

layout(set = 0, binding = 0, std430) buffer Data {
  uint data[];
};

layout(push_constant) uniform Push {
  uint count;
  uint value;
} push;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i < push.count) data[i] = push.value + i;
}
