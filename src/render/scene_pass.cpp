#include "render/scene_pass.h"

#include <glm/geometric.hpp>

#include "draw/draw_layout_checks.h"
#include "scene.frag.spv.h"
#include "scene.vert.spv.h"
#include "sp_types.h"

namespace sp::draw {
namespace {

// Light from above and a little to the side, so floors, walls facing +X/+Z
// and walls facing -X/-Z all get different brightness.
const glm::vec3 kLightDirection = glm::normalize(glm::vec3(0.35f, 1.0f, 0.55f));
// Enough that surfaces facing away from the light keep their tint.
constexpr float kAmbient = 0.3f;
// Metres: rooms beyond the next one fade, which helps read depth through doors.
constexpr float kFogDistance = 40.0f;
// The eye closer than this to the listener would sit inside its marker.
constexpr float kListenerMarkerClearance = 1.0f;

}  // namespace

ScenePass::ScenePass(vk::Context& context, const SceneMesh& mesh, VkFormat color_format, VkFormat depth_format)
    : level_triangles_(mesh.level_triangles),
      source_marker_triangles_(mesh.source_marker_triangles),
      listener_marker_triangles_(mesh.listener_marker_triangles),
      bindings_(context, 1, "scene pass bindings") {
  const VkDeviceSize bytes = mesh.triangles.size() * sizeof(shader::SceneTriangle);
  // An empty mesh still gets a buffer: a binding must point at something.
  triangles_ = vk::Buffer(context, bytes > 0 ? bytes : sizeof(shader::SceneTriangle),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          vk::MemoryUsage::DeviceLocal, "scene triangles");
  vk::upload(context, triangles_, mesh.triangles.data(), bytes);
  bindings_.bind(context, 0, triangles_);

  GraphicsPipelineDesc desc;
  desc.vertex_spirv = sp_spirv_scene_vert;
  desc.fragment_spirv = sp_spirv_scene_frag;
  desc.set_layout = bindings_.layout();
  desc.push_constant_bytes = sizeof(shader::ScenePush);
  desc.color_format = color_format;
  desc.depth_format = depth_format;
  desc.blend = Blend::Opaque;
  desc.depth_write = true;
  desc.name = "scene pass";
  pipeline_ = GraphicsPipeline(context, desc);
}

void ScenePass::record(VkCommandBuffer cmd, const ViewCamera& camera, glm::vec3 listener) const {
  shader::ScenePush push{};
  push.view_proj = camera.view_projection();
  push.eye = camera.eye;
  push.ambient = kAmbient;
  push.light_dir = kLightDirection;
  push.fog_distance = kFogDistance;

  std::uint32_t triangles = level_triangles_ + source_marker_triangles_;
  if (glm::length(camera.eye - listener) > kListenerMarkerClearance) triangles += listener_marker_triangles_;
  if (triangles == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
  const VkDescriptorSet set = bindings_.set();
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.layout(), 0, 1, &set, 0, nullptr);
  vkCmdPushConstants(cmd, pipeline_.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                     &push);
  vkCmdDraw(cmd, triangles * 3, 1, 0, 0);
}

}  // namespace sp::draw
