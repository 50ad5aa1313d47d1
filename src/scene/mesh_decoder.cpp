#include "scene/mesh_decoder.h"

#include "scene/accessor_reader.h"
#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

constexpr int kModeTriangles = TINYGLTF_MODE_TRIANGLES;
constexpr int kModeStrip = TINYGLTF_MODE_TRIANGLE_STRIP;
constexpr int kModeFan = TINYGLTF_MODE_TRIANGLE_FAN;
constexpr const char* kDefaultLayer = "default";

std::string mesh_label(int mesh, std::size_t primitive) {
  return "mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
}

std::string material_layer(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                           const std::string& where) {
  if (primitive.material == -1) return kDefaultLayer;
  if (primitive.material < 0 || static_cast<std::size_t>(primitive.material) >= model.materials.size()) {
    fail(where + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
  }
  const std::string& name = model.materials[static_cast<std::size_t>(primitive.material)].name;
  return name.empty() ? kDefaultLayer : name;
}

// Fills `out` and returns true when the primitive has a surface to hit.
bool decode_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& where,
                      DecodedPrimitive& out) {
  const int mode = primitive.mode == -1 ? kModeTriangles : primitive.mode;
  if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) return false;  // no surface to hit
  if (mode != kModeTriangles && mode != kModeStrip && mode != kModeFan) {
    fail(where + ": unknown primitive mode " + std::to_string(mode));
  }
  const auto position = primitive.attributes.find("POSITION");
  // glTF: a primitive without positions is not rendered; it has no surface.
  if (position == primitive.attributes.end()) return false;

  out.mode = mode;
  out.positions = read_positions(model, position->second);
  out.indexed = primitive.indices != -1;
  if (out.indexed) {
    out.indices = read_indices(model, primitive.indices);
    for (std::size_t i = 0; i < out.indices.size(); ++i) {
      if (out.indices[i] >= out.positions.size()) {
        fail(where + ": index " + std::to_string(out.indices[i]) + " (element " + std::to_string(i) +
             ") is out of range for " + std::to_string(out.positions.size()) + " vertices");
      }
    }
  }
  const std::size_t corners = out.indexed ? out.indices.size() : out.positions.size();
  if (mode == kModeTriangles) {
    if (corners % 3 != 0) fail(where + ": " + std::to_string(corners) + " corners is not a multiple of 3");
    out.triangles = corners / 3;
  } else {
    out.triangles = corners >= 3 ? corners - 2 : 0;
  }
  if (out.triangles == 0) return false;
  out.material_layer = material_layer(model, primitive, where);
  return true;
}

}  // namespace

std::array<std::uint32_t, 3> DecodedPrimitive::corners(std::size_t t) const {
  std::array<std::size_t, 3> c;
  if (mode == kModeStrip) {
    c = {t, t + 1 + t % 2, t + 2 - t % 2};
  } else if (mode == kModeFan) {
    c = {t + 1, t + 2, 0};
  } else {
    c = {3 * t, 3 * t + 1, 3 * t + 2};
  }
  if (!indexed)
    return {static_cast<std::uint32_t>(c[0]), static_cast<std::uint32_t>(c[1]), static_cast<std::uint32_t>(c[2])};
  return {indices[c[0]], indices[c[1]], indices[c[2]]};
}

DecodedMesh decode_mesh(const tinygltf::Model& model, int mesh_index) {
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
  DecodedMesh decoded;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    DecodedPrimitive primitive;
    if (!decode_primitive(model, mesh.primitives[p], mesh_label(mesh_index, p), primitive)) continue;
    decoded.triangles += primitive.triangles;
    decoded.primitives.push_back(std::move(primitive));
  }
  return decoded;
}

}  // namespace sp::scene_detail
