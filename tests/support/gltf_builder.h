// Builds small glTF files in code, so that every input sits next to the
// expectation derived from it by hand: JSON with the buffer embedded as a
// data URI, JSON with the buffer in a file of its own, or binary glTF.
#pragma once

#include <cstdint>
#include <cstring>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sp::test {

using nlohmann::json;

constexpr int kU8 = 5121, kU16 = 5123, kU32 = 5125, kFloat = 5126;

inline std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i];
    const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u;
    const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
    const std::uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

// A glTF document under construction: one buffer, views appended 4-aligned.
class GltfBuilder {
 public:
  json doc = {{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", json::array()}}}},
              {"nodes", json::array()},
              {"meshes", json::array()},
              {"accessors", json::array()},
              {"bufferViews", json::array()}};
  std::vector<std::uint8_t> bin;

  int view(const void* data, std::size_t size) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    const std::size_t offset = bin.size();
    bin.resize(offset + size);
    std::memcpy(bin.data() + offset, data, size);
    return append("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
  }
  int accessor(int view_index, int component_type, std::size_t count, const char* type) {
    return append("accessors",
                  {{"bufferView", view_index}, {"componentType", component_type}, {"count", count}, {"type", type}});
  }
  int positions(const std::vector<glm::vec3>& p) {
    return accessor(view(p.data(), p.size() * sizeof(glm::vec3)), kFloat, p.size(), "VEC3");
  }
  template <class T>
  int indices(const std::vector<T>& values, int component_type) {
    return accessor(view(values.data(), values.size() * sizeof(T)), component_type, values.size(), "SCALAR");
  }
  int mesh(json primitives) { return append("meshes", {{"primitives", std::move(primitives)}}); }
  // A one-primitive mesh of the triangle (1,0,0), (0,1,0), (0,0,1).
  int unit_triangle_mesh(json extra = json::object()) {
    json primitive = {{"attributes", {{"POSITION", positions({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}})}}}};
    primitive.update(extra);
    return mesh(json::array({primitive}));
  }
  // A one-primitive mesh of the 12 outward-facing triangles of the unit
  // cube [0, 1]^3, indexed with 32-bit indices; the first triangle is
  // (0,0,0), (0,1,0), (1,1,0). `unused_vertices` more vertices (at the
  // centre) pad its POSITION accessor without being used.
  int unit_box_mesh(std::size_t unused_vertices = 0) {
    std::vector<glm::vec3> corners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                      {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    corners.resize(corners.size() + unused_vertices, glm::vec3(0.5f));
    const std::vector<std::uint32_t> faces = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                              2, 3, 7, 2, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    return mesh(json::array({{{"attributes", {{"POSITION", positions(corners)}}}, {"indices", indices(faces, kU32)}}}));
  }
  int node(json n) { return append("nodes", std::move(n)); }
  void root(int node_index) { doc["scenes"][0]["nodes"].push_back(node_index); }

  // JSON text with the buffer embedded as a base64 data URI.
  std::string gltf() const {
    json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    return d.dump(1);
  }
  // JSON text whose buffer is the file `uri` names (write `bin` there).
  std::string gltf_with_buffer_uri(const std::string& uri) const {
    json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}, {"uri", uri}}};
    return d.dump(1);
  }
  // Binary glTF: header, JSON chunk (space-padded), BIN chunk (zero-padded).
  std::vector<std::uint8_t> glb() const {
    json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}}};
    std::string text = d.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<std::uint8_t> body = bin;
    while (body.size() % 4 != 0) body.push_back(0);
    std::vector<std::uint8_t> out;
    auto u32 = [&out](std::uint32_t v) {
      for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    };
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + body.size()));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    for (const char c : text) out.push_back(static_cast<std::uint8_t>(c));
    u32(static_cast<std::uint32_t>(body.size()));
    u32(0x004E4942u);  // "BIN\0"
    for (const std::uint8_t byte : body) out.push_back(byte);
    return out;
  }

 private:
  int append(const char* array, json value) {
    doc[array].push_back(std::move(value));
    return static_cast<int>(doc[array].size()) - 1;
  }
};

// The unit box (GltfBuilder::unit_box_mesh) placed by `instances` nodes,
// instance i translated by (3 i, 0, 0): a level of many identical props.
inline GltfBuilder instanced_unit_boxes(int instances, std::size_t unused_vertices = 0) {
  GltfBuilder b;
  const int mesh = b.unit_box_mesh(unused_vertices);
  for (int i = 0; i < instances; ++i) b.root(b.node({{"mesh", mesh}, {"translation", {3.0 * i, 0, 0}}}));
  return b;
}

}  // namespace sp::test
