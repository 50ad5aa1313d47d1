// Output names for `render --frames K`: a printf-style pattern with exactly
// one integer conversion, formatted here without handing user text to printf.
#pragma once

#include <cstdint>
#include <string>

namespace sp::cli {

class FramePattern {
 public:
  // Accepts exactly one "%d" or "%0Nd" (N: 1 or 2 digits, the zero-padded
  // width); "%%" is a literal '%'. Anything else -- no conversion, two, or
  // another one ("%s", "%5d") -- throws sp::Exception(InvalidArgument)
  // naming `option`.
  static FramePattern parse(const std::string& pattern, const std::string& option);

  // The name of frame `index`: "frame%04d.png" -> "frame0007.png".
  std::string format(std::uint64_t index) const;

 private:
  std::string prefix_;
  std::string suffix_;
  std::size_t width_ = 0;  // minimum digits, zero-padded
};

}  // namespace sp::cli
