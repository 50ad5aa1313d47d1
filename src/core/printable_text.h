// Names are data: text that comes from a scene, a config or a file name
// (layers, categories, sources, nodes, paths, JSON keys), made safe to print
// on a terminal, inside one line of a message (README "Security").
//
// A level can name a material "\e]0;title\a\e[2J" or put a line feed and a
// forged "soundpaint: no findings" in it; printed raw, that sets the
// terminal's title, clears the screen or forges a line of output. Every
// message and every line of output that embeds such text passes it through
// printable_text() first, once, here: one implementation, one set of rules.
//
// The rules:
//   * Well-formed UTF-8 that prints stays as it is, byte for byte ("Beton",
//     "Holz.001", "木材", emoji).
//   * Code points that control rather than print are written as their code
//     point, `\u{` lower-case hex `}`, as Rust and ECMAScript write them:
//     C0 controls U+0000-U+001F (TAB, LF, CR, ESC ...: "\u{1b}"), DEL U+007F,
//     C1 controls U+0080-U+009F (CSI "\u{9b}"), the line and paragraph
//     separators U+2028 and U+2029 (new lines to some viewers), and the bidi
//     controls U+061C, U+200E, U+200F, U+202A-U+202E, U+2066-U+2069, which
//     reorder what a line shows ("Trojan Source").
//   * A byte that is not part of well-formed UTF-8 (a stray continuation
//     byte, a truncated or overlong sequence, a surrogate, anything above
//     U+10FFFF) is written as that byte, `\x` and two lower-case hex digits
//     ("\xff"): `\x` is a byte, `\u{}` a code point.
//   * TextQuoting::DoubleQuoted, for text shown between double quotes (JSON
//     key paths in config errors), also writes `\` as `\\` and `"` as `\"`,
//     so that the quoted text reads back exactly.
//   * TextQuoting::Bare leaves `\` and `"` alone: Windows paths stay
//     readable, and escaping text a second time changes nothing, so a caller
//     may pass a whole message through again to be sure. The price is that a
//     name spelling "\u{1b}" out in letters prints as one holding ESC would:
//     the escaped text is for people; tools read the exact names from JSON
//     (`soundpaint check --json`).
#pragma once

#include <string>
#include <string_view>

namespace sp {

enum class TextQuoting {
  Bare,          // controls and invalid bytes escaped; `\` and `"` as they are
  DoubleQuoted,  // also `\` -> `\\` and `"` -> `\"`, for text between double quotes
};

// `text` with every control code point and every byte of invalid UTF-8
// escaped (rules above): the result holds no control character, no invalid
// UTF-8, and no line break. Thread-safe, no allocation beyond the result.
std::string printable_text(std::string_view text, TextQuoting quoting = TextQuoting::Bare);

}  // namespace sp
