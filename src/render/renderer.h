// Records, submits and reads back one frame: the scene pass, then the
// indicator pass over it, into an offscreen target. One renderer per
// picture size; frames are drawn one at a time (render() waits).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "render/host_indicators.h"
#include "draw/indicator_pass.h"
#include "render/render_target.h"
#include "render/scene_pass.h"
#include "render/view_camera.h"
#include "soundpaint/simulation.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace sp::draw {

struct RenderSettings {
  std::uint32_t width = 1280;  // pixels, 1 .. the device's maxImageDimension2D
  std::uint32_t height = 720;  // pixels, likewise
  bool markers = true;         // source and listener markers in the scene pass
};

// GPU time of the last frame from timestamp queries, milliseconds. On a
// tiling or deferring rasteriser (lavapipe bins draws and rasterises them
// later on worker threads) the per-pass split measures mostly vertex work;
// frame_ms, which ends after the copy-out, includes all rasterisation.
struct FrameTimings {
  double scene_ms = 0.0;      // frame start to the end of the scene pass
  double indicator_ms = 0.0;  // the indicator pass's draw
  double frame_ms = 0.0;      // frame start to the end of the copy to the readback buffer
};

class Renderer {
 public:
  // Uploads the level and markers of `world` (which need not outlive the
  // renderer); `context` must. Throws sp::Exception (LimitExceeded for an
  // image larger than the device allows, Vulkan on failure).
  Renderer(vk::Context& context, const World& world, const RenderSettings& settings);
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The scene and `simulator`'s live indicators as they are after its last
  // step, shown as its config's `display` says (off-screen arrows on unless
  // it says otherwise), clipped to their surfaces. A GPU simulator on this
  // renderer's context is drawn straight from its ring and indirect
  // arguments (nothing read back); any other backend through
  // live_indicators(), uploaded into a host-visible ring. Sources whose
  // straight way to the listener is blocked get their arrows in view too
  // (make_source_cues).
  RgbaImage render(const ViewCamera& camera, Simulator& simulator);

  // The scene and the ring of `indicators` (on this renderer's context) of
  // `world` after `steps_run` steps. Ring and arguments written by compute
  // work submitted earlier are made visible by the frame's first barrier.
  RgbaImage render(const ViewCamera& camera, const gpu::IndicatorView& indicators, const World& world,
                   std::uint64_t steps_run);

  // Per source id, SP_SOURCE_CUE_* bits for the next frames (sp_draw_types.h):
  // a source heard and occluded gets its arrow even when it is in view.
  // All 0 until set; render(camera, simulator) sets them from its world's
  // geometry (make_source_cues). Throws
  // sp::Exception(LimitExceeded) past the renderer's source capacity.
  void set_source_cues(std::span<const std::uint32_t> cues) { indicators_.set_source_cues(cues); }

  // Timings of the last frame; empty when the queue has no timestamps.
  std::optional<FrameTimings> last_timings() const { return last_timings_; }

 private:
  void read_timestamps();

  static constexpr std::uint32_t kQueries = 4;

  vk::Context& context_;
  glm::vec3 listener_;
  RenderTarget target_;
  ScenePass scene_;
  IndicatorPass indicators_;
  VkDescriptorSet scene_depth_ = VK_NULL_HANDLE;   // the target's depth, for clipping
  std::optional<HostIndicators> host_indicators_;  // made on first use by a host-side backend
  vk::UniqueQueryPool timestamps_;                 // kQueries: start, scene done, indicators done, copy done
  std::optional<FrameTimings> last_timings_;
};

}  // namespace sp::draw
