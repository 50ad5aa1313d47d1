// The host's own drawing: the level's triangles in flat grey, depth written,
// so that soundpaint's indicators are drawn over (and hidden by) the level.
#pragma once

#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <soundpaint/math.h>
#include <vulkan/vulkan.h>

#include "host_vulkan.h"
#include "vulkan_objects.h"

class SceneRenderer {
 public:
  // `triangles`: 3 world-space vertices per triangle (a soundpaint Scene's),
  // uploaded once.
  SceneRenderer(const HostContext& host, std::span<const sp::Vec3> triangles, VkFormat color_format,
                VkFormat depth_format);

  // Inside the rendering begun by OffscreenTarget::begin (viewport and
  // scissor already set).
  void draw(VkCommandBuffer cmd, const glm::mat4& view_projection) const;

 private:
  void upload(const HostContext& host, std::span<const sp::Vec3> triangles);
  void create_pipeline(VkDevice device, VkFormat color_format, VkFormat depth_format);

  std::uint32_t vertex_count_ = 0;
  Buffer vertices_;
  Memory vertex_memory_;
  PipelineLayout layout_;
  Pipeline pipeline_;
};
