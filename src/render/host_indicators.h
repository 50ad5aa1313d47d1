// Indicators that live on the host (the CPU backend's live_indicators())
// put where the indicator pass can draw them: a host-visible ring and a
// host-written VkDrawIndirectCommand, so both backends share one pipeline.
#pragma once

#include <cstdint>
#include <span>

#include "gpu/gpu_simulator.h"
#include "soundpaint/simulation.h"
#include "vk/buffer.h"
#include "vk/context.h"

namespace sp::draw {

class HostIndicators {
 public:
  // Throws sp::Exception.
  explicit HostIndicators(vk::Context& context);

  // Copies `indicators` into the ring (growing it when needed) and sets the
  // draw's instance count. Not while a frame drawing them is pending.
  // Throws sp::Exception (LimitExceeded when the ring would exceed the
  // device's storage-buffer range).
  void upload(std::span<const shader::Indicator> indicators);

  // The ring and draw arguments, for IndicatorPass; valid until the next upload().
  gpu::IndicatorView view();

 private:
  vk::Context& context_;
  std::uint32_t capacity_ = 0;
  vk::Buffer ring_;  // host-visible, coherent: writes before the submit are seen by it
  vk::Buffer args_;  // one VkDrawIndirectCommand
};

}  // namespace sp::draw
