// Private to the scene loader: which file a scene's buffer URI may name.
//
// Scenes come from strangers (levels, mods), so by default a scene reads
// only regular files inside its own folder tree (README "Security"): no
// absolute paths, no ".." out of the folder, no symbolic link leading out,
// no URI scheme, nothing under /proc or /sys, no devices. A trusted asset
// pipeline may lift the folder rule (SceneLoadOptions::allow_external_uris);
// the other rules always hold.
#pragma once

#include <filesystem>
#include <string>

namespace sp::scene_detail {

struct UriRules {
  std::filesystem::path scene_folder;  // canonical: symbolic links resolved
  bool allow_external = false;
};

// The folder a scene at `scene_path` may read from: the canonical form of
// the folder its path names (a link to the scene file is not followed, as
// relative URIs resolve against the path as given).
std::filesystem::path scene_folder_of(const std::filesystem::path& scene_path);

// The file that `decoded_uri` (a relative reference with its %XX escapes
// already decoded) names, with every symbolic link resolved, when `rules`
// allow reading it. Throws sp::Exception(InvalidScene) with the reason, not
// naming the URI, when they do not or the file does not exist. Resolving
// looks at the path's components but opens nothing.
std::filesystem::path resolve_scene_uri(const UriRules& rules, const std::string& decoded_uri);

// %XX escapes decoded exactly as tinygltf decodes a URI before opening it
// ('+' also becomes a space), so that names compare equal with the paths
// tinygltf asks for.
std::string decode_uri_as_tinygltf(const std::string& uri);

}  // namespace sp::scene_detail
