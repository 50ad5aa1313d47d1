// Embree 3 as the ceiling of CPU ray casting (optional: built only where
// CMake found libembree-dev; elsewhere every call reports it missing).
// Triangles are given in scene order, so Embree's primID is the scene index
// that soundpaint's BvhTriangle::scene_index refers to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include <glm/vec3.hpp>

namespace spbench {

// One ray as both casters read it: hits are sought in (tmin, tmax] (soundpaint)
// or [tmin, tmax] (Embree) along the unit direction.
struct CastRay {
  glm::vec3 origin;
  float tmin;
  glm::vec3 dir;
  float tmax;
};

inline constexpr std::uint32_t kMiss = 0xFFFFFFFFu;

struct CastHit {
  float t = 0.0f;
  // The caster's own index of the triangle hit (Embree: the scene's order;
  // soundpaint: leaf order), or kMiss. Only hit or miss is compared.
  std::uint32_t triangle = kMiss;
};

// Embree's version, or empty when built without it.
std::optional<std::string> embree_version();

enum class EmbreeQuality { Medium, High };  // RTC_BUILD_QUALITY_MEDIUM / _HIGH
const char* quality_name(EmbreeQuality quality);

// Whether `accel` is one word of Embree's configuration syntax (letters,
// digits, '.', '_'; empty for Embree's default), so that a tri_accel name
// cannot add settings of its own after a comma.
bool is_accel_name(const std::string& accel);

// An Embree device and a committed scene of one triangle mesh.
class EmbreeScene {
 public:
  // Builds over `vertices` (3 per triangle) on a device limited to `threads`
  // build threads. `accel`, when not empty, is Embree's tri_accel setting
  // (which tree and leaves it builds, e.g. "bvh4.triangle4"; empty: Embree's
  // own choice for this CPU). Throws std::runtime_error without Embree, for
  // an accel name that is not one word of letters, digits and dots, or on
  // Embree's errors.
  EmbreeScene(std::span<const glm::vec3> vertices, EmbreeQuality quality, unsigned threads,
              const std::string& accel = {});
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Wall time of rtcCommitScene (the BVH build), milliseconds.
  double build_ms() const;

  // Closest hits of rays[0, count): one rtcIntersect1 per ray, or one
  // rtcIntersect16 per 16 rays. Thread-safe.
  void intersect1(const CastRay* rays, std::size_t count, CastHit* hits) const;
  void intersect16(const CastRay* rays, std::size_t count, CastHit* hits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace spbench
