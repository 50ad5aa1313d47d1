// Private to the scene loader: reading a .gltf/.glb file into a tinygltf model.
#pragma once

#include <tiny_gltf.h>

#include <filesystem>

#include "soundpaint/scene.h"

namespace sp::scene_detail {

// Reads `path` as binary glTF when it starts with the "glTF" magic, else as
// JSON glTF (a file named .glb without the magic is an error). Only regular
// files are read. The scene's folder is opened once, and the scene file and
// its buffers are all opened from that descriptor. JSON nested deeper than json_fields::kMaxJsonDepth is
// refused before tinygltf parses it. External buffers are read only as
// uri_confinement.h allows (options.allow_external_uris lifts the folder
// rule); images are never read nor decoded, so missing or unsupported
// textures do not fail the load.
// tinygltf checks the GLB container and JSON syntax; the caller must still
// check every index and byte range before using the model.
// Throws sp::Exception (message without the path) on failure.
tinygltf::Model read_gltf(const std::filesystem::path& path, const SceneLoadOptions& options);

}  // namespace sp::scene_detail
