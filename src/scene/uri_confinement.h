// Private to the scene loader: which file a scene's buffer URI may name.
//
// Scenes come from strangers (levels, mods), so by default a scene reads
// only regular files inside its own folder tree (README "Security"): no
// absolute paths, no ".." out of the folder, no symbolic link leading out,
// no URI scheme, nothing under /proc or /sys, no devices. A trusted asset
// pipeline may lift the folder rule (SceneLoadOptions::allow_external_uris);
// the other rules always hold.
//
// Whoever wrote the scene may also change its folder while it loads (swap a
// subfolder for a link leading out). So the folder is opened once, every
// buffer is opened from that descriptor without ever leaving it
// (core/beneath_open.h), and the checks are made on the descriptor whose
// bytes are read: no path is checked and then looked up again.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/file_descriptor.h"

namespace sp::scene_detail {

struct UriRules {
  int scene_folder = -1;  // open_scene_folder's descriptor, not owned
  bool allow_external = false;
};

// The folder a scene at `scene_path` may read from, opened once: the folder
// its path names (a link to the scene file is not followed, as relative
// URIs resolve against the path as given; the current directory for a bare
// file name). Throws sp::Exception(InvalidScene): "file not found" when
// there is no such folder.
FileDescriptor open_scene_folder(const std::filesystem::path& scene_path);

// The whole content of the file that `decoded_uri` (a relative reference
// with its %XX escapes already decoded) names, relative to
// rules.scene_folder, when `rules` allow reading it and it is at most
// `max_bytes` long. Throws sp::Exception(InvalidScene) with the reason, not
// naming the URI, when they do not or the file does not exist.
std::vector<unsigned char> read_scene_uri(const UriRules& rules, const std::string& decoded_uri,
                                          std::uint64_t max_bytes);

// %XX escapes decoded exactly as tinygltf decodes a URI before opening it
// ('+' also becomes a space), so that names compare equal with the paths
// tinygltf asks for.
std::string decode_uri_as_tinygltf(const std::string& uri);

}  // namespace sp::scene_detail
