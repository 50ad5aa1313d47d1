// The public Vec3 / Mat4 (soundpaint/math.h) as glm types, for the maths
// inside the library. Implicit conversions cover assignments and calls; these
// name the conversion where glm's operator templates cannot deduce it.
#pragma once

#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "soundpaint/math.h"

namespace sp {

inline glm::vec3 to_glm(Vec3 v) { return {v.x, v.y, v.z}; }
inline glm::mat4 to_glm(const Mat4& m) { return glm::mat4(m); }
inline std::vector<glm::vec3> to_glm(std::span<const Vec3> vectors) {
  std::vector<glm::vec3> out;
  out.reserve(vectors.size());
  for (Vec3 v : vectors) out.push_back(to_glm(v));
  return out;
}

}  // namespace sp
