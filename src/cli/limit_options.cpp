#include "cli/limit_options.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <string>

#include "core/printable_text.h"
#include "soundpaint/simulation.h"

namespace sp::cli {

std::string scene_limit_help() {
  return "  --max-triangles N    refuse scenes with more triangles, every mesh instance\n"
         "                       counted (default " +
         std::to_string(kDefaultMaxTriangles) +
         ")\n"
         "  --allow-external-uris  let the scene's buffers come from outside its folder\n"
         "                       (trusted scenes only; see README: Security)\n";
}

std::string memory_limit_help() {
  return "  --memory-budget SIZE most memory the config's rays and indicators may need at\n"
         "                       worst, in bytes or with K, M, G (default " +
         std::to_string(kDefaultMemoryBudgetBytes >> 30) + "G)\n";
}

SceneLoadOptions scene_load_options(const ParsedArgs& parsed) {
  SceneLoadOptions options;
  options.allow_external_uris = parsed.flags.count("--allow-external-uris") != 0;
  // The library caps what it accepts (32-bit triangle ids) and says so.
  options.max_triangles = parsed.unsigned_value("--max-triangles", 1, UINT64_MAX).value_or(options.max_triangles);
  options.memory_budget_bytes = memory_budget(parsed);  // the default where a command has no --memory-budget
  return options;
}

std::uint64_t memory_budget(const ParsedArgs& parsed) {
  const std::optional<std::string> text = parsed.value("--memory-budget");
  if (!text) return kDefaultMemoryBudgetBytes;
  const auto bad = [&] {
    return Exception(ErrorCode::InvalidArgument,
                     "option --memory-budget: expected a size such as 512M, 4G or a byte count, got '" +
                         printable_text(*text) + "'");
  };
  std::uint64_t value = 0;
  const char* const end = text->data() + text->size();
  auto [at, ec] = std::from_chars(text->data(), end, value);
  if (ec != std::errc{} || at == text->data() || value == 0) throw bad();
  int shift = 0;
  if (at != end) {
    switch (std::toupper(static_cast<unsigned char>(*at))) {
      case 'K':
        shift = 10;
        break;
      case 'M':
        shift = 20;
        break;
      case 'G':
        shift = 30;
        break;
      case 'T':
        shift = 40;
        break;
      default:
        throw bad();
    }
    ++at;
    if (at != end && (*at == 'B' || *at == 'b')) ++at;  // "4GB" too
  }
  if (at != end || value > (UINT64_MAX >> shift)) throw bad();
  return value << shift;
}

std::set<std::string> with_options(std::set<std::string> base, const std::set<std::string>& more) {
  base.insert(more.begin(), more.end());
  return base;
}

}  // namespace sp::cli
