// Private to the scene loader: reading a .gltf/.glb file into a tinygltf model.
#pragma once

#include <tiny_gltf.h>

#include <filesystem>

namespace sp::scene_detail {

// Reads `path` as binary glTF when it starts with the "glTF" magic, else as
// JSON glTF (a file named .glb without the magic is an error). External
// buffers are resolved against the file's directory; images are never
// decoded, so missing or unsupported textures do not fail the load.
// tinygltf checks the GLB container and JSON syntax; the caller must still
// check every index and byte range before using the model.
// Throws sp::Exception (message without the path) on failure.
tinygltf::Model read_gltf(const std::filesystem::path& path);

}  // namespace sp::scene_detail
