#include "sim/step_loudness.h"

#include <cmath>

#include "soundpaint/signal.h"

namespace sp {

StepLoudness step_loudness(const SourceDesc& source, const PlayWindow& window, bool in_window, double t,
                           const Config& config) {
  const bool host_level = in_window && !std::isnan(window.level_db);
  if (!host_level && !source.signal) return {source.loudness, 1.0, true};
  double level = 0.0;
  if (host_level) {
    level = window.level_db;
  } else {
    // The play position: from the host's start, or the pattern's latest.
    const double position = in_window ? t - window.signal_origin : std::fmod(t - source.phase, source.interval);
    const double span = config.signal.window ? *config.signal.window : config.dt;
    level = source.signal->level_db(position, span, source.loop);
  }
  // A gain scales amplitude: +20 log10(gain) dB (-infinity at 0).
  if (in_window && window.gain != 1.0f) level += 20.0 * std::log10(static_cast<double>(window.gain));
  const double gain = signal_gain(level, config.signal);
  const float energy = static_cast<float>(static_cast<double>(source.loudness) * gain);
  // At or below tau_min a ray dies at its first hit and paints nothing.
  if (!(gain > 0.0) || !(energy > config.min_energy)) return {0.0f, 0.0, false};
  return {energy, gain, true};
}

}  // namespace sp
