// The camera a picture is taken with: where it comes from (the scene's
// camera, the listener, command-line overrides) and its Vulkan matrices.
#pragma once

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>

#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"

namespace sp::draw {

// Optional replacements for parts of the default camera.
struct CameraOverrides {
  std::optional<glm::vec3> position;  // eye, metres (world space)
  std::optional<glm::vec3> look_at;   // point the camera faces; must differ from the eye
  std::optional<float> yfov_degrees;  // vertical field of view, in (0, 180)
};

struct ViewCamera {
  glm::vec3 eye{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, orthogonal to forward
  float yfov = 0.8f;                     // radians
  float znear = 0.05f;                   // metres
  float zfar = 1000.0f;                  // metres
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};  // Vulkan clip space: y down, depth in [0, 1]

  glm::mat4 view_projection() const { return projection * view; }
};

// The camera for a picture of `world` at `width` x `height` pixels:
//  - the scene's camera (its world matrix looks down local -Z, +Y up), moved
//    to the configured listener position when the config sets one;
//  - without a scene camera: at the listener, facing the centre of the
//    scene's bounding box;
// then `overrides` replace position, view direction (the camera keeps its
// up vector unless the new direction is parallel to it; +Y is preferred)
// and field of view. The aspect ratio always comes from the image.
// Throws sp::Exception(InvalidArgument) when look_at equals the eye or the
// field of view is outside (0, 180) degrees.
ViewCamera make_view_camera(const std::optional<Camera>& scene_camera, const World& world,
                            const CameraOverrides& overrides, std::uint32_t width, std::uint32_t height);

// Where world point `p` lands in an image of `width` x `height` pixels seen
// through `camera`, in pixels from the top-left corner (pixel (i, j) covers
// [i, i+1) x [j, j+1); y grows downwards), or nothing when it is behind the
// eye or outside the depth range.
std::optional<glm::vec2> project_to_pixel(const ViewCamera& camera, glm::vec3 p, std::uint32_t width,
                                          std::uint32_t height);

}  // namespace sp::draw
