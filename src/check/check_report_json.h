// The report of `soundpaint check --json`.
#pragma once

#include <string>

#include "soundpaint/check.h"

namespace sp {

// {"triangles", "findings": [{"code", "count", "message", "layers": [{"name",
// "count"}]}], "probe": {...}}, indented, ending in a new line. Always valid
// UTF-8 JSON: a layer name is written byte for byte when it is valid UTF-8
// (control characters JSON-escaped, as JSON requires, and so read back
// exactly); a name that is not keeps its valid parts, and each ill-formed
// part (a stray byte, a cut or overlong sequence) becomes U+FFFD. Names read
// from glTF and config files are always valid UTF-8 (their JSON parsers
// reject anything else); only a Scene built in code can hold other bytes.
std::string check_report_json(const CheckReport& report);

}  // namespace sp
