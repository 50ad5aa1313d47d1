// Builds small scenes in code for tests whose expectations are derived by
// hand: axis-aligned solid boxes (closed, outward-facing) with named layers.
#pragma once

#include <cstddef>
#include <string>

#include <glm/vec3.hpp>

#include "soundpaint/scene.h"

namespace sp::test {

// The id of layer `layer` in `scene`, added if new.
inline std::uint32_t layer_id(Scene& scene, const std::string& layer) {
  std::uint32_t id = 0;
  while (id < scene.layer_names.size() && scene.layer_names[id] != layer) ++id;
  if (id == scene.layer_names.size()) scene.layer_names.push_back(layer);
  return id;
}

// Appends triangle (a, b, c): its front faces where a -> b -> c runs
// counter-clockwise.
inline void add_triangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, const std::string& layer) {
  const std::uint32_t id = layer_id(scene, layer);
  scene.vertices.insert(scene.vertices.end(), {a, b, c});
  scene.triangle_layers.push_back(id);
}

// Appends quad a b c d (counter-clockwise seen from its front) as two
// triangles sharing the diagonal a-c.
inline void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, const std::string& layer) {
  add_triangle(scene, a, b, c, layer);
  add_triangle(scene, a, c, d, layer);
}

// Faces of a box, for add_box_faces' masks.
enum BoxFace : unsigned {
  kMinusZ = 1u,
  kPlusZ = 2u,
  kMinusY = 4u,
  kPlusY = 8u,
  kMinusX = 16u,
  kPlusX = 32u,
  kAllFaces = 63u,
};

// Appends the faces of box [lo, hi] in `faces` (two triangles each, outward
// fronts); those also in `flipped` are wound inward. Leaving faces out makes
// an open mesh, as render meshes are.
inline void add_box_faces(Scene& scene, glm::vec3 lo, glm::vec3 hi, const std::string& layer, unsigned faces,
                          unsigned flipped = 0u) {
  const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  // In BoxFace order: -z, +z, -y, +y, -x, +x.
  const int corners[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (unsigned f = 0; f < 6; ++f) {
    if ((faces & (1u << f)) == 0u) continue;
    const int* q = corners[f];
    if (flipped & (1u << f)) {
      add_quad(scene, c[q[0]], c[q[3]], c[q[2]], c[q[1]], layer);
    } else {
      add_quad(scene, c[q[0]], c[q[1]], c[q[2]], c[q[3]], layer);
    }
  }
}

// Appends the 12 triangles of the closed box [lo, hi] with layer `layer`.
inline void add_box(Scene& scene, glm::vec3 lo, glm::vec3 hi, const std::string& layer) {
  add_box_faces(scene, lo, hi, layer, kAllFaces);
}

// A closed room: inner space [lo, hi], six solid slabs `thickness` thick.
inline void add_closed_room(Scene& scene, glm::vec3 lo, glm::vec3 hi, float thickness, const std::string& layer) {
  const float t = thickness;
  add_box(scene, {lo.x - t, lo.y - t, lo.z - t}, {lo.x, hi.y + t, hi.z + t}, layer);  // -x
  add_box(scene, {hi.x, lo.y - t, lo.z - t}, {hi.x + t, hi.y + t, hi.z + t}, layer);  // +x
  add_box(scene, {lo.x, lo.y - t, lo.z - t}, {hi.x, lo.y, hi.z + t}, layer);          // -y
  add_box(scene, {lo.x, hi.y, lo.z - t}, {hi.x, hi.y + t, hi.z + t}, layer);          // +y
  add_box(scene, {lo.x, lo.y, lo.z - t}, {hi.x, hi.y, lo.z}, layer);                  // -z
  add_box(scene, {lo.x, lo.y, hi.z}, {hi.x, hi.y, hi.z + t}, layer);                  // +z
}

// A source that plays always, at `position`.
inline SourceDesc source_at(glm::vec3 position, float max_distance = 100.0f) {
  SourceDesc s;
  s.position = position;
  s.max_distance = max_distance;
  s.color = {1.0f, 0.5f, 0.25f};
  return s;
}

// A 6 x 3 x 5 m concrete room with 0.3 m walls and one always-playing
// source near its centre; the listener must come from the config.
inline Scene closed_room() {
  Scene scene;
  add_closed_room(scene, {-3, 0, -2.5f}, {3, 3, 2.5f}, 0.3f, "concrete");
  scene.sources.push_back(source_at({0.5f, 1.5f, 0.2f}));
  return scene;
}

// closed_room() split at x in [0.9, 1.1] by a movable wall (moving part 0,
// "sliding wall", layer "door") spanning its whole cross-section, with the
// only source on the -x side.
inline Scene room_with_movable_wall() {
  Scene scene = closed_room();
  scene.sources = {source_at({-1.5f, 1.5f, 0.0f})};
  const std::size_t static_triangles = scene.triangle_count();
  add_box(scene, {0.9f, 0.0f, -2.5f}, {1.1f, 3.0f, 2.5f}, "door");
  scene.instance_names = {"sliding wall"};
  scene.triangle_instances.assign(scene.triangle_count(), kStaticInstance);
  for (std::size_t t = static_triangles; t < scene.triangle_count(); ++t) scene.triangle_instances[t] = 0;
  return scene;
}

}  // namespace sp::test
