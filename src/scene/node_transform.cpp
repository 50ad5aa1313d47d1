#include "scene/node_transform.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

void check_property(const std::vector<double>& values, std::size_t expected_size, const char* property,
                    const std::string& node_label) {
  if (!values.empty() && values.size() != expected_size) {
    fail(node_label + ": \"" + property + "\" must have " + std::to_string(expected_size) + " numbers, has " +
         std::to_string(values.size()));
  }
  for (const double v : values) {
    if (!std::isfinite(v)) fail(node_label + ": \"" + property + "\" has a non-finite value");
  }
}

}  // namespace

glm::dmat4 local_transform(const tinygltf::Node& node, const std::string& node_label) {
  check_property(node.matrix, 16, "matrix", node_label);
  check_property(node.translation, 3, "translation", node_label);
  check_property(node.rotation, 4, "rotation", node_label);
  check_property(node.scale, 3, "scale", node_label);

  // glTF forbids matrix together with TRS; when both appear, matrix wins.
  if (!node.matrix.empty()) return glm::make_mat4(node.matrix.data());  // both column-major

  glm::dmat4 t(1.0);
  if (!node.translation.empty()) {
    t = glm::translate(glm::dmat4(1.0), glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  glm::dmat4 r(1.0);
  if (!node.rotation.empty()) {
    // glTF stores x, y, z, w; glm's constructor takes w first.
    glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const double length = glm::length(q);
    if (!(length > 1e-12)) fail(node_label + ": \"rotation\" is a zero quaternion");
    // Exporters write quaternions with a few digits; renormalising keeps the
    // rotation from scaling the geometry.
    r = glm::mat4_cast(q / length);
  }
  glm::dmat4 s(1.0);
  if (!node.scale.empty()) s = glm::scale(glm::dmat4(1.0), glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  return t * r * s;
}

}  // namespace sp::scene_detail
