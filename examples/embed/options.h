// The example's command line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

inline constexpr const char* kUsage =
    "usage: soundpaint_embed_example [SCENE] OUT.png [--frames N] [--backend cpu|gpu|auto] [--width W] "
    "[--height H] [--validation]";

struct Options {
  std::filesystem::path scene = SP_DEFAULT_SCENE;
  std::filesystem::path output;
  std::uint32_t frames = 60;  // 0: the bare scene, no simulation drawn
  std::string backend = "auto";
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  bool validation = false;  // also SOUNDPAINT_VALIDATION=1
  bool help = false;
};

// A command line that is not understood; main prints it with the usage line.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Options parse_options(int argc, char** argv);
