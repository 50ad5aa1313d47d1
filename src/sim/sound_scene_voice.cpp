// SoundScene, the host's side of signals and voices: what an audio engine
// tells of the sounds it plays (docs/model.md#loudness-from-the-signal,
// docs/integrating.md#voices). Checked at the call and queued like every
// other change (sound_scene.cpp), so an audio thread may make them.
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/invalid_argument.h"
#include "core/finite.h"
#include "sim/scene_inbox.h"
#include "soundpaint/signal.h"
#include "soundpaint/simulation.h"

namespace sp {
namespace {}  // namespace

Result<bool> SoundScene::set_signal(std::uint32_t id, std::shared_ptr<const Signal> signal, bool loop) {
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("set_signal", id); !known) return known;
  inbox_->commands.emplace_back(detail::SetSignal{id, std::move(signal), loop});
  return true;
}

Result<bool> SoundScene::set_voice(std::uint32_t id, const VoiceState& state) {
  if (!all_finite(state.position)) return invalid_argument_error("set_voice: position must be finite");
  if (!(state.gain >= 0.0f) || !std::isfinite(state.gain))
    return invalid_argument_error("set_voice: gain must be finite and >= 0, got " + std::to_string(state.gain));
  if (!std::isfinite(state.signal_position))
    return invalid_argument_error("set_voice: signal_position must be finite (negative: keep the running position)");
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("set_voice", id); !known) return known;
  inbox_->commands.emplace_back(detail::SetVoice{id, state});
  return true;
}

Result<bool> SoundScene::set_voice_level(std::uint32_t id, double level_db) {
  if (level_db == std::numeric_limits<double>::infinity())
    return invalid_argument_error(
        "set_voice_level: level_db must be a level in dB, -infinity (silence) or NaN (none), not +infinity");
  std::lock_guard lock(inbox_->mutex);
  if (auto known = check_id("set_voice_level", id); !known) return known;
  inbox_->commands.emplace_back(detail::SetVoiceLevel{id, level_db});
  return true;
}

Result<bool> SoundScene::feed_voice(std::uint32_t id, std::span<const float> samples) {
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!std::isfinite(samples[i]))
      return invalid_argument_error("feed_voice: sample " + std::to_string(i) + " is not finite");
  return set_voice_level(id, rms_level_db(samples));
}

}  // namespace sp
