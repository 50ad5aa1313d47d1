// What both visualizer backends share: the borrowed device, the scene, the
// indicator pass built for the host's attachments, the display settings,
// the frame clock, and the argument checks of the record calls.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "draw/indicator_pass.h"
#include "embed/frame_clock.h"
#include "soundpaint/visualizer.h"
#include "vk/context.h"

namespace sp::embed {

class VisualizerBase : public Visualizer {
 public:
  // `context` is the borrowed host device.
  VisualizerBase(std::unique_ptr<vk::Context> context, const DrawTarget& target, World world,
                 const VisualizerSettings& settings, bool simulation_on_graphics_queue);

  SoundScene& scene() override { return scene_; }

  Result<bool> record_draw(VkCommandBuffer cmd, const Mat4& view, const Mat4& projection,
                           const VkRect2D* area) override;
  Result<bool> record_draw(VkCommandBuffer cmd, const Mat4& view, const Mat4& projection,
                           const DrawOptions& options) override;
  Result<bool> set_display(const DisplaySettings& settings) override;
  const DisplaySettings& display() const override { return scene_.world().config.display; }
  Result<bool> set_scene_depth(std::span<const VkImageView> views) override;
  Result<IndicatorRing> indicator_ring() override;

 protected:
  // The ring to draw and whether it has been initialised by a recorded
  // record_simulation (drawing before that would read garbage arguments).
  virtual gpu::IndicatorView indicator_view() = 0;
  virtual bool ready_to_draw() const = 0;

  // Checks record_simulation's arguments; an Error names the problem.
  Result<bool> check_simulation_args(VkCommandBuffer cmd, double dt) const;

  // The end of every record_simulation: the display's source table and
  // prepass (live spots per source, caps), after the ring's last writes.
  void record_display(VkCommandBuffer cmd);

  std::unique_ptr<vk::Context> context_;
  SoundScene scene_;
  FrameClock clock_;
  // The queue running record_simulation has graphics stages (false for an
  // async compute queue, whose barriers may not name them).
  bool simulation_on_graphics_queue_;

 private:
  draw::IndicatorPass pass_;
  std::vector<VkDescriptorSet> scene_depths_;
  bool pass_bound_ = false;
};

}  // namespace sp::embed
