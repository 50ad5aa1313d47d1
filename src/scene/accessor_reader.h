// Private to the scene loader: bounds-checked reading of glTF accessors.
//
// tinygltf parses accessors and buffer views but does not check that they
// fit their buffers, so every byte range is checked here before it is read.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace sp::scene_detail {

// Vertex positions of accessor `index`, which must be a dense (not sparse)
// VEC3 of FLOAT lying inside its buffer view and buffer. Values are not
// checked for finiteness: the caller checks the vertices it uses, after
// transforming them. Throws sp::Exception naming the accessor.
std::vector<glm::vec3> read_positions(const tinygltf::Model& model, int index);

// Index values of accessor `index`, a dense SCALAR of UNSIGNED_BYTE, _SHORT
// or _INT, widened to 32 bits. Values are not range-checked here.
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index);

}  // namespace sp::scene_detail
