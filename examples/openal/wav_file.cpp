#include "wav_file.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace {

std::uint32_t u32(const std::vector<char>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}
std::uint16_t u16(const std::vector<char>& b, std::size_t at) {
  std::uint16_t v = 0;
  std::memcpy(&v, b.data() + at, 2);
  return v;
}

}  // namespace

WavFile read_wav16(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& what) { throw std::runtime_error(path.string() + ": " + what); };
  if (b.size() < 12 || std::memcmp(b.data(), "RIFF", 4) != 0 || std::memcmp(b.data() + 8, "WAVE", 4) != 0)
    fail("not a RIFF/WAVE file");
  WavFile wav;
  bool format_seen = false;
  for (std::size_t at = 12; at + 8 <= b.size();) {
    const std::uint32_t size = u32(b, at + 4);
    if (at + 8 + size > b.size()) fail("a chunk runs past the end");
    if (std::memcmp(b.data() + at, "fmt ", 4) == 0) {
      if (u16(b, at + 8) != 1 || u16(b, at + 22) != 16) fail("not 16-bit PCM");
      wav.channels = u16(b, at + 10);
      wav.rate = static_cast<int>(u32(b, at + 12));
      format_seen = true;
    } else if (std::memcmp(b.data() + at, "data", 4) == 0) {
      if (!format_seen) fail("data before fmt");
      wav.samples.resize(size / 2);
      std::memcpy(wav.samples.data(), b.data() + at + 8, wav.samples.size() * 2);
      return wav;
    }
    at += 8 + size + (size & 1);
  }
  fail("no data chunk");
  return wav;
}
