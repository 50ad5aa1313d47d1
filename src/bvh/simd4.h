// 4-wide float and int32 vectors for the CPU BVH (bvh_geometry.h,
// wide_bvh.cpp, bvh_builder.cpp): exactly the operations that code uses, on
// SSE2 (x86-64, or x86 with SSE2), NEON (ARM), or a plain struct of four
// lanes elsewhere and when SP_SIMD_SCALAR is defined (CMake's
// -DSOUNDPAINT_SIMD=scalar). Portable C++ with intrinsics, not GCC/Clang
// vector extensions, so that MSVC builds it too.
//
// Every operation is lane by lane IEEE single precision with the same result
// on all three paths, bit for bit: the CPU traversal is the GPU's reference
// (wide_bvh.h). In particular vmin(a, b) is `a < b ? a : b` and vmax(a, b)
// `a > b ? a : b` on every path, so an unordered (NaN) lane gives b: SSE's
// minps/maxps do exactly that; NEON's vminq/vmaxq do not (they return NaN
// if either lane is NaN), so the NEON path compares and selects. No fused
// multiply-add anywhere (the build also uses -ffp-contract=off).
//
// Comparisons give Int4 lane masks: all ones where true, 0 where false.
#pragma once

#include <cstdint>
#include <cstring>

#if !defined(SP_SIMD_SCALAR) && (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#define SP_SIMD_SSE2 1
#elif !defined(SP_SIMD_SCALAR) && (defined(__ARM_NEON) || defined(_M_ARM64))
#define SP_SIMD_NEON 1
#endif

#if defined(SP_SIMD_SSE2)
#include <emmintrin.h>
#elif defined(SP_SIMD_NEON)
#include <arm_neon.h>
#endif
// The prefetch hint works without SIMD arithmetic, so it does not depend on
// SP_SIMD_SCALAR.
#if defined(__SSE__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 1)
#include <xmmintrin.h>
#define SP_PREFETCH_SSE 1
#endif

namespace sp {

#if defined(SP_SIMD_SSE2) || defined(SP_SIMD_NEON)
namespace detail_simd4 {
// Lane i written in the vector object's own bytes: memcpy rather than a
// pointer cast (no aliasing question), and in place rather than through a
// stored copy (a 4-byte store then a 16-byte load of it misses
// store-to-load forwarding, which made the wide BVH build slower). Reads go
// the other way (operator[]): the register is stored whole to a local array
// and one lane loaded, which forwards, folds to a shuffle for a constant
// lane, and leaves the vector itself in a register (reading it in place
// forced every vector that was ever indexed into memory: 17 % fewer
// rays/s on level.gltf).
inline void set_lane(void* v, int i, float x) {
  std::memcpy(static_cast<char*>(v) + sizeof(float) * static_cast<unsigned>(i), &x, sizeof(float));
}
}  // namespace detail_simd4
#endif

#if defined(SP_SIMD_SSE2)

struct Int4 {
  __m128 m;  // lane masks live in the float domain, where the comparisons make them
  Int4() = default;
  explicit Int4(__m128 v) : m(v) {}
  explicit Int4(__m128i v) : m(_mm_castsi128_ps(v)) {}
  std::int32_t operator[](int i) const { return (*this)[static_cast<unsigned>(i)]; }
  std::int32_t operator[](unsigned i) const {
    alignas(16) std::int32_t lanes[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes), _mm_castps_si128(m));
    return lanes[i & 3u];
  }
};

struct Vec4 {
  __m128 m;
  Vec4() = default;  // uninitialized, as a float; Vec4{} is all zeros
  Vec4(float x, float y, float z, float w) : m(_mm_setr_ps(x, y, z, w)) {}
  explicit Vec4(__m128 v) : m(v) {}
  float operator[](int i) const { return (*this)[static_cast<unsigned>(i)]; }
  float operator[](unsigned i) const {
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, m);
    return lanes[i & 3u];
  }
  void set(int i, float x) { detail_simd4::set_lane(this, i, x); }
};

inline Vec4 splat(float x) { return Vec4(_mm_set1_ps(x)); }
inline Vec4 operator+(Vec4 a, Vec4 b) { return Vec4(_mm_add_ps(a.m, b.m)); }
inline Vec4 operator-(Vec4 a, Vec4 b) { return Vec4(_mm_sub_ps(a.m, b.m)); }
inline Vec4 operator*(Vec4 a, Vec4 b) { return Vec4(_mm_mul_ps(a.m, b.m)); }
inline Vec4 operator/(Vec4 a, Vec4 b) { return Vec4(_mm_div_ps(a.m, b.m)); }
inline Int4 operator<(Vec4 a, Vec4 b) { return Int4(_mm_cmplt_ps(a.m, b.m)); }
inline Int4 operator>(Vec4 a, Vec4 b) { return Int4(_mm_cmpgt_ps(a.m, b.m)); }
inline Int4 operator<=(Vec4 a, Vec4 b) { return Int4(_mm_cmple_ps(a.m, b.m)); }
inline Int4 operator!=(Vec4 a, Vec4 b) { return Int4(_mm_cmpneq_ps(a.m, b.m)); }
inline Int4 operator&(Int4 a, Int4 b) { return Int4(_mm_and_ps(a.m, b.m)); }
inline Int4 operator|(Int4 a, Int4 b) { return Int4(_mm_or_ps(a.m, b.m)); }
// ~a & b, lane by lane, in one instruction.
inline Int4 and_not(Int4 a, Int4 b) { return Int4(_mm_andnot_ps(a.m, b.m)); }
// a < b ? a : b and a > b ? a : b, lane by lane: minps/maxps return their
// second operand when the comparison is unordered.
inline Vec4 vmin(Vec4 a, Vec4 b) { return Vec4(_mm_min_ps(a.m, b.m)); }
inline Vec4 vmax(Vec4 a, Vec4 b) { return Vec4(_mm_max_ps(a.m, b.m)); }
// mask ? a : b, lane by lane.
inline Vec4 select(Int4 mask, Vec4 a, Vec4 b) {
  return Vec4(_mm_or_ps(_mm_and_ps(mask.m, a.m), _mm_andnot_ps(mask.m, b.m)));
}
// (y, z, x, w) and (y, x, w, z).
inline Vec4 shuffle_yzxw(Vec4 v) { return Vec4(_mm_shuffle_ps(v.m, v.m, _MM_SHUFFLE(3, 0, 2, 1))); }
inline Vec4 shuffle_yxwz(Vec4 v) { return Vec4(_mm_shuffle_ps(v.m, v.m, _MM_SHUFFLE(2, 3, 0, 1))); }
// Float to int32, truncating toward zero, lane by lane (in range only).
inline Int4 to_int4(Vec4 v) { return Int4(_mm_cvttps_epi32(v.m)); }
// Bit i set where lane i of the mask is set.
inline unsigned lane_mask(Int4 m) { return static_cast<unsigned>(_mm_movemask_ps(m.m)); }

#elif defined(SP_SIMD_NEON)

struct Int4 {
  int32x4_t m;
  Int4() = default;
  explicit Int4(int32x4_t v) : m(v) {}
  explicit Int4(uint32x4_t v) : m(vreinterpretq_s32_u32(v)) {}
  std::int32_t operator[](int i) const { return (*this)[static_cast<unsigned>(i)]; }
  std::int32_t operator[](unsigned i) const {
    std::int32_t lanes[4];
    vst1q_s32(lanes, m);
    return lanes[i & 3u];
  }
};

struct alignas(16) Vec4 {
  float32x4_t m;
  Vec4() = default;  // uninitialized, as a float; Vec4{} is all zeros
  Vec4(float x, float y, float z, float w) {
    const float a[4] = {x, y, z, w};
    m = vld1q_f32(a);
  }
  explicit Vec4(float32x4_t v) : m(v) {}
  float operator[](int i) const { return (*this)[static_cast<unsigned>(i)]; }
  float operator[](unsigned i) const {
    float lanes[4];
    vst1q_f32(lanes, m);
    return lanes[i & 3u];
  }
  void set(int i, float x) { detail_simd4::set_lane(this, i, x); }
};

inline Vec4 splat(float x) { return Vec4(vdupq_n_f32(x)); }
inline Vec4 operator+(Vec4 a, Vec4 b) { return Vec4(vaddq_f32(a.m, b.m)); }
inline Vec4 operator-(Vec4 a, Vec4 b) { return Vec4(vsubq_f32(a.m, b.m)); }
inline Vec4 operator*(Vec4 a, Vec4 b) { return Vec4(vmulq_f32(a.m, b.m)); }
inline Vec4 operator/(Vec4 a, Vec4 b) {
#if defined(__aarch64__) || defined(_M_ARM64)
  return Vec4(vdivq_f32(a.m, b.m));
#else  // 32-bit NEON has no exact division: divide lane by lane
  float x[4], y[4];
  vst1q_f32(x, a.m);
  vst1q_f32(y, b.m);
  for (int i = 0; i < 4; ++i) x[i] /= y[i];
  return Vec4(vld1q_f32(x));
#endif
}
inline Int4 operator<(Vec4 a, Vec4 b) { return Int4(vcltq_f32(a.m, b.m)); }
inline Int4 operator>(Vec4 a, Vec4 b) { return Int4(vcgtq_f32(a.m, b.m)); }
inline Int4 operator<=(Vec4 a, Vec4 b) { return Int4(vcleq_f32(a.m, b.m)); }
inline Int4 operator!=(Vec4 a, Vec4 b) { return Int4(vmvnq_u32(vceqq_f32(a.m, b.m))); }
inline Int4 operator&(Int4 a, Int4 b) { return Int4(vandq_s32(a.m, b.m)); }
inline Int4 operator|(Int4 a, Int4 b) { return Int4(vorrq_s32(a.m, b.m)); }
// ~a & b, lane by lane, in one instruction.
inline Int4 and_not(Int4 a, Int4 b) { return Int4(vbicq_s32(b.m, a.m)); }
// mask ? a : b, lane by lane.
inline Vec4 select(Int4 mask, Vec4 a, Vec4 b) { return Vec4(vbslq_f32(vreinterpretq_u32_s32(mask.m), a.m, b.m)); }
// a < b ? a : b and a > b ? a : b, lane by lane (not vminq/vmaxq: see above).
inline Vec4 vmin(Vec4 a, Vec4 b) { return select(a < b, a, b); }
inline Vec4 vmax(Vec4 a, Vec4 b) { return select(a > b, a, b); }
// (y, z, x, w) and (y, x, w, z).
inline Vec4 shuffle_yzxw(Vec4 v) {
  const float32x4_t yzwx = vextq_f32(v.m, v.m, 1);
  return Vec4(vcombine_f32(vget_low_f32(yzwx), vrev64_f32(vget_high_f32(yzwx))));
}
inline Vec4 shuffle_yxwz(Vec4 v) { return Vec4(vrev64q_f32(v.m)); }
// Float to int32, truncating toward zero, lane by lane (in range only).
inline Int4 to_int4(Vec4 v) { return Int4(vcvtq_s32_f32(v.m)); }
// Bit i set where lane i of the mask is set.
inline unsigned lane_mask(Int4 m) {
  const uint32x4_t bits = vshrq_n_u32(vreinterpretq_u32_s32(m.m), 31);
#if defined(__aarch64__) || defined(_M_ARM64)
  const std::int32_t shifts[4] = {0, 1, 2, 3};
  return vaddvq_u32(vshlq_u32(bits, vld1q_s32(shifts)));
#else
  return vgetq_lane_u32(bits, 0) | (vgetq_lane_u32(bits, 1) << 1) | (vgetq_lane_u32(bits, 2) << 2) |
         (vgetq_lane_u32(bits, 3) << 3);
#endif
}

#else  // scalar: four lanes in a struct

struct alignas(16) Int4 {
  std::int32_t v[4];
  std::int32_t operator[](int i) const { return (*this)[static_cast<unsigned>(i)]; }
  std::int32_t operator[](unsigned i) const { return v[i]; }
};

struct alignas(16) Vec4 {
  float v[4];
  Vec4() = default;  // uninitialized, as a float; Vec4{} is all zeros
  Vec4(float x, float y, float z, float w) : v{x, y, z, w} {}
  float operator[](int i) const { return (*this)[static_cast<unsigned>(i)]; }
  float operator[](unsigned i) const { return v[i]; }
  void set(int i, float x) { v[i] = x; }
};

namespace detail_simd4 {
template <class F>
inline Vec4 map(Vec4 a, Vec4 b, F f) {
  return Vec4(f(a.v[0], b.v[0]), f(a.v[1], b.v[1]), f(a.v[2], b.v[2]), f(a.v[3], b.v[3]));
}
template <class F>
inline Int4 compare(Vec4 a, Vec4 b, F f) {
  Int4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = f(a.v[i], b.v[i]) ? -1 : 0;
  return r;
}
}  // namespace detail_simd4

inline Vec4 splat(float x) { return Vec4(x, x, x, x); }
inline Vec4 operator+(Vec4 a, Vec4 b) {
  return detail_simd4::map(a, b, [](float x, float y) { return x + y; });
}
inline Vec4 operator-(Vec4 a, Vec4 b) {
  return detail_simd4::map(a, b, [](float x, float y) { return x - y; });
}
inline Vec4 operator*(Vec4 a, Vec4 b) {
  return detail_simd4::map(a, b, [](float x, float y) { return x * y; });
}
inline Vec4 operator/(Vec4 a, Vec4 b) {
  return detail_simd4::map(a, b, [](float x, float y) { return x / y; });
}
inline Int4 operator<(Vec4 a, Vec4 b) {
  return detail_simd4::compare(a, b, [](float x, float y) { return x < y; });
}
inline Int4 operator>(Vec4 a, Vec4 b) {
  return detail_simd4::compare(a, b, [](float x, float y) { return x > y; });
}
inline Int4 operator<=(Vec4 a, Vec4 b) {
  return detail_simd4::compare(a, b, [](float x, float y) { return x <= y; });
}
inline Int4 operator!=(Vec4 a, Vec4 b) {
  return detail_simd4::compare(a, b, [](float x, float y) { return x != y; });
}
inline Int4 operator&(Int4 a, Int4 b) {
  return Int4{{a.v[0] & b.v[0], a.v[1] & b.v[1], a.v[2] & b.v[2], a.v[3] & b.v[3]}};
}
inline Int4 operator|(Int4 a, Int4 b) {
  return Int4{{a.v[0] | b.v[0], a.v[1] | b.v[1], a.v[2] | b.v[2], a.v[3] | b.v[3]}};
}
// ~a & b, lane by lane.
inline Int4 and_not(Int4 a, Int4 b) {
  return Int4{{~a.v[0] & b.v[0], ~a.v[1] & b.v[1], ~a.v[2] & b.v[2], ~a.v[3] & b.v[3]}};
}
// a < b ? a : b and a > b ? a : b, lane by lane.
inline Vec4 vmin(Vec4 a, Vec4 b) {
  return detail_simd4::map(a, b, [](float x, float y) { return x < y ? x : y; });
}
inline Vec4 vmax(Vec4 a, Vec4 b) {
  return detail_simd4::map(a, b, [](float x, float y) { return x > y ? x : y; });
}
// mask ? a : b, lane by lane.
inline Vec4 select(Int4 mask, Vec4 a, Vec4 b) {
  Vec4 r;
  for (int i = 0; i < 4; ++i) r.v[i] = mask.v[i] != 0 ? a.v[i] : b.v[i];
  return r;
}
// (y, z, x, w) and (y, x, w, z).
inline Vec4 shuffle_yzxw(Vec4 v) { return Vec4(v.v[1], v.v[2], v.v[0], v.v[3]); }
inline Vec4 shuffle_yxwz(Vec4 v) { return Vec4(v.v[1], v.v[0], v.v[3], v.v[2]); }
// Float to int32, truncating toward zero, lane by lane (in range only).
inline Int4 to_int4(Vec4 v) {
  return Int4{{static_cast<std::int32_t>(v.v[0]), static_cast<std::int32_t>(v.v[1]), static_cast<std::int32_t>(v.v[2]),
               static_cast<std::int32_t>(v.v[3])}};
}
// Bit i set where lane i of the mask is set.
inline unsigned lane_mask(Int4 m) {
  return static_cast<unsigned>((m.v[0] & 1) | (m.v[1] & 2) | (m.v[2] & 4) | (m.v[3] & 8));
}

#endif

static_assert(sizeof(Vec4) == 16 && alignof(Vec4) == 16);
static_assert(sizeof(Int4) == 16);

// A hint to fetch the cache line at p; nothing where there is no such hint.
inline void prefetch(const void* p) {
#if defined(SP_PREFETCH_SSE)
  _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
#elif defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

}  // namespace sp
