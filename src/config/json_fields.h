// Strict, typed reading of JSON values with one-line error messages that name
// the origin and the key path, e.g.
//   config.json: key "layers.wood.attenuation": must be a number >= 0, got -1
//
// Private to soundpaint. The configuration parser uses it, and so may the scene
// loader for glTF `extras` (same messages, same rules). Every reader throws
// sp::Exception(ErrorCode::InvalidConfig) on failure; public entry points turn
// that into a Result with capture_errors().
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace sp::json_fields {

// Where a JSON value sits: the text's origin (usually a file path) and the
// dotted key path inside it ("" for the top level, "sources[2].interval").
class JsonPath {
 public:
  explicit JsonPath(std::string_view origin, std::string path = {}) : origin_(origin), path_(std::move(path)) {}

  JsonPath key(std::string_view name) const;  // "a" -> "a.name"
  JsonPath index(std::size_t i) const;        // "a" -> "a[i]"

  std::string_view origin() const { return origin_; }
  const std::string& path() const { return path_; }

  // Throws InvalidConfig: `origin: key "path": <what>` (or `origin: <what>`
  // at the top level). Control characters in the path are escaped so the
  // message stays on one line.
  [[noreturn]] void fail(std::string_view what) const;
  // As fail(), appending ", got <value>" with the value shortened.
  [[noreturn]] void fail(std::string_view what, const nlohmann::json& got) const;

 private:
  std::string_view origin_;  // not owned; outlives every JsonPath made from it
  std::string path_;
};

// An interval of accepted numbers; open ends exclude the bound itself.
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  std::string describe() const;  // ">= 0", "> 0", "in [0, 1]", "" for any
};
inline constexpr NumberRange kAnyNumber{};
inline constexpr NumberRange kNonNegative{0.0};
inline constexpr NumberRange kPositive{0.0, std::numeric_limits<double>::infinity(), true, false};
inline constexpr NumberRange kUnitInterval{0.0, 1.0};

// The deepest nesting of arrays and objects accepted in JSON from outside
// (configs, glTF files; the top-level value is level 1). Real files nest
// fewer than 10 levels. Code that recurses over a value (tinygltf's parser,
// which 20,000 levels of `extras` crashed) then needs at most about 50 KB of
// stack (measured), so a host thread with a small stack survives hostile
// input too.
inline constexpr int kMaxJsonDepth = 128;

// Parses JSON text strictly: malformed text, nesting deeper than
// kMaxJsonDepth, and a key repeated within one object (which nlohmann would
// silently resolve to the last value), are errors naming `origin` and the
// position or key.
nlohmann::json parse_strict(std::string_view text, std::string_view origin);

// `value` must be an object whose keys are all in `known`; otherwise throws
// naming the first unknown key (and a likely intended one, if close).
const nlohmann::json::object_t& expect_object(const nlohmann::json& value, const JsonPath& at,
                                              std::span<const std::string_view> known);
inline const nlohmann::json::object_t& expect_object(const nlohmann::json& value, const JsonPath& at,
                                                     std::initializer_list<std::string_view> known) {
  return expect_object(value, at, std::span<const std::string_view>(known.begin(), known.size()));
}
// `value` must be an object; its keys are free-form (e.g. layer names).
const nlohmann::json::object_t& expect_any_object(const nlohmann::json& value, const JsonPath& at);

// Throws `origin: unknown key "<object_at>.<key>"`, suggesting the closest of
// `known` when it is plausibly a typo.
[[noreturn]] void fail_unknown_key(const JsonPath& object_at, std::string_view key,
                                   std::span<const std::string_view> known);

// A finite JSON number (booleans are not numbers) inside `range`.
double read_double(const nlohmann::json& value, const JsonPath& at, NumberRange range = kAnyNumber);
// As read_double(), and representable as a finite float; the range is checked
// on the float actually stored (so 1e-50 is not "> 0").
float read_float(const nlohmann::json& value, const JsonPath& at, NumberRange range = kAnyNumber);
// A JSON integer literal (5, not 5.0 or 5e0) in [min, max].
std::uint32_t read_uint32(const nlohmann::json& value, const JsonPath& at, std::uint32_t min = 0,
                          std::uint32_t max = std::numeric_limits<std::uint32_t>::max());
std::string read_string(const nlohmann::json& value, const JsonPath& at);
bool read_bool(const nlohmann::json& value, const JsonPath& at);
// An array of exactly three floats, each inside `range`.
glm::vec3 read_vec3(const nlohmann::json& value, const JsonPath& at, NumberRange range = kAnyNumber);

}  // namespace sp::json_fields
