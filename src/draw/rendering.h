// Dynamic rendering's begin call for the one-colour, one-depth passes of
// `render` and the viewer: attachments described by how the pass uses them.
#pragma once

#include <vulkan/vulkan.h>

namespace sp::draw {

// How a pass uses one attachment.
struct AttachmentUse {
  VkImageView view;
  VkImageLayout layout;
  VkAttachmentLoadOp load;
  VkAttachmentStoreOp store;
};

inline VkRenderingAttachmentInfo attachment(const AttachmentUse& use) {
  VkRenderingAttachmentInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  info.imageView = use.view;
  info.imageLayout = use.layout;
  info.loadOp = use.load;
  info.storeOp = use.store;
  return info;
}

inline void begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, const VkRenderingAttachmentInfo& color,
                            const VkRenderingAttachmentInfo& depth) {
  VkRenderingInfo rendering{};
  rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  rendering.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &rendering);
}

}  // namespace sp::draw
