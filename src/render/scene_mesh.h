// What the scene pass draws, as one list of triangles: the level's surfaces
// tinted by layer, then small markers for the sources and the listener.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <string_view>
#include <vector>

#include "soundpaint/simulation.h"
#include "sp_draw_types.h"

namespace sp::draw {

struct SceneMesh {
  std::vector<shader::SceneTriangle> triangles;  // level, then source markers, then the listener marker
  std::uint32_t level_triangles = 0;
  std::uint32_t source_marker_triangles = 0;
  std::uint32_t listener_marker_triangles = 0;  // last in `triangles`, so a draw can leave them out
};

// Marker sizes, metres: big enough to find in a 1280x720 picture of a room,
// small enough not to hide the indicators around a source.
inline constexpr float kSourceMarkerRadius = 0.15f;
inline constexpr float kListenerMarkerHeight = 0.4f;

// Linear RGB tint of a layer: a fixed colour for well-known material names
// (concrete grey, brick red-brown, wood brown, glass light blue, metal
// steel, carpet dark; matched after layer-name normalisation, then as a
// substring: "old_brick" is brick), else a muted colour from a small
// palette indexed by `layer_id`. Muted, so saturated indicators stand out.
glm::vec3 layer_tint(std::string_view layer_name, std::uint32_t layer_id);

// The triangles of `world`'s BVH (any order) tinted by layer; with
// `markers`, an octahedron in its colour at every source and a white
// pyramid standing on the listener's position.
SceneMesh build_scene_mesh(const World& world, bool markers);

}  // namespace sp::draw
