// Private to the scene loader: how its parts report a malformed file.
//
// Every part throws sp::Exception with a message that does not name the file;
// load_scene() catches it at the API boundary and prefixes the path, so that
// helpers need not carry the path around and every message names it once.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <string_view>

#include "soundpaint/result.h"

namespace sp::scene_detail {

[[noreturn]] inline void fail(std::string message) { throw Exception(ErrorCode::InvalidScene, std::move(message)); }

// Names come from the file; control characters would break the promise that
// an error is one line.
inline std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return out;
}

// `node 3 "Lamp"`, or `node 3` for an unnamed node: names in glTF are
// optional and not unique, so the index is what locates the node.
inline std::string node_label(const tinygltf::Model& model, int index) {
  std::string label = "node " + std::to_string(index);
  if (index >= 0 && static_cast<std::size_t>(index) < model.nodes.size()) {
    const std::string& name = model.nodes[static_cast<std::size_t>(index)].name;
    if (!name.empty()) label += " \"" + printable(name) + "\"";
  }
  return label;
}

}  // namespace sp::scene_detail
