// The GPU backend's side of Simulator::set_config: the buffers a new config
// sizes differently, made aside, then committed into GpuResources with what
// carries the simulation's state across (the ring's spots and its head,
// the layers' acoustics). The descriptor set is kept and pointed at the new
// buffers; the kernels are kept but resolve, rebuilt when diffraction is
// switched on or off (make_resolve_kernel).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "bvh/bvh.h"
#include "gpu/gpu_resources.h"
#include "sp_gpu_types.h"
#include "vk/context.h"

namespace sp::gpu {

class GpuResize {
 public:
  // Creates the buffers `resources` needs for `config` (those whose size
  // changes, and the exposed edges of `bvh` when diffraction is on and the
  // edges buffer holds none, uploaded now), and resolve's kernel when
  // diffraction is switched on or off. Throws sp::Exception
  // (LimitExceeded: a device limit; Vulkan) with `resources` untouched.
  GpuResize(vk::Context& context, const GpuResources& resources, const Config& config, const Bvh& bvh);

  // Whether the capture buffer, the last step's indicators, is replaced.
  bool replaces_capture() const { return replaced_[capture_index()]; }

  // Records, for a command buffer the caller submits and waits for before
  // commit(): the ring's newest spots that fit into the new ring, in order
  // from its slot 0; the ring's head and fill in `control`; the new
  // admission buffer zeroed; `layer_table` into the layers buffer.
  // `control` is the control block as the last step left it.
  void record(VkCommandBuffer cmd, const GpuResources& resources, const shader::Control& control,
              std::span<const shader::LayerAcoustics> layer_table) const;

  // After the recorded work is done: moves the new buffers (and kernel)
  // into `resources`, points the descriptor set at them and takes the new
  // sizes.
  // `control` (the host's copy of the control block) takes the ring's new
  // head and fill.
  void commit(vk::Context& context, GpuResources& resources, shader::Control& control);

 private:
  static std::size_t capture_index();
  static std::size_t ring_index();
  // Spots the new ring keeps of `filled`.
  std::uint32_t kept_spots(std::uint32_t filled) const;

  ConfigSizes sizes_;
  std::array<vk::Buffer, kSizedBufferCount> buffers_;  // per kSizedBuffers entry, when replaced
  std::array<bool, kSizedBufferCount> replaced_{};
  vk::Buffer edges_;             // the exposed edges, when they must be uploaded
  vk::ComputePipeline resolve_;  // resolve for the config's diffraction, when it changes
  bool diffraction_ = false;
  std::size_t edge_count_ = 0;
};

}  // namespace sp::gpu
