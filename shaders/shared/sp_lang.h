// Language bridge: lets the files in shaders/shared compile both as GLSL 4.60
// and as C++20, so the GPU and CPU backends run literally the same arithmetic.
//
// Rules for shared code (see CONTRIBUTING.md):
//  - only scalar and vecN/uvecN types, component access by .x/.y/.z or [i];
//  - parameters that are written use SP_INOUT / SP_OUT;
//  - variables whose rounding matters for CPU/GPU parity are SP_PRECISE
//    (GLSL `precise` forbids fused multiply-add; the C++ side is compiled with
//    -ffp-contract=off for the same reason);
//  - buffers are reached through SP_BVH_ARGS (C++ pointers, GLSL globals).
#ifndef SP_LANG_H
#define SP_LANG_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

// A shared struct's layout, checked where it is declared: the C++ offsets
// must be the std430 ones GLSL uses (every vec3 is paired with a 4-byte
// scalar, so they are). GLSL ignores the check.
#define SP_CHECK_LAYOUT(condition) static_assert(condition, "C++ and std430 layouts of a shared struct differ")

#define SP_BEGIN_NAMESPACE namespace sp::shader {
#define SP_END_NAMESPACE }
#define SP_INLINE inline
#define SP_INOUT(T) T&
#define SP_OUT(T) T&
#define SP_PRECISE

SP_BEGIN_NAMESPACE
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;
using glm::abs;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::length;
using glm::max;
using glm::min;
using glm::mod;
using glm::sin;
using glm::sqrt;
SP_END_NAMESPACE

#else  // GLSL

#define SP_BEGIN_NAMESPACE
#define SP_END_NAMESPACE
#define SP_INLINE
#define SP_INOUT(T) inout T
#define SP_OUT(T) out T
#define SP_PRECISE precise
#define SP_CHECK_LAYOUT(condition)

#endif

// pi as a float, for both languages (GLSL has no constant of its own).
#define SP_PI 3.14159265f

#endif  // SP_LANG_H
