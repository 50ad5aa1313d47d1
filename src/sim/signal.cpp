// Signal: a sound's mean square per block of about a millisecond, kept as
// prefix sums so that a window's RMS costs two lookups whatever its length
// (docs/model.md#loudness-from-the-signal). A millisecond resolves a
// gunshot's attack; a three-minute track is 180,000 doubles, not the
// 8.6 million samples.
#include "core/invalid_argument.h"
#include "soundpaint/signal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sp {
namespace {

constexpr double kBlockSeconds = 0.001;
constexpr double kMinRate = 1000.0, kMaxRate = 768000.0;
constexpr unsigned kMaxChannels = 8;
constexpr double kMinHop = 0.0005, kMaxHop = 1.0;
constexpr double kEdge = 1e-6;  // blocks: how near a block's start a position counts as in it

// Checks what every PCM layout shares; empty when fine.
std::string pcm_problem(std::size_t count, double sample_rate, unsigned channels) {
  if (channels < 1 || channels > kMaxChannels) return "channels must be 1 to 8, got " + std::to_string(channels);
  if (!(sample_rate >= kMinRate && sample_rate <= kMaxRate))
    return "sample_rate must be in [1000, 768000] Hz, got " + std::to_string(sample_rate);
  if (count == 0) return "no samples";
  if (count % channels != 0)
    return std::to_string(count) + " samples are not a whole number of " + std::to_string(channels) + "-channel frames";
  return {};
}

// `to_unit(i)`: sample i scaled so that full scale is 1.
template <class ToUnit>
Result<std::vector<double>> block_powers(std::size_t count, double sample_rate, unsigned channels, ToUnit to_unit,
                                         std::size_t& frames_per_block) {
  frames_per_block = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(sample_rate * kBlockSeconds)));
  const std::size_t block_values = frames_per_block * channels;
  std::vector<double> powers((count + block_values - 1) / block_values, 0.0);
  for (std::size_t i = 0; i < count; ++i) {
    const double x = to_unit(i);
    if (!std::isfinite(x)) return invalid_argument_error("sample " + std::to_string(i) + " is not finite");
    powers[i / block_values] += x * x;
  }
  // A last, partial block is padded with silence: the sound has ended.
  for (double& p : powers) p /= static_cast<double>(block_values);
  return powers;
}

struct BlockPowers {
  std::vector<double> mean_squares;
  double block_seconds = 0.0;
  double duration = 0.0;
};

template <class Sample, class ToUnit>
Result<BlockPowers> pcm_powers(const char* what, std::span<const Sample> samples, double sample_rate, unsigned channels,
                               ToUnit to_unit) {
  if (std::string problem = pcm_problem(samples.size(), sample_rate, channels); !problem.empty())
    return invalid_argument_error(std::string(what) + ": " + problem);
  std::size_t frames_per_block = 0;
  auto powers = block_powers(
      samples.size(), sample_rate, channels, [&](std::size_t i) { return to_unit(samples[i]); }, frames_per_block);
  if (!powers) return invalid_argument_error(std::string(what) + ": " + powers.error().message);
  const double frames = static_cast<double>(samples.size() / channels);
  return BlockPowers{std::move(powers).value(), static_cast<double>(frames_per_block) / sample_rate,
                     frames / sample_rate};
}

}  // namespace

Signal::Signal(const std::vector<double>& block_mean_squares, double block_seconds, double duration)
    : block_seconds_(block_seconds), duration_(duration) {
  prefix_.resize(block_mean_squares.size() + 1, 0.0);
  for (std::size_t k = 0; k < block_mean_squares.size(); ++k) prefix_[k + 1] = prefix_[k] + block_mean_squares[k];
}

Result<Signal> Signal::from_pcm(std::span<const float> samples, double sample_rate, unsigned channels) {
  auto p = pcm_powers("Signal::from_pcm", samples, sample_rate, channels, [](float x) { return double{x}; });
  if (!p) return p.error();
  return Signal(p.value().mean_squares, p.value().block_seconds, p.value().duration);
}

Result<Signal> Signal::from_pcm16(std::span<const std::int16_t> samples, double sample_rate, unsigned channels) {
  auto p = pcm_powers("Signal::from_pcm16", samples, sample_rate, channels,
                      [](std::int16_t x) { return static_cast<double>(x) / 32768.0; });
  if (!p) return p.error();
  return Signal(p.value().mean_squares, p.value().block_seconds, p.value().duration);
}

Result<Signal> Signal::from_pcm8(std::span<const std::uint8_t> samples, double sample_rate, unsigned channels) {
  auto p = pcm_powers("Signal::from_pcm8", samples, sample_rate, channels,
                      [](std::uint8_t x) { return (static_cast<double>(x) - 128.0) / 128.0; });
  if (!p) return p.error();
  return Signal(p.value().mean_squares, p.value().block_seconds, p.value().duration);
}

Result<Signal> Signal::from_levels(std::span<const float> levels_db, double hop_seconds) {
  if (!(hop_seconds >= kMinHop && hop_seconds <= kMaxHop))
    return invalid_argument_error("Signal::from_levels: hop_seconds must be in [0.0005, 1], got " +
                                  std::to_string(hop_seconds));
  if (levels_db.empty()) return invalid_argument_error("Signal::from_levels: no levels");
  std::vector<double> powers(levels_db.size());
  for (std::size_t k = 0; k < levels_db.size(); ++k) {
    const double level = levels_db[k];
    if (std::isnan(level) || level == std::numeric_limits<double>::infinity())
      return invalid_argument_error("Signal::from_levels: level " + std::to_string(k) +
                                    " must be a number or -infinity");
    powers[k] = std::pow(10.0, level / 10.0);  // -infinity: 0
  }
  return Signal(powers, hop_seconds, hop_seconds * static_cast<double>(levels_db.size()));
}

double Signal::mean_square(double position, double window, bool loop) const {
  const std::size_t blocks = prefix_.size() - 1;
  // In blocks, nudged by a millionth of one: a step time n * dt that
  // should fall on a block's start but rounds just below it reads that block.
  double x = position / block_seconds_ + kEdge;
  const double turn = duration_ / block_seconds_;
  if (loop) {
    x = std::fmod(x, turn);
    if (x < 0.0) x += turn;
  } else if (x < 0.0 || x >= turn) {
    return 0.0;
  }
  const std::size_t first = std::min(blocks - 1, static_cast<std::size_t>(x));
  // Capped before rounding: a window of 1e300 s must not overflow the cast.
  const double span = std::min(window / block_seconds_, 1e12);
  const std::size_t count = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(span)));
  double sum = 0.0;
  if (!loop) {
    sum = prefix_[std::min(blocks, first + count)] - prefix_[first];
  } else {
    // Whole turns of the loop, then the rest, wrapping past the end.
    const std::size_t turns = count / blocks, rest = count % blocks;
    sum = static_cast<double>(turns) * prefix_[blocks];
    const std::size_t end = first + rest;
    sum += end <= blocks ? prefix_[end] - prefix_[first] : (prefix_[blocks] - prefix_[first]) + prefix_[end - blocks];
  }
  return sum / static_cast<double>(count);
}

double Signal::level_db(double position, double window, bool loop) const {
  if (!std::isfinite(position) || !(window > 0.0)) return -std::numeric_limits<double>::infinity();
  const double power = mean_square(position, window, loop);
  if (!(power > 0.0)) return -std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(power);
}

double signal_gain(double level_db, const SignalSettings& law) {
  const double floor = law.floor_db, reference = law.reference_db;
  if (!(level_db > floor)) return 0.0;  // -infinity and NaN included
  return std::min(1.0, (level_db - floor) / (reference - floor));
}

double rms_level_db(std::span<const float> samples) {
  double sum = 0.0;
  for (float x : samples) sum += static_cast<double>(x) * static_cast<double>(x);
  if (samples.empty() || !(sum > 0.0) || !std::isfinite(sum)) return -std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(sum / static_cast<double>(samples.size()));
}

}  // namespace sp
