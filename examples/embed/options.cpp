#include "options.h"

#include <charconv>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace {

std::uint32_t parse_count(std::string_view option, std::string_view text, std::uint32_t min, std::uint32_t max) {
  std::uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < min || value > max)
    throw UsageError(std::string(option) + " needs an integer in " + std::to_string(min) + ".." + std::to_string(max) +
                     ", not '" + std::string(text) + "'");
  return value;
}

}  // namespace

Options parse_options(int argc, char** argv) {
  Options options;
  std::vector<std::string_view> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw UsageError(std::string(arg) + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if (arg == "--frames") {
      options.frames = parse_count(arg, value(), 0, 1000000);
    } else if (arg == "--width") {
      options.width = parse_count(arg, value(), 1, 16384);
    } else if (arg == "--height") {
      options.height = parse_count(arg, value(), 1, 16384);
    } else if (arg == "--backend") {
      options.backend = value();
      if (options.backend != "cpu" && options.backend != "gpu" && options.backend != "auto")
        throw UsageError("--backend must be cpu, gpu or auto, not '" + options.backend + "'");
    } else if (arg == "--validation") {
      options.validation = true;
    } else if (arg.starts_with("-") && arg != "-") {
      throw UsageError("unknown option '" + std::string(arg) + "'");
    } else {
      positional.push_back(arg);
    }
  }
  if (options.help) return options;
  if (positional.empty()) throw UsageError("the output path OUT.png is missing");
  if (positional.size() > 2) throw UsageError("too many arguments: '" + std::string(positional[2]) + "'");
  if (positional.size() == 2) options.scene = positional[0];
  options.output = positional.back();
  const char* env = std::getenv("SOUNDPAINT_VALIDATION");
  if (env != nullptr && std::string_view(env) == "1") options.validation = true;
  return options;
}
