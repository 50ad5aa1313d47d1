#include "core/glm_interop.h"
#include "render/view_camera.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "sim/world_geometry.h"
#include "soundpaint/result.h"

namespace sp::draw {
namespace {

// Directions closer than this to parallel make a degenerate basis.
constexpr float kParallelCosine = 0.999f;

glm::vec3 bounds_centre(const World& world) {
  if (world.geometry->bvh.nodes.empty()) return glm::vec3(0.0f);
  return 0.5f * (world.geometry->bvh.nodes[0].bmin + world.geometry->bvh.nodes[0].bmax);
}

// An up vector orthogonal to `forward`: `preferred` if usable, else +Y, else -Z.
glm::vec3 orthogonal_up(glm::vec3 forward, glm::vec3 preferred) {
  for (glm::vec3 candidate : {preferred, glm::vec3(0, 1, 0), glm::vec3(0, 0, -1)}) {
    const float length = glm::length(candidate);
    if (length == 0.0f || std::abs(glm::dot(forward, candidate / length)) > kParallelCosine) continue;
    const glm::vec3 right = glm::normalize(glm::cross(forward, candidate));
    return glm::cross(right, forward);
  }
  return glm::vec3(0, 1, 0);  // unreachable: +Y and -Z cannot both be parallel to forward
}

}  // namespace

ViewCamera make_view_camera(const std::optional<Camera>& scene_camera, const World& world,
                            const CameraOverrides& overrides, std::uint32_t width, std::uint32_t height) {
  ViewCamera camera;
  glm::vec3 preferred_up(0.0f, 1.0f, 0.0f);
  if (scene_camera) {
    camera.eye = world.config.listener_position ? *world.config.listener_position : scene_camera->position();
    const glm::vec3 minus_z = -glm::vec3(to_glm(scene_camera->world)[2]);
    camera.forward = glm::length(minus_z) > 0.0f ? glm::normalize(minus_z) : glm::vec3(0, 0, -1);
    preferred_up = glm::vec3(to_glm(scene_camera->world)[1]);
    camera.yfov = scene_camera->yfov;
    camera.znear = scene_camera->znear;
    camera.zfar = scene_camera->zfar;
  } else {
    camera.eye = world.listener;
    const glm::vec3 to_centre = bounds_centre(world) - camera.eye;
    camera.forward = glm::length(to_centre) > 1e-6f ? glm::normalize(to_centre) : glm::vec3(0, 0, -1);
  }

  if (overrides.position) camera.eye = *overrides.position;
  if (overrides.look_at) {
    const glm::vec3 direction = *overrides.look_at - camera.eye;
    if (!(glm::length(direction) > 1e-6f))
      throw Exception(ErrorCode::InvalidArgument, "option --look-at: the point must differ from the camera position");
    camera.forward = glm::normalize(direction);
    preferred_up = glm::vec3(0.0f, 1.0f, 0.0f);  // a new direction: keep the horizon level
  }
  if (overrides.yfov_degrees) {
    const float degrees = *overrides.yfov_degrees;
    if (!(degrees > 0.0f && degrees < 180.0f))
      throw Exception(ErrorCode::InvalidArgument, "option --fov: expected degrees in (0, 180)");
    camera.yfov = glm::radians(degrees);
  }
  camera.up = orthogonal_up(camera.forward, preferred_up);

  camera.view = glm::lookAtRH(camera.eye, camera.eye + camera.forward, camera.up);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  camera.projection = glm::perspectiveRH_ZO(camera.yfov, aspect, camera.znear, camera.zfar);
  camera.projection[1][1] *= -1.0f;  // Vulkan's clip-space y points down
  return camera;
}

std::optional<glm::vec2> project_to_pixel(const ViewCamera& camera, glm::vec3 p, std::uint32_t width,
                                          std::uint32_t height) {
  const glm::vec4 clip = camera.view_projection() * glm::vec4(p, 1.0f);
  if (!(clip.w > 0.0f)) return std::nullopt;
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  if (ndc.z < 0.0f || ndc.z > 1.0f) return std::nullopt;
  return glm::vec2((ndc.x * 0.5f + 0.5f) * static_cast<float>(width),
                   (ndc.y * 0.5f + 0.5f) * static_cast<float>(height));
}

}  // namespace sp::draw
