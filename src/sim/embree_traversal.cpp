#include "sim/embree_traversal.h"

#include <cmath>
#include <limits>
#include <string>

#include "config/build_features.h"
#include "soundpaint/result.h"

#ifdef SOUNDPAINT_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace sp {

#ifdef SOUNDPAINT_HAVE_EMBREE

struct EmbreeTraversal::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    if (const RTCError error = rtcGetDeviceError(device); error != RTC_ERROR_NONE)
      throw Exception(ErrorCode::LimitExceeded,
                      std::string("Embree: ") + what + " failed (RTCError " + std::to_string(error) + ")");
  }
};

std::unique_ptr<EmbreeTraversal::Impl> EmbreeTraversal::build(const Bvh& bvh, unsigned threads) {
  auto impl = std::make_unique<Impl>();
  const std::string config = "threads=" + std::to_string(threads);
  impl->device = rtcNewDevice(config.c_str());
  if (!impl->device) throw Exception(ErrorCode::LimitExceeded, "Embree: rtcNewDevice failed");

  // The vertices are read from the BVH's own triangles: each BvhTriangle is
  // four 16-byte rows (v0, v1, v2, normal, each with a word after it), so
  // with a 16-byte stride triangle i's corners are rows 4i, 4i + 1, 4i + 2.
  // The last row read is a normal, so Embree's 16-byte loads stay inside.
  const std::size_t count = bvh.triangles.size();
  RTCGeometry geometry = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, bvh.triangles.data(), 0, 16,
                             4 * count);
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
  impl->check("allocating the index buffer");
  for (std::size_t i = 0; i < count; ++i) {
    indices[3 * i + 0] = static_cast<unsigned>(4 * i + 0);
    indices[3 * i + 1] = static_cast<unsigned>(4 * i + 1);
    indices[3 * i + 2] = static_cast<unsigned>(4 * i + 2);
  }
  rtcCommitGeometry(geometry);
  impl->scene = rtcNewScene(impl->device);
  rtcAttachGeometry(impl->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl->scene);
  impl->check("building the scene");
  return impl;
}

HitInfo EmbreeTraversal::closest_hit(glm::vec3 origin, glm::vec3 dir, float tmin, float tmax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  query.ray.org_x = origin.x;
  query.ray.org_y = origin.y;
  query.ray.org_z = origin.z;
  // Embree looks in [tnear, tfar]; soundpaint in (tmin, tmax].
  query.ray.tnear = tmin == 0.0f ? std::numeric_limits<float>::denorm_min() : std::nextafter(tmin, INFINITY);
  query.ray.dir_x = dir.x;
  query.ray.dir_y = dir.y;
  query.ray.dir_z = dir.z;
  query.ray.tfar = tmax;
  query.ray.mask = 0xFFFFFFFFu;
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &query);
  HitInfo hit;
  hit.t = tmax;
  hit.triangle = SP_INVALID;
  hit.cut_short = 0u;  // Embree's walk has no leaf bound (docs/model.md#work-bounds)
  if (query.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    hit.t = query.ray.tfar;
    hit.triangle = query.hit.primID;
  }
  return hit;
}

#else  // built without Embree

struct EmbreeTraversal::Impl {};

std::unique_ptr<EmbreeTraversal::Impl> EmbreeTraversal::build(const Bvh&, unsigned) {
  throw Exception(ErrorCode::InvalidConfig, std::string("cpu_traversal: Embree ") + kEmbreeBuildHint);
}

HitInfo EmbreeTraversal::closest_hit(glm::vec3, glm::vec3, float, float tmax) const {
  HitInfo hit;
  hit.t = tmax;
  hit.triangle = SP_INVALID;
  hit.cut_short = 0u;  // Embree's walk has no leaf bound (docs/model.md#work-bounds)
  return hit;
}

#endif

EmbreeTraversal::EmbreeTraversal(const Bvh& bvh, unsigned threads)
    : bvh_(&bvh), threads_(threads), impl_(build(bvh, threads)) {}

EmbreeTraversal::~EmbreeTraversal() = default;

void EmbreeTraversal::update(const BvhChanges& changes) {
  if (!changes.triangles.empty()) impl_ = build(*bvh_, threads_);
}

std::unique_ptr<EmbreeTraversal> make_cpu_traversal(const Config& config, const Bvh& bvh, unsigned threads) {
  if (config.cpu_traversal != CpuTraversal::Embree) return nullptr;
  return std::make_unique<EmbreeTraversal>(bvh, threads);
}

}  // namespace sp
