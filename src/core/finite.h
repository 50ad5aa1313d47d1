// Finiteness checks for the vectors and matrices that API callers pass in:
// a NaN position or transform must become an error, not a poisoned BVH.
#pragma once

#include <cmath>

#include "soundpaint/math.h"

namespace sp {

inline bool all_finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline bool all_finite(const Mat4& m) {
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(m[column][row])) return false;
  return true;
}

}  // namespace sp
