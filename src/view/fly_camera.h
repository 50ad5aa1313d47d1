// The viewer's camera: an eye that flies (WASD, Q/E down/up) and turns
// (yaw about +Y, pitch), with the ray through a pixel for picking.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/view_camera.h"

namespace sp::view {

struct FlyCamera {
  glm::vec3 eye{0.0f};
  float yaw = 0.0f;    // radians about +Y; 0 looks down -Z, as a glTF camera
  float pitch = 0.0f;  // radians, up positive, kept inside +-89 degrees
  float yfov = 0.8f;   // radians

  // Takes the eye, direction and field of view of `camera`.
  static FlyCamera from(const draw::ViewCamera& camera);

  glm::vec3 forward() const;
  glm::vec3 right() const;  // horizontal
  // Turns by a mouse movement in pixels (0.004 radians a pixel).
  void turn(glm::vec2 delta_pixels);
  // Moves by `axes` (x right, y up, z forward) at `speed` metres a second.
  void fly(glm::vec3 axes, float speed, float seconds);
  // The Vulkan matrices for a `width` x `height` framebuffer.
  draw::ViewCamera view_camera(std::uint32_t width, std::uint32_t height) const;
  // Unit direction of the ray from the eye through pixel `pixel` (from the
  // top-left corner, y down) of a `width` x `height` framebuffer.
  glm::vec3 ray_through(glm::vec2 pixel, std::uint32_t width, std::uint32_t height) const;
};

}  // namespace sp::view
