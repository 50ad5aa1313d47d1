// The options that set how far soundpaint trusts its input (README
// "Security"), shared by the commands that take them (simulate, render,
// info, check, view).
#pragma once

#include <cstdint>
#include <set>
#include <string>

#include "cli/options.h"
#include "soundpaint/scene.h"

namespace sp::cli {

// --max-triangles N (value) and --allow-external-uris (flag).
inline const std::set<std::string> kSceneLimitValueOptions = {"--max-triangles"};
inline const std::set<std::string> kSceneLimitFlagOptions = {"--allow-external-uris"};
// --memory-budget SIZE (value).
inline const std::set<std::string> kMemoryLimitValueOptions = {"--memory-budget"};

// Help text lines for the options above, with their defaults.
std::string scene_limit_help();
std::string memory_limit_help();

// The scene options the parsed arguments set, defaults elsewhere.
SceneLoadOptions scene_load_options(const ParsedArgs& parsed);

// --memory-budget in bytes ("512M", "4G", "1073741824"), or the default.
// Throws sp::Exception(InvalidArgument) naming the option on bad text.
std::uint64_t memory_budget(const ParsedArgs& parsed);

// `base` with the options above added.
std::set<std::string> with_options(std::set<std::string> base, const std::set<std::string>& more);

}  // namespace sp::cli
