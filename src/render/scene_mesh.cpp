#include "render/scene_mesh.h"

#include <array>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "config/layer_names.h"
#include "sim/world_geometry.h"
#include "sp_types.h"

namespace sp::draw {
namespace {

struct NamedTint {
  const char* name;
  glm::vec3 tint;
};

// Linear RGB; the target is sRGB, so these read lighter than their numbers.
constexpr std::array<NamedTint, 6> kNamedTints = {{
    {"concrete", {0.28f, 0.28f, 0.27f}},
    {"brick", {0.42f, 0.13f, 0.08f}},
    {"wood", {0.36f, 0.20f, 0.08f}},
    {"glass", {0.45f, 0.66f, 0.80f}},
    {"metal", {0.40f, 0.44f, 0.50f}},
    {"carpet", {0.08f, 0.07f, 0.10f}},
}};

// For layers with names we do not know: distinct, but all greyish.
constexpr std::array<glm::vec3, 6> kPalette = {{
    {0.38f, 0.36f, 0.30f},
    {0.28f, 0.34f, 0.38f},
    {0.36f, 0.30f, 0.36f},
    {0.30f, 0.36f, 0.30f},
    {0.40f, 0.34f, 0.28f},
    {0.30f, 0.30f, 0.40f},
}};

void add_triangle(std::vector<shader::SceneTriangle>& out, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 color,
                  std::uint32_t shading, std::uint32_t layer) {
  shader::SceneTriangle t{};
  t.v0 = a;
  t.v1 = b;
  t.v2 = c;
  t.color = color;
  t.shading = shading;
  t.layer = layer;
  out.push_back(t);
}

// Eight faces around `centre`, counter-clockwise seen from outside.
void add_octahedron(std::vector<shader::SceneTriangle>& out, glm::vec3 centre, float radius, glm::vec3 color) {
  const glm::vec3 axes[3] = {{radius, 0, 0}, {0, radius, 0}, {0, 0, radius}};
  for (float sx : {-1.0f, 1.0f}) {
    for (float sy : {-1.0f, 1.0f}) {
      for (float sz : {-1.0f, 1.0f}) {
        glm::vec3 a = centre + sx * axes[0], b = centre + sy * axes[1], c = centre + sz * axes[2];
        // An odd number of negative axes flips the winding.
        if (sx * sy * sz < 0.0f) std::swap(b, c);
        add_triangle(out, a, b, c, color, SP_SHADE_MARKER, SP_MARKER_LAYER);
      }
    }
  }
}

// A square-based pyramid pointing up, its apex at `apex`.
void add_pyramid(std::vector<shader::SceneTriangle>& out, glm::vec3 apex, float height, glm::vec3 color) {
  const float half = 0.35f * height;
  const glm::vec3 base = apex - glm::vec3(0, height, 0);
  const glm::vec3 c[4] = {base + glm::vec3(-half, 0, -half), base + glm::vec3(half, 0, -half),
                          base + glm::vec3(half, 0, half), base + glm::vec3(-half, 0, half)};
  for (int k = 0; k < 4; ++k) add_triangle(out, c[(k + 1) % 4], c[k], apex, color, SP_SHADE_MARKER, SP_MARKER_LAYER);
  add_triangle(out, c[0], c[1], c[2], color, SP_SHADE_MARKER, SP_MARKER_LAYER);
  add_triangle(out, c[0], c[2], c[3], color, SP_SHADE_MARKER, SP_MARKER_LAYER);
}

}  // namespace

glm::vec3 layer_tint(std::string_view layer_name, std::uint32_t layer_id) {
  const std::string normalised = layer_names::normalise(layer_name);
  for (const NamedTint& named : kNamedTints)
    if (normalised == named.name) return named.tint;
  for (const NamedTint& named : kNamedTints)
    if (normalised.find(named.name) != std::string::npos) return named.tint;
  return kPalette[layer_id % kPalette.size()];
}

SceneMesh build_scene_mesh(const World& world, bool markers) {
  SceneMesh mesh;
  std::vector<glm::vec3> tints(world.layer_names.size());
  for (std::size_t l = 0; l < tints.size(); ++l)
    tints[l] = layer_tint(world.layer_names[l], static_cast<std::uint32_t>(l));
  mesh.triangles.reserve(world.geometry->bvh.triangles.size() + (markers ? world.sources.size() * 8 + 6 : 0));
  for (const BvhTriangle& t : world.geometry->bvh.triangles) {
    const glm::vec3 tint = t.layer < tints.size() ? tints[t.layer] : kPalette[0];
    add_triangle(mesh.triangles, t.v0, t.v1, t.v2, tint, SP_SHADE_LIT, t.layer);
  }
  mesh.level_triangles = static_cast<std::uint32_t>(mesh.triangles.size());
  if (!markers) return mesh;
  for (std::size_t id = 0; id < world.sources.size(); ++id)
    add_octahedron(mesh.triangles, world.sources[id].position, kSourceMarkerRadius, world.source_colors[id]);
  mesh.source_marker_triangles = static_cast<std::uint32_t>(mesh.triangles.size()) - mesh.level_triangles;
  add_pyramid(mesh.triangles, world.listener, kListenerMarkerHeight, glm::vec3(1.0f));
  mesh.listener_marker_triangles =
      static_cast<std::uint32_t>(mesh.triangles.size()) - mesh.level_triangles - mesh.source_marker_triangles;
  return mesh;
}

}  // namespace sp::draw
