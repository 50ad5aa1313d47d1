// sp::load_scene: flattens the default scene of a glTF 2.0 file into one
// world-space triangle list with a layer per triangle, and collects its sound
// sources and first camera (contract: README.md, "Authoring scenes").
#include <algorithm>
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

#include "scene/gltf_document.h"
#include "scene/mesh_decoder.h"
#include "scene/node_transform.h"
#include "scene/scene_error.h"
#include "scene/scene_sources.h"
#include "soundpaint/scene.h"

namespace sp {
namespace scene_detail {
namespace {

// Triangle ids downstream (BVH, GPU buffers) are 32-bit.
constexpr std::uint64_t kMaxTriangleIds = std::numeric_limits<std::uint32_t>::max() / 3;

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
  SceneAssembler(const tinygltf::Model& model, const SceneLoadOptions& options, Scene& scene)
      : model_(model), options_(options), scene_(scene), emitters_(read_audio_emitters(model)) {}

  // Walks the nodes (sources and camera in node order), then decodes each
  // mesh once, checks the total triangle count before building anything,
  // and places every instance into storage reserved once.
  void run() {
    visit(root_nodes(), roots_owner());
    const std::uint64_t triangles = count_triangles();
    if (triangles == 0) fail("no triangles (the scene has no triangle meshes)");
    scene_.vertices.reserve(3 * triangles);
    scene_.triangle_layers.reserve(triangles);
    for (const Instance& instance : instances_) place(instance);
  }

 private:
  // A node's mesh, placed by its world transform.
  struct Instance {
    int node;
    int mesh;
    glm::dmat4 world;
    std::optional<std::string> layer;  // the node's extras.acoustic_layer
  };

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
  // the sources (README.md, "Authoring scenes"). An explicit stack, so that a
  // deep chain of nodes cannot overflow the call stack; a node reached twice (a
  // cycle, or a child shared by two parents, both invalid glTF) is an error.
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
    if (node.mesh >= 0 || node.mesh < -1) {
      if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
        fail(label(node_index) + " refers to mesh " + std::to_string(node.mesh) + ", which does not exist");
      }
      instances_.push_back({node_index, node.mesh, world, acoustics.layer});
    }
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

  // Decodes each instanced mesh once; the sum over instances is checked
  // against the limits without overflowing, however many instances.
  std::uint64_t count_triangles() {
    const std::uint64_t limit = std::min<std::uint64_t>(options_.max_triangles, kMaxTriangleIds);
    std::uint64_t total = 0;
    for (const Instance& instance : instances_) {
      const std::size_t mesh = static_cast<std::size_t>(instance.mesh);
      if (meshes_.size() <= mesh) meshes_.resize(model_.meshes.size());
      if (!meshes_[mesh]) meshes_[mesh] = decode_mesh(model_, instance.mesh);
      total += meshes_[mesh]->triangles;
      if (total > limit) {
        const std::string over = "more than " + std::to_string(limit) + " triangles over its " +
                                 std::to_string(instances_.size()) + " mesh instances";
        if (limit == kMaxTriangleIds) fail(over + ", the most soundpaint supports");
        fail(over + " (the limit max_triangles can be raised: --max-triangles, SceneLoadOptions)");
      }
    }
    if (total > options_.memory_budget_bytes / kSceneBytesPerTriangle) {
      const auto mib = [](std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
      throw Exception(ErrorCode::LimitExceeded,
                      std::to_string(total) + " triangles need about " + mib(total * kSceneBytesPerTriangle) +
                          " to load and build (" + std::to_string(kSceneBytesPerTriangle) +
                          " bytes each), over the memory budget of " + mib(options_.memory_budget_bytes) +
                          "; raise it (--memory-budget, SceneLoadOptions::memory_budget_bytes)");
    }
    return total;
  }

  void place(const Instance& instance) {
    // A mirroring transform turns counter-clockwise into clockwise; swapping
    // two corners keeps front faces facing outward for the renderer.
    const bool mirrored = glm::determinant(instance.world) < 0.0;
    for (const DecodedPrimitive& primitive : meshes_[static_cast<std::size_t>(instance.mesh)]->primitives) {
      const std::uint32_t layer = layer_id(instance.layer ? *instance.layer : primitive.material_layer);
      for (std::size_t t = 0; t < primitive.triangles; ++t) {
        std::array<std::uint32_t, 3> corner = primitive.corners(t);
        if (mirrored) std::swap(corner[1], corner[2]);
        for (const std::uint32_t vertex : corner) {
          const glm::dvec4 p = instance.world * glm::dvec4(glm::dvec3(primitive.positions[vertex]), 1.0);
          const glm::vec3 w(p);
          if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z)) {
            fail("mesh " + std::to_string(instance.mesh) + " in " + label(instance.node) + ": vertex " +
                 std::to_string(vertex) + " is not finite in world space");
          }
          scene_.vertices.push_back(w);
        }
        scene_.triangle_layers.push_back(layer);
      }
    }
  }

  std::uint32_t layer_id(const std::string& name) {
    const auto [it, inserted] = layer_ids_.try_emplace(name, static_cast<std::uint32_t>(scene_.layer_names.size()));
    if (inserted) scene_.layer_names.push_back(name);
    return it->second;
  }

  const tinygltf::Model& model_;
  const SceneLoadOptions& options_;
  Scene& scene_;
  std::vector<AudioEmitter> emitters_;
  std::vector<Instance> instances_;                 // in node order
  std::vector<std::optional<DecodedMesh>> meshes_;  // by mesh index, once instanced
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
    scene_detail::SceneAssembler(model, options, scene).run();
    return scene;
  } catch (const Exception& e) {
    // Parts report without the path (json_fields as InvalidConfig); every
    // problem in a scene file is a scene error, but the memory budget's.
    const ErrorCode code =
        e.error().code == ErrorCode::LimitExceeded ? ErrorCode::LimitExceeded : ErrorCode::InvalidScene;
    return Error{code, file + ": " + e.error().message, 0};
  } catch (const std::bad_alloc&) {
    return Error{ErrorCode::LimitExceeded, file + ": out of memory while loading", 0};
  } catch (const std::exception& e) {
    return Error{ErrorCode::InvalidScene, file + ": " + e.what(), 0};
  }
}

}  // namespace sp
