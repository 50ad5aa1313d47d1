// CategoryRules: parse the rule file and match names against it. Matching is
// the classic two-pointer wildcard walk, linear in the name for each star
// it backtracks to, so a hostile rule cannot make it exponential.
#include "soundpaint/category_rules.h"

#include <array>
#include <cctype>

#include <nlohmann/json.hpp>

#include "config/json_fields.h"
#include "core/regular_file.h"

namespace sp {
namespace jf = json_fields;

namespace {

constexpr std::array<std::string_view, 3> kTopKeys = {"version", "rules", "default"};
constexpr std::array<std::string_view, 4> kRuleKeys = {"match", "category", "priority", "ignore"};
constexpr std::size_t kMaxRules = 4096;  // a game's sound folders, with room to spare
constexpr std::uint64_t kMaxRulesFileBytes = 4u << 20;

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

CategoryRules read_rules(const nlohmann::json& root, std::string_view origin) {
  const jf::JsonPath top(origin);
  CategoryRules out;
  bool versioned = false;
  for (const auto& [key, value] : jf::expect_object(root, top, kTopKeys)) {
    const jf::JsonPath at = top.key(key);
    if (key == "version") {
      if (jf::read_uint32(value, at) != 1) at.fail("must be 1 (the only version of the rule file)", value);
      versioned = true;
    } else if (key == "default") {
      if (!value.is_null()) out.fallback = jf::read_string(value, at);
    } else if (key == "rules") {
      if (!value.is_array()) at.fail("must be an array of rules", value);
      if (value.size() > kMaxRules) at.fail("must hold at most 4096 rules");
      for (std::size_t i = 0; i < value.size(); ++i) {
        const jf::JsonPath rule_at = at.index(i);
        CategoryRule rule;
        bool has_match = false, has_category = false;
        for (const auto& [rkey, field] : jf::expect_object(value[i], rule_at, kRuleKeys)) {
          const jf::JsonPath field_at = rule_at.key(rkey);
          if (rkey == "match") {
            rule.match = jf::read_string(field, field_at);
            has_match = true;
          } else if (rkey == "category") {
            rule.category = jf::read_string(field, field_at);
            has_category = true;
          } else if (rkey == "priority") {
            rule.priority = static_cast<int>(jf::read_double(field, field_at, {-1e6, 1e6}));
          } else if (rkey == "ignore") {
            rule.ignore = jf::read_bool(field, field_at);
          }
        }
        if (!has_match) rule_at.fail("needs \"match\"");
        if (!has_category && !rule.ignore) rule_at.fail("needs \"category\" or \"ignore\": true");
        out.rules.push_back(std::move(rule));
      }
    }
  }
  if (!versioned) top.fail("needs \"version\": 1");
  return out;
}

}  // namespace

bool wildcard_match(std::string_view pattern, std::string_view name) {
  std::size_t p = 0, n = 0, star = std::string_view::npos, resume = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || lower(pattern[p]) == lower(name[n]))) {
      ++p;
      ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = n;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      n = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::optional<std::string> CategoryRules::category_of(std::string_view name) const {
  const CategoryRule* best = nullptr;
  for (const CategoryRule& rule : rules)
    if ((best == nullptr || rule.priority > best->priority) && wildcard_match(rule.match, name)) best = &rule;
  if (best == nullptr) return fallback;
  if (best->ignore) return std::nullopt;
  return best->category;
}

Result<CategoryRules> CategoryRules::parse(std::string_view json_text, std::string_view origin) {
  return capture_errors(
      [&] {
        nlohmann::json root;
        try {
          root = nlohmann::json::parse(json_text);
        } catch (const nlohmann::json::parse_error& e) {
          throw Exception(ErrorCode::InvalidConfig, std::string(origin) + ": not valid JSON: " + e.what());
        }
        return read_rules(root, origin);
      },
      ErrorCode::InvalidConfig);
}

Result<CategoryRules> CategoryRules::load(const std::filesystem::path& path) {
  const std::string origin = path.string();
  std::vector<unsigned char> bytes;
  try {
    bytes = read_regular_file(path, kMaxRulesFileBytes, ErrorCode::Io);
  } catch (const Exception& e) {
    return Error{e.error().code, origin + ": " + e.error().message, 0};
  }
  return parse(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), origin);
}

}  // namespace sp
