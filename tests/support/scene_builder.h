// Builds small scenes in code for tests whose expectations are derived by
// hand: axis-aligned solid boxes (closed, outward-facing) with named layers.
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "soundpaint/scene.h"

namespace sp::test {

// Appends the 12 triangles of the box [lo, hi] with layer `layer`.
inline void add_box(Scene& scene, glm::vec3 lo, glm::vec3 hi, const std::string& layer) {
  std::uint32_t layer_id = 0;
  while (layer_id < scene.layer_names.size() && scene.layer_names[layer_id] != layer) ++layer_id;
  if (layer_id == scene.layer_names.size()) scene.layer_names.push_back(layer);
  const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    for (int tri : {0, 1}) {
      scene.vertices.push_back(c[f[0]]);
      scene.vertices.push_back(c[f[1 + tri]]);
      scene.vertices.push_back(c[f[2 + tri]]);
      scene.triangle_layers.push_back(layer_id);
    }
  }
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

}  // namespace sp::test
