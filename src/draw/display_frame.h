// What one frame's indicator draw needs besides the ring: how the host
// looks at the scene (DrawView) and what the display shows (DisplayFrame).
#pragma once

#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "soundpaint/display.h"
#include "soundpaint/simulation.h"

namespace sp::draw {

// The most pixels a viewport's side or origin may have: each pair travels
// to the indicator pass as two 16-bit halves of a push-constant word.
inline constexpr std::uint32_t kMaxViewportPixels = 0xFFFFu;

struct DrawView {
  glm::mat4 view_projection{1.0f};  // world -> Vulkan clip space
  glm::vec3 eye{0.0f};              // camera position, world space
  glm::vec2 viewport{1.0f};         // pixels
  glm::uvec2 viewport_origin{0u};   // the viewport's top-left pixel in the framebuffer and the scene's depth
  float pixel_scale = 0.0f;         // pixels per metre 1 m ahead: |projection[1][1]| * height / 2; 0: unknown
  float depth_a = 0.0f;             // projection[2][2]; view distance = depth_b / (depth + depth_a)
  float depth_b = 0.0f;             // projection[3][2]
  glm::vec2 heading{0.0f, -1.0f};   // the view's heading, world (x, z), unit: view_heading()

  // From the host's matrices (Vulkan clip space, a perspective projection)
  // and the viewport's size in pixels.
  static DrawView from(const glm::mat4& view, const glm::mat4& projection, glm::vec2 viewport);
};

// The way a camera faces in the horizontal plane (world up is +Y), as a
// unit vector of world (x, z): off-screen arrows tell bearings from it
// (sp_arrows.h). `forward` and `up` are the camera's unit view direction
// and up vector. It is forward projected on the horizontal plane; for a
// camera looking straight down, the up vector's projection (the way the
// picture's top faces), and straight up, its opposite (the way the
// picture's bottom faces: where a player tilting their head back was
// facing). Either way it is the limit of forward's projection as the
// camera tips through straight down or up, so arrows do not flip there.
// World -Z for a camera with neither.
glm::vec2 view_heading(glm::vec3 forward, glm::vec3 up);

struct DisplayFrame {
  std::uint32_t current_step = 0;    // the last step run: ages count from it (shown_step())
  float dt = 1.0f / 60.0f;           // seconds per step
  float lifetime = 1.0f;             // the display's lifetime (display_lifetime()): sp_indicator_live decides
  float inv_indicator_size = 0.0f;   // 1 / indicator_size, 0 when it is 0
  std::uint32_t source_count = 0;    // entries of the source table
  std::uint32_t category_count = 0;  // categories the world numbers
  DisplaySettings settings;
  bool offscreen_arrows = false;  // settings.offscreen_arrows, or the front end's default

  // For `world` after `steps_run` steps, shown as `settings` say;
  // `arrows_by_default` where the settings leave arrows unset.
  static DisplayFrame from(const World& world, std::uint64_t steps_run, const DisplaySettings& settings,
                           bool arrows_by_default);
};

}  // namespace sp::draw
