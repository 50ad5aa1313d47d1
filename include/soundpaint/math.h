// The vector and matrix types of the public API: plain floats, no maths
// library attached, so a host needs none of ours to include the headers.
// Each converts implicitly from and to any type shaped like it (glm::vec3
// and glm::mat4, or an engine's own vector with x, y, z members and a
// (x, y, z) constructor), so a host passes and receives its own types.
#pragma once

#include <concepts>
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// A type with float-convertible x, y and z members and no w (a 4-vector
// does not silently lose its w).
template <class V>
concept Vec3Shaped = requires(const V& v) {
  { v.x } -> std::convertible_to<float>;
  { v.y } -> std::convertible_to<float>;
  { v.z } -> std::convertible_to<float>;
}
&&!requires(const V& v) { v.w; };

// A 4x4 float matrix indexed m[column][row], as GLSL and glm index them
// (16 floats in size: a container of vectors is not one).
template <class M>
concept Mat4Shaped = sizeof(M) == 16 * sizeof(float) && requires(const M& m) {
  { m[0][0] } -> std::convertible_to<float>;
};

struct Vec3 {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;

  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  template <Vec3Shaped V>
  requires(!std::same_as<V, Vec3>) constexpr Vec3(const V& v)
      : x(static_cast<float>(v.x)), y(static_cast<float>(v.y)), z(static_cast<float>(v.z)) {}

  template <Vec3Shaped V>
  requires(!std::same_as<V, Vec3> && std::constructible_from<V, float, float, float>) constexpr operator V() const {
    return V(x, y, z);
  }

  constexpr float operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
  constexpr float& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }

  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

// Column-major: columns[c][r] is row r of column c; a transform's
// translation is columns[3]. Default: the identity.
struct Mat4 {
  float columns[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

  constexpr Mat4() = default;
  template <Mat4Shaped M>
  requires(!std::same_as<M, Mat4>) constexpr Mat4(const M& m) {
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) columns[c][r] = static_cast<float>(m[c][r]);
    }
  }

  template <Mat4Shaped M>
  requires(!std::same_as<M, Mat4> && std::default_initializable<M>) constexpr operator M() const {
    M m{};
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m[c][r] = columns[c][r];
    }
    return m;
  }

  constexpr const float* operator[](int column) const { return columns[column]; }
  constexpr float* operator[](int column) { return columns[column]; }
  constexpr Vec3 translation() const { return {columns[3][0], columns[3][1], columns[3][2]}; }

  friend constexpr bool operator==(const Mat4&, const Mat4&) = default;
};

}  // namespace sp

SP_CPP_API_END
