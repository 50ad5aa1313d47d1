#include "core/printable_text.h"

#include <cstdint>

namespace sp {
namespace {

// The length of the well-formed UTF-8 sequence at the start of `text` and
// its code point, or length 0 when the first byte starts none. The ranges
// are those of the Unicode Standard's table 3-7 ("Well-Formed UTF-8 Byte
// Sequences"), which leave out overlong forms, surrogates and code points
// above U+10FFFF.
struct Decoded {
  std::size_t length = 0;
  char32_t code_point = 0;
};

Decoded decode_utf8(std::string_view text) {
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(text[i]); };
  const std::uint8_t lead = byte(0);
  if (lead < 0x80) return {1, lead};
  std::size_t length = 0;
  std::uint8_t second_lo = 0x80, second_hi = 0xbf;  // the second byte's range depends on the lead
  if (lead >= 0xc2 && lead <= 0xdf) {
    length = 2;
  } else if (lead >= 0xe0 && lead <= 0xef) {
    length = 3;
    if (lead == 0xe0) second_lo = 0xa0;  // no overlong forms
    if (lead == 0xed) second_hi = 0x9f;  // no surrogates
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    length = 4;
    if (lead == 0xf0) second_lo = 0x90;  // no overlong forms
    if (lead == 0xf4) second_hi = 0x8f;  // nothing above U+10FFFF
  } else {
    return {};  // a continuation byte, or a lead byte no well-formed sequence has
  }
  if (text.size() < length) return {};
  if (byte(1) < second_lo || byte(1) > second_hi) return {};
  char32_t code_point = lead & (0x7f >> length);
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(i) & 0xc0) != 0x80) return {};
    code_point = (code_point << 6) | (byte(i) & 0x3f);
  }
  return {length, code_point};
}

// Code points that steer a terminal or a line's layout instead of printing.
bool is_control(char32_t c) {
  if (c < 0x20 || (c >= 0x7f && c <= 0x9f)) return true;  // C0, DEL, C1
  if (c == 0x2028 || c == 0x2029) return true;            // line and paragraph separators
  // Bidi_Control: marks, embeddings, overrides and isolates.
  return c == 0x061c || c == 0x200e || c == 0x200f || (c >= 0x202a && c <= 0x202e) || (c >= 0x2066 && c <= 0x2069);
}

void append_hex(std::string& out, std::uint32_t value, int min_digits) {
  static constexpr char kDigits[] = "0123456789abcdef";
  int digits = 1;
  while (digits < 8 && (value >> (4 * digits)) != 0) ++digits;
  if (digits < min_digits) digits = min_digits;
  for (int d = digits - 1; d >= 0; --d) out.push_back(kDigits[(value >> (4 * d)) & 0xf]);
}

}  // namespace

std::string printable_text(std::string_view text, TextQuoting quoting) {
  std::string out;
  out.reserve(text.size());
  while (!text.empty()) {
    const Decoded decoded = decode_utf8(text);
    if (decoded.length == 0) {
      out += "\\x";
      append_hex(out, static_cast<std::uint8_t>(text.front()), 2);
      text.remove_prefix(1);
      continue;
    }
    if (is_control(decoded.code_point)) {
      out += "\\u{";
      append_hex(out, decoded.code_point, 1);
      out += '}';
    } else if (quoting == TextQuoting::DoubleQuoted && (text.front() == '\\' || text.front() == '"')) {
      out += '\\';
      out += text.front();
    } else {
      out.append(text.substr(0, decoded.length));
    }
    text.remove_prefix(decoded.length);
  }
  return out;
}

}  // namespace sp
