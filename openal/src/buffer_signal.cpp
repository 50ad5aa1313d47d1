#include "buffer_signal.h"

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace sp::openal {
namespace {

// AL_EXT_float32's formats (AL/alext.h), named here so that the adapter
// reads them wherever the extension exists without needing its header.
constexpr ALenum kMonoFloat32 = 0x10010;
constexpr ALenum kStereoFloat32 = 0x10011;

Error invalid(std::string message) { return Error{ErrorCode::InvalidArgument, std::move(message), 0}; }

std::string hex(ALenum value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%X", static_cast<unsigned>(value));
  return text;
}

}  // namespace

Result<Signal> buffer_signal(ALenum format, const ALvoid* data, ALsizei size, ALsizei frequency) {
  unsigned channels = 0, bytes = 0;
  switch (format) {
    case AL_FORMAT_MONO8:
      channels = 1, bytes = 1;
      break;
    case AL_FORMAT_STEREO8:
      channels = 2, bytes = 1;
      break;
    case AL_FORMAT_MONO16:
      channels = 1, bytes = 2;
      break;
    case AL_FORMAT_STEREO16:
      channels = 2, bytes = 2;
      break;
    case kMonoFloat32:
      channels = 1, bytes = 4;
      break;
    case kStereoFloat32:
      channels = 2, bytes = 4;
      break;
    default:
      return invalid("format " + hex(format) +
                     " is not one soundpaint reads (AL_FORMAT_MONO8/16, STEREO8/16, MONO/STEREO_FLOAT32)");
  }
  if (data == nullptr) return invalid("data is NULL");
  if (size <= 0 || static_cast<unsigned>(size) % (channels * bytes) != 0)
    return invalid("size " + std::to_string(size) + " is not a whole number of " + std::to_string(channels * bytes) +
                   "-byte frames");
  const auto count = static_cast<std::size_t>(size) / bytes;
  if (bytes == 1) return Signal::from_pcm8({static_cast<const std::uint8_t*>(data), count}, frequency, channels);
  // alBufferData takes samples in host order, but not necessarily aligned.
  if (bytes == 2) {
    std::vector<std::int16_t> samples(count);
    std::memcpy(samples.data(), data, count * 2);
    return Signal::from_pcm16(samples, frequency, channels);
  }
  std::vector<float> samples(count);
  std::memcpy(samples.data(), data, count * 4);
  return Signal::from_pcm(samples, frequency, channels);
}

}  // namespace sp::openal
