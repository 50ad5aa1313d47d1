// The sound a source plays, reduced to what its cues need: its short-term
// loudness over time (docs/model.md#loudness-from-the-signal).
//
// Levels are in dB re full scale: L = 20 log10(RMS), where full scale is a
// sample of magnitude 1 (float PCM) or 32768 (16-bit PCM). A full-scale
// square wave is 0 dB, a full-scale sine -3.01 dB, as sox's `stats` reads
// them ("RMS lev dB"); silence is -infinity.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "soundpaint/config.h"
#include "soundpaint/result.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

// A loudness envelope: the mean square of the sound in consecutive blocks
// of about a millisecond (an integer number of samples, at least one), so
// that the RMS over any window of whole blocks is two lookups. Immutable;
// share it between sources with std::shared_ptr<const Signal>
// (SourceDesc::signal). Thread-safe to read.
class Signal {
 public:
  // Interleaved PCM with `channels` channels (1 to 8; the mean square is
  // taken over all of them) at `sample_rate` Hz, in [1000, 768000].
  // Errors (InvalidArgument, naming the problem): no samples, a sample
  // count that is not a multiple of `channels`, a bad rate, a sample that
  // is not finite.
  static Result<Signal> from_pcm(std::span<const float> samples, double sample_rate, unsigned channels = 1);
  static Result<Signal> from_pcm16(std::span<const std::int16_t> samples, double sample_rate, unsigned channels = 1);
  // 8-bit unsigned PCM as OpenAL takes it (128 is silence, full scale 128).
  static Result<Signal> from_pcm8(std::span<const std::uint8_t> samples, double sample_rate, unsigned channels = 1);
  // An envelope computed elsewhere: one level (dB re full scale; -infinity
  // for silence, never NaN or +infinity) per `hop_seconds`, in [0.0005, 1].
  static Result<Signal> from_levels(std::span<const float> levels_db, double hop_seconds);

  // Seconds of sound.
  double duration() const { return duration_; }
  // Seconds per block.
  double block_seconds() const { return block_seconds_; }

  // The level of [position, position + window) in dB re full scale: the
  // RMS of the blocks from the one holding `position` on, round(window /
  // block) of them (at least one). Past the end the sound is silence, or,
  // with `loop`, the signal again from its start (and `position` is taken
  // modulo duration()). Before 0: silence. -infinity when all is silent,
  // and for a position that is not finite or a window that is not > 0.
  double level_db(double position, double window, bool loop) const;

 private:
  Signal(const std::vector<double>& block_mean_squares, double block_seconds, double duration);
  double mean_square(double position, double window, bool loop) const;
  // prefix_[k]: the sum of the mean squares of blocks 0 .. k-1.
  std::vector<double> prefix_;
  double block_seconds_ = 0.0;
  double duration_ = 0.0;
};

// The law (docs/model.md#loudness-from-the-signal): the gain in [0, 1] that
// a level gives, clamp((level_db - floor_db) / (reference_db - floor_db), 0, 1).
double signal_gain(double level_db, const SignalSettings& law);

// dB re full scale of the RMS of interleaved float samples (all channels
// together): what a voice fed its mixer's block is heard at
// (SoundScene::set_voice_level). -infinity for silence or no samples.
double rms_level_db(std::span<const float> samples);

}  // namespace sp

SP_CPP_API_END
