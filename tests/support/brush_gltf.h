// Writes a scene of brushes (12 triangles each, as add_box makes them) as
// glTF, the two ways level editors export them: each brush its own mesh,
// placed by a node of its own, or the whole level merged into one mesh.
// Loading either must give the same solids (docs/model.md#the-rules: they
// come from the triangles' shared edges, not from meshes, nodes or layers).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "soundpaint/scene.h"
#include "support/gltf_builder.h"

namespace sp::test {

inline constexpr std::size_t kBrushVertices = 36;

inline glm::vec3 brush_vertex(const Scene& scene, std::size_t k) {
  return {scene.vertices[k].x, scene.vertices[k].y, scene.vertices[k].z};
}

// One node per brush, its translation the brush's first corner and its mesh
// the corners relative to it; extras.acoustic_layer keeps the brush's layer.
inline GltfBuilder gltf_node_per_brush(const Scene& scene) {
  GltfBuilder b;
  for (std::size_t first = 0; first + kBrushVertices <= scene.vertices.size(); first += kBrushVertices) {
    const glm::vec3 origin = brush_vertex(scene, first);
    std::vector<glm::vec3> corners;
    for (std::size_t k = first; k < first + kBrushVertices; ++k) corners.push_back(brush_vertex(scene, k) - origin);
    const int mesh = b.mesh(json::array({{{"attributes", {{"POSITION", b.positions(corners)}}}}}));
    const std::string& layer = scene.layer_names[scene.triangle_layers[first / 3]];
    b.root(b.node(
        {{"mesh", mesh}, {"translation", {origin.x, origin.y, origin.z}}, {"extras", {{"acoustic_layer", layer}}}}));
  }
  return b;
}

// One node, one mesh, one primitive: every brush's triangles in scene order,
// all on one layer.
inline GltfBuilder gltf_merged(const Scene& scene) {
  GltfBuilder b;
  std::vector<glm::vec3> corners;
  for (std::size_t k = 0; k < scene.vertices.size(); ++k) corners.push_back(brush_vertex(scene, k));
  const int mesh = b.mesh(json::array({{{"attributes", {{"POSITION", b.positions(corners)}}}}}));
  b.root(b.node({{"mesh", mesh}}));
  return b;
}

}  // namespace sp::test
