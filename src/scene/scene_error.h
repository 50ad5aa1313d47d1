// Private to the scene loader: how its parts report a malformed file.
//
// Every part throws sp::Exception with a message that does not name the file;
// load_scene() catches it at the API boundary and prefixes the path, so that
// helpers need not carry the path around and every message names it once.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <string_view>

#include "core/printable_text.h"
#include "soundpaint/result.h"

namespace sp::scene_detail {

[[noreturn]] inline void fail(std::string message) { throw Exception(ErrorCode::InvalidScene, std::move(message)); }

// Names come from the file and are shown between double quotes: escaped
// as every name is (core/printable_text.h), so that an error stays one line
// and a level cannot drive the terminal through it.
inline std::string printable(std::string_view text) { return printable_text(text, TextQuoting::DoubleQuoted); }

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
