#include "scene/accessor_reader.h"

#include <bit>
#include <cstddef>
#include <cstring>
#include <string>

#include <glm/glm.hpp>

#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

// glTF buffers are little-endian; elements are copied without byte swapping.
static_assert(std::endian::native == std::endian::little, "the glTF reader assumes a little-endian host");

// Where an accessor's elements lie: element i starts at first + i * stride.
struct ElementSpan {
  const unsigned char* first = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};

std::size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

std::string accessor_label(int index) { return "accessor " + std::to_string(index); }

const tinygltf::Accessor& find_accessor(const tinygltf::Model& model, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    fail(accessor_label(index) + " does not exist (the file has " + std::to_string(model.accessors.size()) + ")");
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.sparse.isSparse) fail(accessor_label(index) + ": sparse accessors are not supported");
  return accessor;
}

// Checks that `accessor` (already known to have the expected type) lies
// inside its buffer view and that the view lies inside its buffer. All sums
// are arranged so that hostile sizes cannot wrap around.
ElementSpan locate(const tinygltf::Model& model, int index, std::size_t element_size) {
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  const std::string label = accessor_label(index);
  if (accessor.bufferView < 0) fail(label + " has no bufferView (all-zero accessors are not supported)");
  if (static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size()) {
    fail(label + " refers to bufferView " + std::to_string(accessor.bufferView) + ", which does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  const std::string view_label = "bufferView " + std::to_string(accessor.bufferView);
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    fail(view_label + " refers to buffer " + std::to_string(view.buffer) + ", which does not exist");
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    fail(view_label + " (offset " + std::to_string(view.byteOffset) + ", length " + std::to_string(view.byteLength) +
         ") lies outside buffer " + std::to_string(view.buffer) + " (" + std::to_string(data.size()) + " bytes)");
  }
  const std::size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
  if (stride < element_size) {
    fail(view_label + ": byteStride " + std::to_string(stride) + " is smaller than the " +
         std::to_string(element_size) + "-byte elements of " + label);
  }
  ElementSpan span;
  span.stride = stride;
  span.count = accessor.count;
  if (accessor.count == 0) return span;
  // The last element ends at byteOffset + (count - 1) * stride + element_size.
  const std::size_t available = view.byteLength;
  const bool fits = accessor.byteOffset <= available && element_size <= available - accessor.byteOffset &&
                    accessor.count - 1 <= (available - accessor.byteOffset - element_size) / stride;
  if (!fits) {
    fail(label + " (offset " + std::to_string(accessor.byteOffset) + ", " + std::to_string(accessor.count) +
         " elements of " + std::to_string(element_size) + " bytes, stride " + std::to_string(stride) +
         ") reaches beyond " + view_label + " (" + std::to_string(view.byteLength) + " bytes)");
  }
  span.first = data.data() + view.byteOffset + accessor.byteOffset;
  return span;
}

}  // namespace

std::vector<glm::vec3> read_positions(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = find_accessor(model, index);
  if (accessor.type != TINYGLTF_TYPE_VEC3 || accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    fail(accessor_label(index) + ": POSITION must be VEC3 of FLOAT (quantized positions are not supported)");
  }
  const ElementSpan span = locate(model, index, 3 * sizeof(float));
  std::vector<glm::vec3> positions(span.count);
  for (std::size_t i = 0; i < span.count; ++i) {
    float xyz[3];
    // memcpy: the data need not be aligned for float.
    std::memcpy(xyz, span.first + i * span.stride, sizeof xyz);
    positions[i] = glm::vec3(xyz[0], xyz[1], xyz[2]);
  }
  return positions;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = find_accessor(model, index);
  const int type = accessor.componentType;
  const bool unsigned_type = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                             type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  if (accessor.type != TINYGLTF_TYPE_SCALAR || !unsigned_type) {
    fail(accessor_label(index) + ": indices must be SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  const std::size_t size = component_size(type);
  const ElementSpan span = locate(model, index, size);
  std::vector<std::uint32_t> indices(span.count);
  for (std::size_t i = 0; i < span.count; ++i) {
    const unsigned char* p = span.first + i * span.stride;
    if (size == 1) {
      indices[i] = p[0];
    } else if (size == 2) {
      std::uint16_t v;
      std::memcpy(&v, p, sizeof v);
      indices[i] = v;
    } else {
      std::memcpy(&indices[i], p, sizeof(std::uint32_t));
    }
  }
  return indices;
}

}  // namespace sp::scene_detail
