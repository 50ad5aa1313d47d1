// Finiteness checks for the vectors and matrices that API callers pass in:
// a NaN position or transform must become an error, not a poisoned BVH.
#pragma once

#include <cmath>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace sp {

inline bool all_finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline bool all_finite(const glm::mat4& m) {
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(m[column][row])) return false;
  return true;
}

}  // namespace sp
