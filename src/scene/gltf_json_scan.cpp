#include "scene/gltf_json_scan.h"

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "config/json_fields.h"
#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

using nlohmann::json;

// Follows where the parser is: one frame per open container, so that the
// strings at "buffers[i].uri" can be told apart from every other string.
class ScanHandler final : public nlohmann::json_sax<json> {
 public:
  GltfJsonFacts facts;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool string(string_t& value) override {
    if (at_buffer_uri()) facts.buffer_uris.push_back(value);
    return true;
  }
  bool key(string_t& name) override {
    frames_.back().key = name;
    return true;
  }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& error) override {
    // what() is "[json.exception.parse_error.101] parse error at line 1, ...";
    // the bracketed id means nothing to a user.
    std::string detail = error.what();
    const std::size_t close = detail.find("] ");
    if (!detail.empty() && detail.front() == '[' && close != std::string::npos) detail.erase(0, close + 2);
    fail(printable_text(detail));
  }

 private:
  struct Frame {
    bool is_object;
    std::string key;  // objects: the key of the value being read
  };

  bool open(bool is_object) {
    if (frames_.size() + 1 > static_cast<std::size_t>(json_fields::kMaxJsonDepth)) {
      fail("JSON nested deeper than " + std::to_string(json_fields::kMaxJsonDepth) + " levels");
    }
    frames_.push_back(Frame{is_object, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
  // Root object -> "buffers" -> array -> object -> "uri".
  bool at_buffer_uri() const {
    return frames_.size() == 3 && frames_[0].is_object && frames_[0].key == "buffers" && !frames_[1].is_object &&
           frames_[2].is_object && frames_[2].key == "uri";
  }

  std::vector<Frame> frames_;
};

std::uint32_t read_u32(std::span<const unsigned char> bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof value);  // little-endian, as the GLB container
  return value;
}

}  // namespace

GltfJsonFacts scan_gltf_json(std::string_view text) {
  ScanHandler handler;
  json::sax_parse(text.begin(), text.end(), &handler);
  return std::move(handler.facts);
}

std::string_view glb_json_chunk(std::span<const unsigned char> file) {
  // Header: magic, version, total length; then the first chunk: length, type.
  constexpr std::size_t kHeaderBytes = 20;
  constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"
  if (file.size() < kHeaderBytes) fail("shorter than the 20-byte binary glTF header");
  const std::uint32_t total = read_u32(file, 8);
  const std::uint32_t chunk = read_u32(file, 12);
  if (total > file.size())
    fail("the header says " + std::to_string(total) + " bytes, the file has " + std::to_string(file.size()));
  if (read_u32(file, 16) != kJsonChunk) fail("the first chunk is not JSON");
  if (total < kHeaderBytes || chunk > total - kHeaderBytes) fail("the JSON chunk reaches beyond the file");
  return std::string_view(reinterpret_cast<const char*>(file.data()) + kHeaderBytes, chunk);
}

}  // namespace sp::scene_detail
