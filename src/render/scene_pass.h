// The scene pass: the level's triangles and the markers, uploaded once,
// drawn opaque with depth writes so the indicator pass is tested against it.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include <glm/glm.hpp>

#include "draw/graphics_pipeline.h"
#include "sp_draw_types.h"
#include "render/scene_mesh.h"
#include "render/view_camera.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "vk/context.h"

namespace sp::draw {

class ScenePass {
 public:
  // Linear RGB the frame is cleared to; the shader's fog fades towards it.
  static constexpr float kClearColor[4] = {SP_CLEAR_RGB, 1.0f};

  // Uploads `mesh` (waits for the upload). Throws sp::Exception.
  ScenePass(vk::Context& context, const SceneMesh& mesh, VkFormat color_format, VkFormat depth_format);

  // Records the draw inside an active rendering scope. The listener marker
  // is left out when the eye is inside or next to it.
  void record(VkCommandBuffer cmd, const ViewCamera& camera, glm::vec3 listener) const;

 private:
  std::uint32_t level_triangles_ = 0;
  std::uint32_t source_marker_triangles_ = 0;
  std::uint32_t listener_marker_triangles_ = 0;
  vk::Buffer triangles_;
  vk::StorageBindings bindings_;
  GraphicsPipeline pipeline_;
};

}  // namespace sp::draw
