#include "cli/frame_pattern.h"

#include <cctype>

#include "soundpaint/result.h"

namespace sp::cli {

FramePattern FramePattern::parse(const std::string& pattern, const std::string& option) {
  auto fail = [&](const std::string& why) -> FramePattern {
    throw Exception(ErrorCode::InvalidArgument, "option " + option + ": '" + pattern + "' " + why +
                                                    " (with --frames it needs exactly one %d or %0Nd, e.g. "
                                                    "frame%04d.png)");
  };
  FramePattern result;
  bool found = false;
  std::string* out = &result.prefix_;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      *out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      *out += '%';
      ++i;
      continue;
    }
    // A conversion: '%', optional '0' + 1-2 digits, then 'd'.
    std::size_t j = i + 1;
    std::size_t width = 0;
    if (j < pattern.size() && pattern[j] == '0') {
      ++j;
      const std::size_t digits_start = j;
      while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && j - digits_start < 2)
        width = width * 10 + static_cast<std::size_t>(pattern[j++] - '0');
      if (j == digits_start) return fail("has a conversion without a width after %0");
    }
    if (j >= pattern.size() || pattern[j] != 'd') return fail("has a conversion other than %d or %0Nd");
    if (found) return fail("has more than one conversion");
    found = true;
    result.width_ = width;
    out = &result.suffix_;
    i = j;
  }
  if (!found) return fail("has no %d conversion");
  return result;
}

std::string FramePattern::format(std::uint64_t index) const {
  std::string digits = std::to_string(index);
  if (digits.size() < width_) digits.insert(0, width_ - digits.size(), '0');
  return prefix_ + digits + suffix_;
}

}  // namespace sp::cli
