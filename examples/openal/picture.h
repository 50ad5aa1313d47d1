// The example's own pictures: soundpaint's offline renderer (the one
// `soundpaint render` uses, internal to this repository) draws the level
// and the live cues from a point towards another. A game draws them in its
// own frame with sp::Visualizer instead (examples/embed, docs/integrating.md);
// nothing here is what a game needs to add.
#pragma once

#include <filesystem>
#include <memory>

#include "soundpaint/simulation.h"

class PictureWriter {
 public:
  PictureWriter(const sp::Scene& scene, const sp::World& world, unsigned width, unsigned height);
  ~PictureWriter();
  void write(const std::filesystem::path& png, sp::Simulator& simulator, sp::Vec3 eye, sp::Vec3 look_at);

 private:
  struct State;
  std::unique_ptr<State> state_;
};
