// Private to the scene loader: the only way tinygltf reaches the file system.
//
// tinygltf's own callbacks open whatever a URI names, and look for it in the
// current directory too. These serve exactly the external buffers the
// document declares, each once, from files read_scene_uri() allows;
// images are never read (soundpaint needs geometry only), and nothing is
// ever written.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "scene/uri_confinement.h"

namespace sp::scene_detail {

class GltfFileAccess {
 public:
  // `buffer_uris`: the URIs of the document's buffers as written
  // (GltfJsonFacts); `max_file_bytes`: the largest buffer file read.
  // rules.scene_folder must stay open while this object is used.
  GltfFileAccess(UriRules rules, const std::vector<std::string>& buffer_uris, std::uint64_t max_file_bytes);
  GltfFileAccess(const GltfFileAccess&) = delete;
  GltfFileAccess& operator=(const GltfFileAccess&) = delete;

  // Callbacks bound to this object, which must outlive the load. Give the
  // loader an empty base directory: tinygltf then asks for the decoded URI
  // itself, and never for a second place to look.
  tinygltf::FsCallbacks callbacks();

  // The first buffer that could not be read, as a one-line message naming
  // its URI as written; empty when none failed.
  const std::string& refusal() const { return refusal_; }

 private:
  struct Declared {
    std::string as_written;
    int reads_left = 0;
  };

  bool read(std::vector<unsigned char>& out, std::string& error, const std::string& decoded_uri);

  UriRules rules_;
  std::uint64_t max_file_bytes_;
  std::map<std::string, Declared> declared_;  // by decoded URI
  std::string refusal_;
};

}  // namespace sp::scene_detail
