#include "scene/gltf_file_access.h"

#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

// URIs are shown as the file writes them, cut to keep a message one line.
constexpr std::size_t kMaxShownUriChars = 80;

std::string shown(const std::string& uri) {
  std::string text = printable(uri);
  if (text.size() > kMaxShownUriChars) {
    // Cut between characters, never inside one's UTF-8 bytes.
    std::size_t cut = kMaxShownUriChars - 3;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0u) == 0x80u) --cut;
    text = text.substr(0, cut) + "...";
  }
  return text;
}

// tinygltf checks that a file exists before reading it; answering yes for
// every name keeps it from probing elsewhere: the read decides.
bool exists(const std::string& path, void*) { return !path.empty(); }

std::string unexpanded(const std::string& path, void*) { return path; }

bool never_write(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
  if (error) *error += "soundpaint never writes glTF files";
  return false;
}

}  // namespace

GltfFileAccess::GltfFileAccess(UriRules rules, const std::vector<std::string>& buffer_uris,
                               std::uint64_t max_file_bytes)
    : rules_(std::move(rules)), max_file_bytes_(max_file_bytes) {
  for (const std::string& uri : buffer_uris) {
    Declared& entry = declared_[decode_uri_as_tinygltf(uri)];
    entry.as_written = uri;
    entry.reads_left += 1;
  }
}

tinygltf::FsCallbacks GltfFileAccess::callbacks() {
  tinygltf::FsCallbacks callbacks{};
  callbacks.FileExists = &exists;
  callbacks.ExpandFilePath = &unexpanded;
  callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* error, const std::string& path,
                               void* self) {
    std::string ignored;
    return static_cast<GltfFileAccess*>(self)->read(*out, error ? *error : ignored, path);
  };
  callbacks.WriteWholeFile = &never_write;
  callbacks.user_data = this;
  return callbacks;
}

bool GltfFileAccess::read(std::vector<unsigned char>& out, std::string& error, const std::string& decoded_uri) {
  // Buffers are parsed before images, so once every declared buffer has
  // been read, any further request is an image's: refused without a word
  // (a missing texture never fails a load).
  const auto found = declared_.find(decoded_uri);
  if (found == declared_.end() || found->second.reads_left == 0) {
    error += "not read: soundpaint reads buffers only";
    return false;
  }
  found->second.reads_left -= 1;
  try {
    out = read_scene_uri(rules_, decoded_uri, max_file_bytes_);
    return true;
  } catch (const Exception& e) {
    if (refusal_.empty()) refusal_ = "buffer URI \"" + shown(found->second.as_written) + "\": " + e.error().message;
    error += refusal_;
    return false;
  }
}

}  // namespace sp::scene_detail
