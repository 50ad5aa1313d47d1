#include "scene/uri_confinement.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>
#include <system_error>

#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

// Pseudo-file systems: files there report sizes they do not have and read
// the process's secrets (/proc/self/environ). Never scene data.
constexpr std::array<std::string_view, 2> kPseudoFileSystems = {"/proc", "/sys"};

bool is_within(const std::filesystem::path& path, const std::filesystem::path& folder) {
  const auto [folder_end, path_at] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return folder_end == folder.end();
}

// RFC 3986: a scheme is a letter, then letters, digits, '+', '-' or '.',
// then ':' (this also catches Windows drive letters such as "C:").
bool has_scheme(std::string_view uri) {
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  for (const char c : uri.substr(1)) {
    if (c == ':') return true;
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

// Whether ".." segments climb above the folder the URI starts in, judged on
// the text alone (symbolic links are checked after resolving).
bool climbs_out(std::string_view uri) {
  long depth = 0;
  std::size_t start = 0;
  while (start <= uri.size()) {
    std::size_t end = uri.find('/', start);
    if (end == std::string_view::npos) end = uri.size();
    const std::string_view segment = uri.substr(start, end - start);
    if (segment == "..") {
      if (--depth < 0) return true;
    } else if (!segment.empty() && segment != ".") {
      ++depth;
    }
    start = end + 1;
  }
  return false;
}

unsigned char hex_value(char c) {
  if (c >= '0' && c <= '9') return static_cast<unsigned char>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<unsigned char>(c - 'a' + 10);
  if (c >= 'A' && c <= 'F') return static_cast<unsigned char>(c - 'A' + 10);
  return 0;  // as tinygltf: a bad digit counts as 0
}

}  // namespace

std::filesystem::path scene_folder_of(const std::filesystem::path& scene_path) {
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::absolute(scene_path, ec).parent_path();
  std::filesystem::path canonical = std::filesystem::canonical(folder, ec);
  if (ec) fail("cannot resolve the scene's folder: " + ec.message());
  return canonical;
}

std::filesystem::path resolve_scene_uri(const UriRules& rules, const std::string& decoded_uri) {
  if (decoded_uri.empty()) fail("empty");
  if (decoded_uri.find('\0') != std::string::npos) fail("contains a NUL byte");
  if (has_scheme(decoded_uri)) fail("has a URI scheme; only relative references and data: URIs are read");
  const bool absolute = decoded_uri.front() == '/';
  if (!rules.allow_external && absolute) {
    fail("is an absolute path; a scene reads only files in its own folder (allow_external_uris lifts this)");
  }
  if (!rules.allow_external && climbs_out(decoded_uri)) {
    fail("leads out of the scene's folder with \"..\" (allow_external_uris lifts this)");
  }
  std::error_code ec;
  const std::filesystem::path named = absolute ? std::filesystem::path(decoded_uri) : rules.scene_folder / decoded_uri;
  std::filesystem::path file = std::filesystem::canonical(named, ec);
  if (ec) fail(ec == std::errc::no_such_file_or_directory ? "file not found" : "cannot resolve: " + ec.message());
  if (!rules.allow_external && !is_within(file, rules.scene_folder)) {
    fail("leads out of the scene's folder through a symbolic link (allow_external_uris lifts this)");
  }
  for (const std::string_view pseudo : kPseudoFileSystems) {
    if (is_within(file, std::filesystem::path(pseudo))) fail("names a file under " + std::string(pseudo));
  }
  return file;
}

std::string decode_uri_as_tinygltf(const std::string& uri) {
  std::string decoded;
  decoded.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      decoded += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      decoded += static_cast<char>((hex_value(uri[i + 1]) << 4) | hex_value(uri[i + 2]));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  return decoded;
}

}  // namespace sp::scene_detail
