// A 16-bit PCM WAV file, as sox and espeak-ng write them: enough to hand its
// samples to alBufferData. Not a general WAV reader.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

struct WavFile {
  std::vector<std::int16_t> samples;  // interleaved
  int channels = 1;
  int rate = 0;
};

// Throws std::runtime_error naming the file and what is wrong with it.
WavFile read_wav16(const std::filesystem::path& path);
