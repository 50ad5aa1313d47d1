// Private to the scene loader: a glTF node's local transform.
#pragma once

#include <tiny_gltf.h>

#include <glm/mat4x4.hpp>
#include <string>

namespace sp::scene_detail {

// The node's `matrix` when it has one, else T * R * S from `translation`,
// `rotation` (quaternion x, y, z, w; normalised here) and `scale`. Double
// precision, so that deep hierarchies lose nothing before the final cast of
// vertices to float. Throws sp::Exception naming `node_label` when a property
// has the wrong length, a non-finite value, or a zero quaternion.
glm::dmat4 local_transform(const tinygltf::Node& node, const std::string& node_label);

}  // namespace sp::scene_detail
