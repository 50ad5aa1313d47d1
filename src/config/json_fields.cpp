#include "config/json_fields.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/printable_text.h"
#include "soundpaint/result.h"

namespace sp::json_fields {
namespace {

using nlohmann::json;

// Long values are cut in messages so that an error stays one readable line.
constexpr std::size_t kMaxShownValueChars = 40;

[[noreturn]] void throw_config_error(std::string_view origin, std::string_view message) {
  std::string line;
  line.reserve(origin.size() + 2 + message.size());
  line.append(origin).append(": ").append(message);
  throw Exception(ErrorCode::InvalidConfig, std::move(line));
}

// Key names come from the file; they are shown between double quotes, so
// the quotes and backslashes inside are escaped too (core/printable_text.h).
std::string escape_for_message(std::string_view text) { return printable_text(text, TextQuoting::DoubleQuoted); }

// Appends `value` in compact JSON to `out`, stopping once `out` is longer
// than `limit`: a huge value costs no more than its first few elements, and
// as every level writes at least one character first, the recursion is at
// most `limit` deep whatever the value's nesting.
void append_bounded(const json& value, std::string& out, std::size_t limit) {
  if (out.size() > limit) return;
  const auto dump = [](const json& scalar) {
    return scalar.dump(-1, ' ', /*ensure_ascii=*/true, json::error_handler_t::replace);
  };
  if (value.is_object()) {
    out += '{';
    for (const auto& [key, element] : value.get_ref<const json::object_t&>()) {
      if (out.size() > limit) return;
      if (out.back() != '{') out += ',';
      out += dump(json(key.substr(0, limit))) + ':';
      append_bounded(element, out, limit);
    }
    out += '}';
  } else if (value.is_array()) {
    out += '[';
    for (const json& element : value.get_ref<const json::array_t&>()) {
      if (out.size() > limit) return;
      if (out.back() != '[') out += ',';
      append_bounded(element, out, limit);
    }
    out += ']';
  } else if (value.is_string()) {
    out += dump(json(value.get_ref<const std::string&>().substr(0, limit)));
  } else {
    out += dump(value);
  }
}

std::string show_value(const json& value) {
  // nlohmann writes non-finite floats as "null", which would mislead.
  if (value.is_number_float()) {
    const double d = value.get<double>();
    if (std::isnan(d)) return "nan";
    if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
  }
  std::string text;
  append_bounded(value, text, kMaxShownValueChars);
  if (text.size() > kMaxShownValueChars) {
    text.resize(kMaxShownValueChars - 3);
    text += "...";
  }
  return text;
}

std::string format_bound(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

// Levenshtein distance, for "did you mean" hints on misspelt keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Tracks the key path while nlohmann parses, so that a repeated key can be
// reported with its location. Depends only on the order of parser events:
// containers and scalars start elements; keys name the next element.
class DuplicateKeyChecker {
 public:
  explicit DuplicateKeyChecker(std::string_view origin) : origin_(origin) {}

  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        begin_element();
        check_depth();
        frames_.push_back(Frame{true, {}, {}, 0});
        break;
      case json::parse_event_t::array_start:
        begin_element();
        check_depth();
        frames_.push_back(Frame{false, {}, {}, 0});
        break;
      case json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.seen.insert(frame.key).second) {
          throw_config_error(origin_, "duplicate key \"" + escape_for_message(current_path()) + "\"");
        }
        break;
      }
      case json::parse_event_t::value:
        begin_element();
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        break;
    }
    return true;
  }

  // The path of the value the parser is about to report, for errors raised
  // before the parser hands it over (number overflow): in an array, that is
  // the next element.
  std::string pending_path() const { return path_to(1); }

 private:
  struct Frame {
    bool is_object;
    std::set<std::string> seen;  // objects: keys so far
    std::string key;             // objects: key of the element being parsed
    std::size_t count;           // arrays: elements begun so far
  };

  void begin_element() {
    if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().count;
  }

  // Called as a container opens: stops the parse at the first level too
  // deep, before the rest of a hostile file is even read.
  void check_depth() const {
    if (frames_.size() + 1 > static_cast<std::size_t>(kMaxJsonDepth)) {
      std::string path = current_path();
      if (path.size() > kMaxShownValueChars) path = path.substr(0, kMaxShownValueChars - 3) + "...";
      const std::string where = path.empty() ? std::string() : " at \"" + escape_for_message(path) + "\"";
      throw_config_error(origin_, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels" + where);
    }
  }

  // The path of the value being parsed (the last key's, or the array
  // element begun last).
  std::string current_path() const { return path_to(0); }

  // Every array but the innermost has begun the element that holds the rest
  // of the path, so its count is >= 1; only the innermost takes the offset.
  std::string path_to(std::size_t array_offset) const {
    std::string path;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& frame = frames_[i];
      if (frame.is_object) {
        if (!path.empty()) path += '.';
        path += frame.key;
      } else {
        const std::size_t offset = i + 1 == frames_.size() ? array_offset : 0;
        path += '[' + std::to_string(frame.count + offset - 1) + ']';
      }
    }
    return path;
  }

  std::string_view origin_;
  std::vector<Frame> frames_;
};

}  // namespace

JsonPath JsonPath::key(std::string_view name) const {
  std::string child = path_;
  if (!child.empty()) child += '.';
  child.append(name);
  return JsonPath(origin_, std::move(child));
}

JsonPath JsonPath::index(std::size_t i) const { return JsonPath(origin_, path_ + '[' + std::to_string(i) + ']'); }

void JsonPath::fail(std::string_view what) const {
  if (path_.empty()) throw_config_error(origin_, what);
  std::string message = "key \"" + escape_for_message(path_) + "\": ";
  message.append(what);
  throw_config_error(origin_, message);
}

void JsonPath::fail(std::string_view what, const json& got) const {
  std::string message(what);
  message += ", got " + show_value(got);
  fail(message);
}

std::string NumberRange::describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return std::string("in ") + (min_open ? "(" : "[") + format_bound(min) + ", " + format_bound(max) +
           (max_open ? ")" : "]");
  }
  if (has_min) return std::string(min_open ? "> " : ">= ") + format_bound(min);
  if (has_max) return std::string(max_open ? "< " : "<= ") + format_bound(max);
  return {};
}

json parse_strict(std::string_view text, std::string_view origin) {
  DuplicateKeyChecker checker(origin);
  try {
    return json::parse(text.begin(), text.end(), [&checker](int depth, json::parse_event_t event, json& parsed) {
      return checker(depth, event, parsed);
    });
  } catch (const json::exception& e) {
    if (e.id == 406) {
      // A literal beyond double range such as 1e999 ("number overflow parsing
      // '1e999'"): report it like any other non-finite value, by key.
      const std::string detail = e.what();
      const std::size_t open = detail.find('\'');
      const std::size_t close = detail.rfind('\'');
      std::string literal = open < close ? detail.substr(open + 1, close - open - 1) : "a huge number";
      if (literal.size() > kMaxShownValueChars) literal = literal.substr(0, kMaxShownValueChars - 3) + "...";
      JsonPath(origin, checker.pending_path())
          .fail("must be a finite number, got " + literal + " (overflows a double)");
    }
    // what() is "[json.exception.parse_error.101] parse error at line 1, ...";
    // the bracketed id means nothing to a user.
    std::string detail = e.what();
    if (!detail.empty() && detail.front() == '[') {
      const std::size_t close = detail.find("] ");
      if (close != std::string::npos) detail.erase(0, close + 2);
    }
    std::replace(detail.begin(), detail.end(), '\n', ' ');
    throw_config_error(origin, "malformed JSON: " + printable_text(detail));
  }
}

void fail_unknown_key(const JsonPath& object_at, std::string_view key, std::span<const std::string_view> known) {
  std::string message = "unknown key \"" + escape_for_message(object_at.key(key).path()) + "\"";
  // Suggest a known key only when it is plausibly a typo of this one.
  std::string_view best;
  std::size_t best_distance = 3;
  for (const std::string_view candidate : known) {
    const std::size_t distance = edit_distance(key, candidate);
    if (distance < best_distance && distance < key.size()) {
      best = candidate;
      best_distance = distance;
    }
  }
  if (!best.empty()) message += " (did you mean \"" + std::string(best) + "\"?)";
  throw_config_error(object_at.origin(), message);
}

const json::object_t& expect_any_object(const json& value, const JsonPath& at) {
  if (!value.is_object()) {
    at.fail(at.path().empty() ? "the top level must be a JSON object" : "must be an object", value);
  }
  return value.get_ref<const json::object_t&>();
}

const json::object_t& expect_object(const json& value, const JsonPath& at, std::span<const std::string_view> known) {
  const auto& object = expect_any_object(value, at);
  for (const auto& [name, ignored] : object) {
    if (std::find(known.begin(), known.end(), name) == known.end()) fail_unknown_key(at, name, known);
  }
  return object;
}

namespace {

bool in_range(double d, const NumberRange& range) {
  const bool above_min = range.min_open ? d > range.min : d >= range.min;
  const bool below_max = range.max_open ? d < range.max : d <= range.max;
  return above_min && below_max;
}

// "must be a number >= 0" (or "must be a finite number >= 0").
std::string expectation(const NumberRange& range, bool finite) {
  std::string text = finite ? "must be a finite number" : "must be a number";
  const std::string described = range.describe();
  if (!described.empty()) text += " " + described;
  return text;
}

// The value as a double if it is a finite JSON number; the range only words
// the message.
double finite_number(const json& value, const JsonPath& at, const NumberRange& range) {
  // is_number() is false for booleans, so `true` is rejected here.
  if (!value.is_number()) at.fail(expectation(range, false), value);
  const double d = value.get<double>();
  // The parser turns an overflowing literal such as 1e999 into infinity.
  if (!std::isfinite(d)) at.fail(expectation(range, true), value);
  return d;
}

}  // namespace

double read_double(const json& value, const JsonPath& at, NumberRange range) {
  const double d = finite_number(value, at, range);
  if (!in_range(d, range)) at.fail(expectation(range, false), value);
  return d;
}

float read_float(const json& value, const JsonPath& at, NumberRange range) {
  const double d = finite_number(value, at, range);
  if (std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max())) {
    at.fail(expectation(range, false) + " within 32-bit float range", value);
  }
  // Check what is stored: 1e-50 becomes 0 as a float and is not "> 0".
  const auto f = static_cast<float>(d);
  if (!in_range(static_cast<double>(f), range)) at.fail(expectation(range, false), value);
  return f;
}

std::uint32_t read_uint32(const json& value, const JsonPath& at, std::uint32_t min, std::uint32_t max) {
  const std::string expected = "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  // 5.0 and 5e0 are floats to nlohmann: counts must be written as integers.
  if (value.is_number_unsigned()) {
    const auto u = value.get<std::uint64_t>();
    if (u < min || u > max) at.fail(expected, value);
    return static_cast<std::uint32_t>(u);
  }
  if (value.is_number_integer()) {
    const auto i = value.get<std::int64_t>();
    if (i < static_cast<std::int64_t>(min) || i > static_cast<std::int64_t>(max)) at.fail(expected, value);
    return static_cast<std::uint32_t>(i);
  }
  at.fail(expected, value);
}

std::string read_string(const json& value, const JsonPath& at) {
  if (!value.is_string()) at.fail("must be a string", value);
  return value.get<std::string>();
}

glm::vec3 read_vec3(const json& value, const JsonPath& at, NumberRange range) {
  if (!value.is_array() || value.size() != 3) at.fail("must be an array of 3 numbers", value);
  glm::vec3 v{};
  for (std::size_t i = 0; i < 3; ++i) {
    v[static_cast<glm::vec3::length_type>(i)] = read_float(value[i], at.index(i), range);
  }
  return v;
}

bool read_bool(const nlohmann::json& value, const JsonPath& at) {
  if (!value.is_boolean()) at.fail("must be true or false", value);
  return value.get<bool>();
}

}  // namespace sp::json_fields
