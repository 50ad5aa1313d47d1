// Private to the scene loader: a glTF mesh decoded once into checked local
// triangles, however many nodes instance it.
//
// Decoding reads and checks every accessor; placing an instance then costs
// only its triangles. So a level of thousands of props loads in time
// proportional to its triangles, and a mesh whose primitives index a few
// corners of a huge vertex array is not read again per instance.
#pragma once

#include <tiny_gltf.h>

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace sp::scene_detail {

struct DecodedPrimitive {
  int mode = TINYGLTF_MODE_TRIANGLES;  // TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN
  std::vector<glm::vec3> positions;    // local space, not yet checked finite
  std::vector<std::uint32_t> indices;  // each < positions.size(); empty when not indexed
  bool indexed = false;
  std::size_t triangles = 0;
  std::string material_layer;  // the material's name, or "default"

  // The position indices of triangle t's corners, per the glTF 2.0 spec's
  // definitions of strips and fans (section 3.7.2.1).
  std::array<std::uint32_t, 3> corners(std::size_t t) const;
};

struct DecodedMesh {
  std::vector<DecodedPrimitive> primitives;  // those with triangles only
  std::size_t triangles = 0;                 // over every primitive
};

// Decodes mesh `mesh_index` (which must exist). Points and lines, and
// primitives without POSITION, have no surface and are left out. Throws
// sp::Exception naming the mesh, primitive and problem (unknown mode, a
// corner count that is not a multiple of 3, an index out of range, a
// material that does not exist, any accessor problem).
DecodedMesh decode_mesh(const tinygltf::Model& model, int mesh_index);

}  // namespace sp::scene_detail
