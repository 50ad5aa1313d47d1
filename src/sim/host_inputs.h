// What the host application tells a running simulation between steps: where
// the listener is and which sources it made play (Simulator::set_listener and
// ::play). Both backends keep it the same way and hand it to plan_step.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "sim/step_plan.h"

namespace sp {

class HostInputs {
 public:
  HostInputs(glm::vec3 listener, std::size_t source_count) : listener_(listener), play_windows_(source_count) {}

  Result<bool> set_listener(glm::vec3 position) {
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
      return Error{ErrorCode::InvalidArgument, "set_listener: position must be finite"};
    listener_ = position;
    return true;
  }

  // Plays `source_id` for `duration` seconds from time `now` on.
  Result<bool> play(std::uint32_t source_id, double duration, double now) {
    if (source_id >= play_windows_.size())
      return Error{ErrorCode::InvalidArgument, "play: unknown source id " + std::to_string(source_id) + " (there are " +
                                                   std::to_string(play_windows_.size()) + " sources)"};
    if (!(duration >= 0.0) || !std::isfinite(duration))
      return Error{ErrorCode::InvalidArgument, "play: duration must be finite and >= 0"};
    play_windows_[source_id] = {now, now + duration};
    return true;
  }

  StepPlan plan(const World& world, std::uint64_t step) const {
    return plan_step(world, step, listener_, play_windows_);
  }

 private:
  glm::vec3 listener_;
  std::vector<PlayWindow> play_windows_;
};

}  // namespace sp
