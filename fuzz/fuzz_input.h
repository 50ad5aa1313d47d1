// How the fuzz targets cut one fuzzer input into parts: a separator line
// between files (scene, then buffers) or between a config and the bytes
// that drive the calls. A separator in the dictionaries lets the fuzzer
// add and remove parts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace sp::fuzz {

inline constexpr std::string_view kPartSeparator = "\n--8<--\n";

inline std::vector<std::string_view> split_parts(const std::uint8_t* data, std::size_t size) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  std::vector<std::string_view> parts;
  for (;;) {
    const std::size_t at = rest.find(kPartSeparator);
    if (at == std::string_view::npos) break;
    parts.push_back(rest.substr(0, at));
    rest.remove_prefix(at + kPartSeparator.size());
  }
  parts.push_back(rest);
  return parts;
}

// Reads values off the front of a byte string; zeros once it runs out.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  bool empty() const { return bytes_.empty(); }
  template <class T>
  T take() {
    T value{};
    const std::size_t n = bytes_.size() < sizeof(T) ? bytes_.size() : sizeof(T);
    if (n == 0) return value;  // an empty view's data() may be null, which memcpy must not get
    std::memcpy(&value, bytes_.data(), n);
    bytes_.remove_prefix(n);
    return value;
  }

 private:
  std::string_view bytes_;
};

}  // namespace sp::fuzz
