// The host's frame pacing: two frames in flight, each with its own command
// buffer and fence. A slot's command buffer is re-recorded only after its
// fence says the GPU finished the frame that last used it.
#pragma once

#include <array>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "host_vulkan.h"
#include "vulkan_objects.h"

class FrameSlots {
 public:
  static constexpr std::uint32_t kFramesInFlight = 2;

  explicit FrameSlots(const HostContext& host);
  // Waits for the device, so that nothing declared before this object (and
  // still used by frames in flight) is destroyed under a running frame.
  ~FrameSlots();
  FrameSlots(const FrameSlots&) = delete;
  FrameSlots& operator=(const FrameSlots&) = delete;

  // Waits for the slot of `frame`, then begins recording its command buffer.
  VkCommandBuffer begin(std::uint64_t frame);
  // Ends the command buffer of `frame` and submits it with the slot's fence.
  void submit(std::uint64_t frame);
  void wait_idle() const;

 private:
  const HostContext& host_;
  CommandPool pool_;
  std::array<VkCommandBuffer, kFramesInFlight> commands_{};
  std::array<Fence, kFramesInFlight> fences_;
};
