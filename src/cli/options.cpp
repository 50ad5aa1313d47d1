#include "cli/options.h"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstdlib>

#include <glm/glm.hpp>

#include "soundpaint/result.h"

namespace sp::cli {

std::optional<std::string> ParsedArgs::value(const std::string& name) const {
  auto it = values.find(name);
  if (it == values.end()) return std::nullopt;
  return it->second;
}

std::optional<std::uint64_t> ParsedArgs::unsigned_value(const std::string& name, std::uint64_t min,
                                                        std::uint64_t max) const {
  auto text = value(name);
  if (!text) return std::nullopt;
  std::uint64_t parsed = 0;
  auto [end, ec] = std::from_chars(text->data(), text->data() + text->size(), parsed);
  if (text->empty() || ec != std::errc{} || end != text->data() + text->size() || parsed < min || parsed > max)
    throw Exception(ErrorCode::InvalidArgument, "option " + name + ": expected an integer in [" + std::to_string(min) +
                                                    ", " + std::to_string(max) + "], got '" + *text + "'");
  return parsed;
}

ParsedArgs parse_args(const std::vector<std::string>& args, const std::set<std::string>& value_options,
                      const std::set<std::string>& flag_options) {
  ParsedArgs parsed;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg.size() < 2 || arg.rfind("--", 0) != 0) {
      if (arg.size() > 1 && arg[0] == '-' && arg != "-h")
        throw Exception(ErrorCode::InvalidArgument, "unknown option " + arg);
      if (arg == "-h") {
        parsed.flags.insert("--help");
      } else {
        parsed.positionals.push_back(arg);
      }
      continue;
    }
    std::string name = arg;
    std::optional<std::string> inline_value;
    if (auto eq = arg.find('='); eq != std::string::npos) {
      name = arg.substr(0, eq);
      inline_value = arg.substr(eq + 1);
    }
    if (flag_options.count(name)) {
      if (inline_value) throw Exception(ErrorCode::InvalidArgument, "option " + name + " takes no value");
      parsed.flags.insert(name);
    } else if (value_options.count(name)) {
      if (!inline_value) {
        // "--steps --stats x" is a forgotten value, not a value "--stats".
        if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)
          throw Exception(ErrorCode::InvalidArgument, "option " + name + " needs a value");
        inline_value = args[++i];
      }
      if (parsed.values.count(name)) throw Exception(ErrorCode::InvalidArgument, "option " + name + " given twice");
      parsed.values[name] = *inline_value;
    } else {
      throw Exception(ErrorCode::InvalidArgument, "unknown option " + name);
    }
  }
  return parsed;
}

glm::vec3 parse_vec3(const std::string& option, const std::string& text) {
  glm::vec3 v(0.0f);
  const char* cursor = text.c_str();
  for (int k = 0; k < 3; ++k) {
    char* end = nullptr;
    const float value = std::strtof(cursor, &end);
    const char expected = k < 2 ? ',' : '\0';
    if (end == cursor || *end != expected || !std::isfinite(value))
      throw Exception(ErrorCode::InvalidArgument,
                      "option " + option + ": expected three finite numbers x,y,z, got '" + text + "'");
    v[k] = value;
    cursor = end + 1;
  }
  return v;
}

float parse_fov(const std::string& text) {
  char* end = nullptr;
  const float value = std::strtof(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(value > 0.0f && value < 180.0f))
    throw Exception(ErrorCode::InvalidArgument, "option --fov: expected degrees in (0, 180), got '" + text + "'");
  return value;
}


bool printed_help(const ParsedArgs& parsed, std::initializer_list<std::string_view> sections) {
  if (parsed.flags.count("--help") == 0) return false;
  for (std::string_view section : sections) std::fwrite(section.data(), 1, section.size(), stdout);
  return true;
}

const std::string& scene_argument(const ParsedArgs& parsed, const char* command) {
  if (parsed.positionals.size() != 1)
    throw Exception(ErrorCode::InvalidArgument,
                    std::string(command) + " needs exactly one SCENE argument (see --help)");
  return parsed.positionals[0];
}

}  // namespace sp::cli
