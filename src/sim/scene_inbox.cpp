#include "sim/scene_inbox.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace sp::detail {

std::optional<std::uint32_t> SceneInbox::lowest_free(std::uint32_t capacity) const {
  if (taken >= capacity) return std::nullopt;
  const auto free_slot = std::find(slot_taken.begin(), slot_taken.end(), false);
  return static_cast<std::uint32_t>(free_slot - slot_taken.begin());
}

void SceneInbox::take(std::uint32_t id) {
  if (id >= slot_taken.size()) slot_taken.resize(std::size_t{id} + 1, false);
  if (!slot_taken[id]) taken += 1;
  slot_taken[id] = true;
}

void SceneInbox::release(std::uint32_t id) {
  if (id >= slot_taken.size() || !slot_taken[id]) return;
  slot_taken[id] = false;
  taken -= 1;
}

void expect_stepping_thread([[maybe_unused]] const SceneInbox& inbox, [[maybe_unused]] const char* call) {
#ifndef NDEBUG
  const std::thread::id stepping = inbox.stepping_thread.load(std::memory_order_relaxed);
  if (stepping == std::thread::id{} || stepping == std::this_thread::get_id()) return;
  std::fprintf(stderr,
               "soundpaint: SoundScene::%s called on a thread other than the one that steps the simulation; "
               "only the SoundScene calls simulation.h marks \"any thread\" may be (debug check)\n",
               call);
  std::abort();
#endif
}

}  // namespace sp::detail
