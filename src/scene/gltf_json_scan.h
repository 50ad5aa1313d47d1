// Private to the scene loader: what must be known about a glTF file's JSON
// before tinygltf parses it.
//
// tinygltf turns `extras` and `extensions` into values recursively, so a
// file nested thousands of levels deep overflows the stack of whichever
// thread loads it. The scan reads the JSON once with nlohmann's
// non-recursive SAX parser, stops at kMaxJsonDepth, and notes the buffer
// URIs, the only files a scene is allowed to make us read.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sp::scene_detail {

struct GltfJsonFacts {
  // Every string found at "buffers[i].uri", JSON escapes decoded, in file
  // order (data: URIs included).
  std::vector<std::string> buffer_uris;
};

// Throws sp::Exception(InvalidScene) for malformed JSON (with its position)
// and for nesting deeper than json_fields::kMaxJsonDepth.
GltfJsonFacts scan_gltf_json(std::string_view json);

// The JSON chunk of a binary glTF container. Throws sp::Exception
// (InvalidScene) when the header or the chunk does not fit the file.
std::string_view glb_json_chunk(std::span<const unsigned char> file);

}  // namespace sp::scene_detail
