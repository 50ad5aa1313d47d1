// Minimal command-line parsing for the soundpaint subcommands: --name VALUE
// options, --flags and positionals, with errors that name the option.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace sp::cli {

struct ParsedArgs {
  std::vector<std::string> positionals;
  std::map<std::string, std::string> values;  // "--steps" -> "100"
  std::set<std::string> flags;                // "--help"

  std::optional<std::string> value(const std::string& name) const;
  // Parses an unsigned integer option in [min, max]; throws on bad text.
  std::optional<std::uint64_t> unsigned_value(const std::string& name, std::uint64_t min, std::uint64_t max) const;
};

// `value_options` take one argument; `flag_options` take none. Throws
// sp::Exception(InvalidArgument) on unknown options or missing values.
ParsedArgs parse_args(const std::vector<std::string>& args, const std::set<std::string>& value_options,
                      const std::set<std::string>& flag_options);

// --help: prints the command's help, then each of `sections` (the help of
// the option groups it takes), and returns true; the command then exits 0.
bool printed_help(const ParsedArgs& parsed, std::initializer_list<std::string_view> sections);

// The one SCENE argument; throws naming `command` when there are none or several.
const std::string& scene_argument(const ParsedArgs& parsed, const char* command);

// "x,y,z": three finite numbers (--camera-pos, --look-at); throws naming `option`.
glm::vec3 parse_vec3(const std::string& option, const std::string& text);
// Degrees in (0, 180) (--fov); throws naming the option.
float parse_fov(const std::string& text);

}  // namespace sp::cli
