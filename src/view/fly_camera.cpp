#include "view/fly_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

namespace sp::view {
namespace {

constexpr float kTurnPerPixel = 0.004f;
constexpr float kMaxPitch = 1.55f;  // ~89 degrees: lookAt needs forward off +Y
constexpr float kNear = 0.05f;
constexpr float kFar = 1000.0f;

}  // namespace

FlyCamera FlyCamera::from(const draw::ViewCamera& camera) {
  FlyCamera fly;
  fly.eye = camera.eye;
  const glm::vec3 f = glm::normalize(camera.forward);
  fly.pitch = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  fly.yaw = std::atan2(-f.x, -f.z);
  fly.yfov = camera.yfov;
  return fly;
}

glm::vec3 FlyCamera::forward() const {
  return {-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

glm::vec3 FlyCamera::right() const { return {std::cos(yaw), 0.0f, -std::sin(yaw)}; }

void FlyCamera::turn(glm::vec2 delta_pixels) {
  yaw -= delta_pixels.x * kTurnPerPixel;
  pitch = std::clamp(pitch - delta_pixels.y * kTurnPerPixel, -kMaxPitch, kMaxPitch);
}

void FlyCamera::fly(glm::vec3 axes, float speed, float seconds) {
  eye += (right() * axes.x + glm::vec3(0.0f, 1.0f, 0.0f) * axes.y + forward() * axes.z) * (speed * seconds);
}

draw::ViewCamera FlyCamera::view_camera(std::uint32_t width, std::uint32_t height) const {
  draw::ViewCamera camera;
  camera.eye = eye;
  camera.forward = forward();
  camera.up = glm::normalize(glm::cross(right(), camera.forward));
  camera.yfov = yfov;
  camera.znear = kNear;
  camera.zfar = kFar;
  camera.view = glm::lookAtRH(eye, eye + camera.forward, camera.up);
  const float aspect = static_cast<float>(std::max(width, 1u)) / static_cast<float>(std::max(height, 1u));
  camera.projection = glm::perspectiveRH_ZO(yfov, aspect, kNear, kFar);
  camera.projection[1][1] *= -1.0f;  // Vulkan's framebuffer y points down
  return camera;
}

glm::vec3 FlyCamera::ray_through(glm::vec2 pixel, std::uint32_t width, std::uint32_t height) const {
  const float w = static_cast<float>(std::max(width, 1u));
  const float h = static_cast<float>(std::max(height, 1u));
  const float tan_half = std::tan(0.5f * yfov);
  const float x = (2.0f * pixel.x / w - 1.0f) * tan_half * (w / h);
  const float y = (1.0f - 2.0f * pixel.y / h) * tan_half;
  const glm::vec3 up = glm::normalize(glm::cross(right(), forward()));
  return glm::normalize(forward() + right() * x + up * y);
}

}  // namespace sp::view
