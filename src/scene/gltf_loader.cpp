// sp::load_scene: flattens the default scene of a glTF 2.0 file into one
// world-space triangle list with a layer per triangle, and collects its sound
// sources and first camera (SPEC section 3).
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <limits>
#include <new>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "scene/accessor_reader.h"
#include "scene/gltf_document.h"
#include "scene/node_transform.h"
#include "scene/scene_error.h"
#include "scene/scene_sources.h"
#include "soundpaint/scene.h"

namespace sp {
namespace scene_detail {
namespace {

constexpr int kModeTriangles = TINYGLTF_MODE_TRIANGLES;
constexpr int kModeStrip = TINYGLTF_MODE_TRIANGLE_STRIP;
constexpr int kModeFan = TINYGLTF_MODE_TRIANGLE_FAN;
constexpr const char* kDefaultLayer = "default";
// Triangle ids downstream (BVH, GPU buffers) are 32-bit.
constexpr std::size_t kMaxTriangles = std::numeric_limits<std::uint32_t>::max() / 3;

std::string mesh_label(int mesh, std::size_t primitive) {
  return "mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
}

// The corner indices of triangle t of a primitive, per the glTF 2.0 spec's
// definitions of strips and fans (section 3.7.2.1).
std::array<std::size_t, 3> triangle_corners(int mode, std::size_t t) {
  if (mode == kModeStrip) return {t, t + 1 + t % 2, t + 2 - t % 2};
  if (mode == kModeFan) return {t + 1, t + 2, 0};
  return {3 * t, 3 * t + 1, 3 * t + 2};
}

// Rotation and translation of a node's world matrix. A camera's scale would
// distort the view, and glTF says camera nodes should not be scaled anyway.
glm::mat4 without_scale(const glm::dmat4& world) {
  glm::dmat4 m = world;
  for (int axis = 0; axis < 3; ++axis) {
    const double length = glm::length(glm::dvec3(m[axis]));
    if (length > 0.0) m[axis] /= length;
  }
  return glm::mat4(m);
}

class SceneAssembler {
 public:
  SceneAssembler(const tinygltf::Model& model, Scene& scene)
      : model_(model), scene_(scene), emitters_(read_audio_emitters(model)) {}

  void run() {
    visit(root_nodes(), roots_owner());
    if (scene_.triangle_layers.empty()) fail("no triangles (the scene has no triangle meshes)");
  }

 private:
  std::string roots_owner() const {
    if (model_.scenes.empty()) return "the node list";
    return "scene " + std::to_string(model_.defaultScene >= 0 ? model_.defaultScene : 0);
  }

  std::vector<int> root_nodes() const {
    const auto& scenes = model_.scenes;
    if (!scenes.empty()) {
      if (model_.defaultScene < -1 || model_.defaultScene >= static_cast<int>(scenes.size())) {
        fail("default scene " + std::to_string(model_.defaultScene) + " does not exist");
      }
      const int chosen = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      return scenes[static_cast<std::size_t>(chosen)].nodes;
    }
    // No scenes: every node that is nobody's child, in index order.
    std::vector<bool> is_child(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes) {
      for (const int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < is_child.size()) {
          is_child[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < is_child.size(); ++i) {
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }

  // Depth-first, pre-order, children in listed order: the order that numbers
  // the sources (SPEC 3). An explicit stack, so that a deep chain of nodes
  // cannot overflow the call stack; a node reached twice (a cycle, or a
  // child shared by two parents, both invalid glTF) is an error.
  void visit(const std::vector<int>& roots, const std::string& roots_owner) {
    struct Pending {
      int node;
      int parent;
      glm::dmat4 parent_world;
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, glm::dmat4(1.0)});
    std::vector<bool> reached(model_.nodes.size(), false);
    while (!stack.empty()) {
      const Pending pending = stack.back();
      stack.pop_back();
      if (pending.node < 0 || static_cast<std::size_t>(pending.node) >= model_.nodes.size()) {
        const std::string owner = pending.parent < 0 ? roots_owner : node_label(model_, pending.parent);
        fail(owner + " lists node " + std::to_string(pending.node) + ", which does not exist");
      }
      const auto index = static_cast<std::size_t>(pending.node);
      if (reached[index]) {
        fail(node_label(model_, pending.node) + " is reached twice (a cycle or a shared child)");
      }
      reached[index] = true;
      const glm::dmat4 world = pending.parent_world * local_transform(model_.nodes[index], label(pending.node));
      add_node(pending.node, world);
      const std::vector<int>& children = model_.nodes[index].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, pending.node, world});
    }
  }

  std::string label(int node) const { return node_label(model_, node); }

  void add_node(int node_index, const glm::dmat4& world) {
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(node_index)];
    NodeAcoustics acoustics = read_node_acoustics(model_, node_index, emitters_);
    if (!acoustics.sources.empty()) {
      const glm::vec3 position(world[3]);
      if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
        fail(label(node_index) + ": sound source position is not finite");
      }
      for (SourceDesc& source : acoustics.sources) {
        source.position = position;
        scene_.sources.push_back(std::move(source));
      }
    }
    if (node.camera >= 0 || node.camera < -1) add_camera(node_index, node.camera, world);
    if (node.mesh >= 0 || node.mesh < -1) add_mesh(node_index, node.mesh, world, acoustics.layer);
  }

  void add_camera(int node_index, int camera_index, const glm::dmat4& world) {
    if (camera_index < 0 || static_cast<std::size_t>(camera_index) >= model_.cameras.size()) {
      fail(label(node_index) + " refers to camera " + std::to_string(camera_index) + ", which does not exist");
    }
    if (scene_.camera) return;  // the first camera node is the listener
    const tinygltf::Camera& source = model_.cameras[static_cast<std::size_t>(camera_index)];
    Camera camera;
    camera.world = without_scale(world);
    if (source.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = source.perspective;
      const std::string at = "camera " + std::to_string(camera_index) + ": ";
      if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi)) fail(at + "yfov must be in (0, pi) radians");
      if (!(p.znear > 0.0 && std::isfinite(p.znear))) fail(at + "znear must be a finite number > 0");
      // zfar 0 (absent) means an infinite projection in glTF; keep ours.
      if (p.zfar != 0.0 && !(p.zfar > p.znear && std::isfinite(p.zfar))) fail(at + "zfar must exceed znear");
      if (!(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio))) fail(at + "aspectRatio must be > 0");
      camera.yfov = static_cast<float>(p.yfov);
      camera.znear = static_cast<float>(p.znear);
      if (p.zfar != 0.0) camera.zfar = static_cast<float>(p.zfar);
      camera.aspect_ratio = static_cast<float>(p.aspectRatio);
    }
    // Orthographic cameras keep the default projection; only the pose is used.
    scene_.camera = camera;
  }

  void add_mesh(int node_index, int mesh_index, const glm::dmat4& world, const std::optional<std::string>& layer) {
    if (mesh_index < 0 || static_cast<std::size_t>(mesh_index) >= model_.meshes.size()) {
      fail(label(node_index) + " refers to mesh " + std::to_string(mesh_index) + ", which does not exist");
    }
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(mesh_index)];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      add_primitive(mesh.primitives[p], mesh_label(mesh_index, p), world, layer);
    }
  }

  void add_primitive(const tinygltf::Primitive& primitive, const std::string& where, const glm::dmat4& world,
                     const std::optional<std::string>& node_layer) {
    const int mode = primitive.mode == -1 ? kModeTriangles : primitive.mode;
    if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) return;  // no surface to hit
    if (mode != kModeTriangles && mode != kModeStrip && mode != kModeFan) {
      fail(where + ": unknown primitive mode " + std::to_string(mode));
    }
    const auto position = primitive.attributes.find("POSITION");
    // glTF: a primitive without positions is not rendered; it has no surface.
    if (position == primitive.attributes.end()) return;

    const std::vector<glm::vec3> local = read_positions(model_, position->second);
    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0 || primitive.indices < -1) {
      indices = read_indices(model_, primitive.indices);
      for (std::size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= local.size()) {
          fail(where + ": index " + std::to_string(indices[i]) + " (element " + std::to_string(i) +
               ") is out of range for " + std::to_string(local.size()) + " vertices");
        }
      }
    }
    const bool indexed = primitive.indices != -1;
    const std::size_t corners = indexed ? indices.size() : local.size();
    std::size_t triangles = 0;
    if (mode == kModeTriangles) {
      if (corners % 3 != 0) fail(where + ": " + std::to_string(corners) + " corners is not a multiple of 3");
      triangles = corners / 3;
    } else if (corners >= 3) {
      triangles = corners - 2;
    }
    if (triangles == 0) return;
    if (triangles > kMaxTriangles - scene_.triangle_layers.size()) fail("more than 2^32/3 triangles");

    const std::uint32_t layer = layer_id(node_layer ? *node_layer : material_layer(primitive, where));
    // A mirroring transform turns counter-clockwise into clockwise; swapping
    // two corners keeps front faces facing outward for the renderer.
    const bool mirrored = glm::determinant(world) < 0.0;
    scene_.vertices.reserve(scene_.vertices.size() + 3 * triangles);
    for (std::size_t t = 0; t < triangles; ++t) {
      std::array<std::size_t, 3> corner = triangle_corners(mode, t);
      if (mirrored) std::swap(corner[1], corner[2]);
      for (const std::size_t c : corner) {
        const std::size_t vertex = indexed ? indices[c] : c;
        const glm::dvec4 p = world * glm::dvec4(glm::dvec3(local[vertex]), 1.0);
        const glm::vec3 w(p);
        if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z)) {
          fail(where + ": vertex " + std::to_string(vertex) + " is not finite in world space");
        }
        scene_.vertices.push_back(w);
      }
      scene_.triangle_layers.push_back(layer);
    }
  }

  std::string material_layer(const tinygltf::Primitive& primitive, const std::string& where) const {
    if (primitive.material == -1) return kDefaultLayer;
    if (primitive.material < 0 || static_cast<std::size_t>(primitive.material) >= model_.materials.size()) {
      fail(where + " refers to material " + std::to_string(primitive.material) + ", which does not exist");
    }
    const std::string& name = model_.materials[static_cast<std::size_t>(primitive.material)].name;
    return name.empty() ? kDefaultLayer : name;
  }

  std::uint32_t layer_id(const std::string& name) {
    const auto [it, inserted] = layer_ids_.try_emplace(name, static_cast<std::uint32_t>(scene_.layer_names.size()));
    if (inserted) scene_.layer_names.push_back(name);
    return it->second;
  }

  const tinygltf::Model& model_;
  Scene& scene_;
  std::vector<AudioEmitter> emitters_;
  std::unordered_map<std::string, std::uint32_t> layer_ids_;
};

}  // namespace
}  // namespace scene_detail

Result<Scene> load_scene(const std::filesystem::path& path) { return load_scene(path, SceneLoadOptions{}); }

Result<Scene> load_scene(const std::filesystem::path& path, const SceneLoadOptions& options) {
  const std::string file = path.string();
  try {
    Scene scene;
    scene.path = path;
    const tinygltf::Model model = scene_detail::read_gltf(path, options);
    scene_detail::SceneAssembler(model, scene).run();
    return scene;
  } catch (const Exception& e) {
    // Parts report without the path (json_fields as InvalidConfig); every
    // problem in a scene file is a scene error.
    return Error{ErrorCode::InvalidScene, file + ": " + e.error().message, 0};
  } catch (const std::bad_alloc&) {
    return Error{ErrorCode::LimitExceeded, file + ": out of memory while loading", 0};
  } catch (const std::exception& e) {
    return Error{ErrorCode::InvalidScene, file + ": " + e.what(), 0};
  }
}

}  // namespace sp
