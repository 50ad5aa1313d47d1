#include "scene/gltf_document.h"

#include <fcntl.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/regular_file.h"
#include "scene/gltf_file_access.h"
#include "scene/gltf_json_scan.h"
#include "scene/scene_error.h"
#include "scene/uri_confinement.h"

namespace sp::scene_detail {
namespace {

// Extensions that replace the geometry buffers with a compressed form this
// loader cannot decode; failing up front gives a clearer message than the
// empty accessors they leave behind.
constexpr std::array<std::string_view, 3> kUnsupportedRequiredExtensions = {
    "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"};

// tinygltf takes a file's length as unsigned int; buffers get the same cap.
constexpr std::uint64_t kMaxGltfFileBytes = std::numeric_limits<std::uint32_t>::max();

// Soundpaint needs geometry only; textures are neither decoded nor checked.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// tinygltf's messages end in newlines and may hold several lines; ours are
// one line. nlohmann's "[json.exception.parse_error.101] " ids mean nothing
// to a user either.
std::string one_line(std::string text) {
  for (std::size_t at = text.find("[json.exception."); at != std::string::npos; at = text.find("[json.exception.")) {
    const std::size_t close = text.find("] ", at);
    if (close == std::string::npos) break;
    text.erase(at, close + 2 - at);
  }
  std::replace(text.begin(), text.end(), '\n', ';');
  std::replace(text.begin(), text.end(), '\r', ' ');
  while (!text.empty() && (text.back() == ';' || text.back() == ' ')) text.pop_back();
  return printable_text(text);
}

bool has_glb_magic(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

// The first byte that is not whitespace (or a UTF-8 byte order mark) is '{'.
bool starts_like_json_object(const std::vector<unsigned char>& bytes) {
  std::size_t at = bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF ? 3 : 0;
  while (at < bytes.size() && (bytes[at] == ' ' || bytes[at] == '\t' || bytes[at] == '\n' || bytes[at] == '\r')) ++at;
  return at < bytes.size() && bytes[at] == '{';
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The scene file, opened from its folder's descriptor: the folder its
// buffers are read from is the folder it was read from, even if a folder on
// its path is swapped meanwhile. The file itself may be a link (the caller
// chose the path).
std::vector<unsigned char> read_scene_file(int folder, const std::filesystem::path& path) {
  // A path that ends in '/' names a folder: "is a directory".
  const std::filesystem::path name = path.filename().empty() ? "." : path.filename();
  const FileOpener open = [folder, &name](int flags) {
    FileDescriptor fd(::openat(folder, name.c_str(), flags | O_CLOEXEC));
    if (!fd.valid() && (errno == ENOENT || errno == ENOTDIR)) fail("file not found");
    if (!fd.valid()) fail(std::string("cannot open: ") + std::strerror(errno));
    return fd;
  };
  return read_regular_file(open, kMaxGltfFileBytes, ErrorCode::InvalidScene);
}

}  // namespace

tinygltf::Model read_gltf(const std::filesystem::path& path, const SceneLoadOptions& options) {
  const FileDescriptor folder = open_scene_folder(path);
  const std::vector<unsigned char> bytes = read_scene_file(folder.get(), path);
  if (bytes.empty()) fail("empty file");
  const bool binary = has_glb_magic(bytes);
  if (!binary && lower_extension(path) == ".glb") fail("not a binary glTF file (no \"glTF\" magic)");
  // A level in another format (a .bsp, an .fbx, an .obj) is neither binary
  // glTF nor a JSON object: say so, not where JSON parsing stopped.
  if (!binary && !starts_like_json_object(bytes))
    fail("not a glTF 2.0 file (a .gltf is a JSON object, a .glb starts with \"glTF\"); convert the level to glTF 2.0");
  const char* const kind = binary ? "cannot load binary glTF: " : "cannot load glTF: ";

  // The JSON is scanned before tinygltf sees it: too deep a file would
  // overflow the stack in its recursive parse.
  GltfJsonFacts facts;
  try {
    const std::string_view json =
        binary ? glb_json_chunk(bytes) : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    facts = scan_gltf_json(json);
  } catch (const Exception& e) {
    fail(kind + e.error().message);
  }
  GltfFileAccess files(UriRules{folder.get(), options.allow_external_uris}, facts.buffer_uris, kMaxGltfFileBytes);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  loader.SetFsCallbacks(files.callbacks());
  // Extras are read back as JSON text, which keeps integer/float/bool distinct.
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);

  tinygltf::Model model;
  std::string err;
  std::string warn;
  // No base directory: every URI reaches GltfFileAccess as written, which
  // resolves it against the scene's folder itself.
  const std::string base_dir;
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
                         : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                      size, base_dir);
  if (!ok && !files.refusal().empty()) fail(files.refusal());
  if (!ok) {
    std::string problem = one_line(err.empty() ? warn : err);
    if (problem.empty()) problem = "tinygltf could not parse it";
    fail(kind + problem);
  }
  if (model.asset.version.rfind("2.", 0) != 0) {
    fail("unsupported glTF version \"" + printable(model.asset.version) + "\" (need 2.x)");
  }
  for (const std::string& required : model.extensionsRequired) {
    const auto it = std::find(kUnsupportedRequiredExtensions.begin(), kUnsupportedRequiredExtensions.end(), required);
    if (it != kUnsupportedRequiredExtensions.end()) {
      fail("required extension " + required + " (compressed geometry) is not supported");
    }
  }
  return model;
}

}  // namespace sp::scene_detail
