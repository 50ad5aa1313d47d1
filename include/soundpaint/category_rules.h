// Categories from asset names: a data-driven rule file that maps the name a
// game gives a sound ("sound/player/footsteps/boot1.wav") to the category the
// display draws (README.md "Sound-event traces"). Used by the OpenAL adapter
// and by `soundpaint simulate|render --events`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "soundpaint/result.h"
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

struct CategoryRule {
  std::string match;     // wildcard pattern: `*` any run of characters ('/' too), `?` one; case-insensitive
  std::string category;  // what a matching name becomes (empty when `ignore`)
  int priority = 0;      // the highest priority among matching rules wins; ties: the earlier rule
  bool ignore = false;   // a matching name is not painted at all
};

// The rule file (JSON, version 1):
//   { "version": 1,
//     "rules": [ { "match": "sound/weapons/*", "category": "gunfire", "priority": 10 },
//                { "match": "sound/misc/menu*", "ignore": true } ],
//     "default": "sound" }
// "default" (optional) is the category of a name no rule matches; absent or
// null, such a name is ignored. Errors (InvalidConfig) name the file and key.
class CategoryRules {
 public:
  static Result<CategoryRules> parse(std::string_view json_text, std::string_view origin = "rules");
  static Result<CategoryRules> load(const std::filesystem::path& path);

  // The category of `name`, or nothing when it is ignored.
  std::optional<std::string> category_of(std::string_view name) const;

  std::vector<CategoryRule> rules;
  std::optional<std::string> fallback;  // the file's "default"
};

// `*` matches any run of characters, `?` any one; ASCII case is ignored.
bool wildcard_match(std::string_view pattern, std::string_view name);

}  // namespace sp

SP_CPP_API_END
