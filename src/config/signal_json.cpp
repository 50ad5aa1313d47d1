#include "config/signal_json.h"

#include <array>
#include <string_view>

namespace sp::json_fields {
namespace {

constexpr std::array<std::string_view, 3> kSignalKeys = {"window", "floor", "reference"};
// A millisecond is one block of the envelope (soundpaint/signal.h); past a
// second the level no longer follows a sound's attack.
constexpr NumberRange kWindow{0.001, 1.0};
// dB re full scale: 16-bit audio reaches about -96 dB, float further; below
// -200 dB nothing is audible, above +40 dB nothing is sane.
constexpr NumberRange kLevel{-200.0, 40.0};

}  // namespace

void read_signal(const nlohmann::json& value, const JsonPath& at, SignalSettings& signal) {
  for (const auto& [key, field] : expect_object(value, at, kSignalKeys)) {
    const JsonPath field_at = at.key(key);
    if (key == "window") {
      signal.window = read_double(field, field_at, kWindow);
    } else if (key == "floor") {
      signal.floor_db = read_float(field, field_at, kLevel);
    } else if (key == "reference") {
      signal.reference_db = read_float(field, field_at, kLevel);
    }
  }
  if (!(signal.floor_db < signal.reference_db))
    at.key("floor").fail("must be below signal.reference (" + std::to_string(signal.reference_db) + " dB), got " +
                         std::to_string(signal.floor_db));
}

}  // namespace sp::json_fields
