#include "embree_cast.h"
#include "sp_types.h"

#include <algorithm>
#include <stdexcept>

#ifdef SP_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <chrono>
#include <numeric>

#include <glm/glm.hpp>
#endif

namespace spbench {

const char* quality_name(EmbreeQuality quality) { return quality == EmbreeQuality::High ? "high" : "medium"; }

bool is_accel_name(const std::string& accel) {
  return std::all_of(accel.begin(), accel.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_';
  });
}

#ifdef SP_HAVE_EMBREE

std::optional<std::string> embree_version() { return std::string(RTC_VERSION_STRING); }

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  double build_ms = 0.0;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    if (RTCError error = rtcGetDeviceError(device); error != RTC_ERROR_NONE)
      throw std::runtime_error(std::string("Embree: ") + what + " failed with error " + std::to_string(error));
  }
};

EmbreeScene::EmbreeScene(std::span<const glm::vec3> vertices, EmbreeQuality quality, unsigned threads,
                         const std::string& accel)
    : impl_(std::make_unique<Impl>()) {
  if (!is_accel_name(accel)) throw std::runtime_error("Embree: \"" + accel + "\" is not an acceleration structure");
  std::string config = "threads=" + std::to_string(threads);
  if (!accel.empty()) config += ",tri_accel=" + accel;
  impl_->device = rtcNewDevice(config.c_str());
  if (!impl_->device) throw std::runtime_error("Embree: rtcNewDevice failed (configuration \"" + config + "\")");
  const RTCBuildQuality build_quality =
      quality == EmbreeQuality::High ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;

  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* positions = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                3 * sizeof(float), vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), vertices.size() / 3));
  impl_->check("allocating the geometry buffers");
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    positions[3 * i + 0] = vertices[i].x;
    positions[3 * i + 1] = vertices[i].y;
    positions[3 * i + 2] = vertices[i].z;
  }
  std::iota(indices, indices + vertices.size(), 0u);
  rtcSetGeometryBuildQuality(geometry, build_quality);
  rtcCommitGeometry(geometry);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, build_quality);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);

  const auto start = std::chrono::steady_clock::now();
  rtcCommitScene(impl_->scene);
  impl_->build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  impl_->check(accel.empty() ? "building the scene" : ("building the scene as " + accel).c_str());
}

EmbreeScene::~EmbreeScene() = default;

double EmbreeScene::build_ms() const { return impl_->build_ms; }

void EmbreeScene::intersect1(const CastRay* rays, std::size_t count, CastHit* hits) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t i = 0; i < count; ++i) {
    RTCRayHit rh{};
    rh.ray.org_x = rays[i].origin.x;
    rh.ray.org_y = rays[i].origin.y;
    rh.ray.org_z = rays[i].origin.z;
    rh.ray.tnear = rays[i].tmin;
    rh.ray.dir_x = rays[i].dir.x;
    rh.ray.dir_y = rays[i].dir.y;
    rh.ray.dir_z = rays[i].dir.z;
    rh.ray.tfar = rays[i].tmax;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rh);
    hits[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? CastHit{} : CastHit{rh.ray.tfar, rh.hit.primID};
  }
}

void EmbreeScene::intersect16(const CastRay* rays, std::size_t count, CastHit* hits) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t first = 0; first < count; first += 16) {
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;  // lanes that are not valid are never read
    for (std::size_t k = 0; k < 16; ++k) {
      const std::size_t i = first + k;
      valid[k] = i < count ? -1 : 0;
      if (i >= count) continue;
      rh.ray.org_x[k] = rays[i].origin.x;
      rh.ray.org_y[k] = rays[i].origin.y;
      rh.ray.org_z[k] = rays[i].origin.z;
      rh.ray.tnear[k] = rays[i].tmin;
      rh.ray.dir_x[k] = rays[i].dir.x;
      rh.ray.dir_y[k] = rays[i].dir.y;
      rh.ray.dir_z[k] = rays[i].dir.z;
      rh.ray.time[k] = 0.0f;
      rh.ray.tfar[k] = rays[i].tmax;
      rh.ray.mask[k] = 0xFFFFFFFFu;
      rh.ray.id[k] = 0;
      rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, impl_->scene, &context, &rh);
    for (std::size_t k = 0; k < 16 && first + k < count; ++k)
      hits[first + k] =
          rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? CastHit{} : CastHit{rh.ray.tfar[k], rh.hit.primID[k]};
  }
}

#else  // built without libembree-dev

std::optional<std::string> embree_version() { return std::nullopt; }

struct EmbreeScene::Impl {};

EmbreeScene::EmbreeScene(std::span<const glm::vec3>, EmbreeQuality, unsigned, const std::string&) {
  throw std::runtime_error("Embree not available: built without libembree-dev");
}
EmbreeScene::~EmbreeScene() = default;
double EmbreeScene::build_ms() const { return 0.0; }
void EmbreeScene::intersect1(const CastRay*, std::size_t, CastHit*) const {}
void EmbreeScene::intersect16(const CastRay*, std::size_t, CastHit*) const {}

#endif

}  // namespace spbench
