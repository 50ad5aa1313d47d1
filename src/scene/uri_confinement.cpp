#include "scene/uri_confinement.h"

#include <fcntl.h>
#include <linux/magic.h>
#include <sys/vfs.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <string_view>

#include "core/beneath_open.h"
#include "core/regular_file.h"
#include "scene/scene_error.h"

namespace sp::scene_detail {
namespace {

// Pseudo-file systems, told by the file system a descriptor lies on (not by
// a path, which a link or a bind mount disguises): files there report sizes
// they do not have and read the process's secrets (/proc/self/environ).
// Never scene data. Each is named by where it is mounted.
struct PseudoFileSystem {
  unsigned long magic;
  std::string_view mounted_under;
};
constexpr std::array<PseudoFileSystem, 13> kPseudoFileSystems = {{
    {PROC_SUPER_MAGIC, "/proc"},
    {BINFMTFS_MAGIC, "/proc"},
    {NSFS_MAGIC, "/proc"},
    {SYSFS_MAGIC, "/sys"},
    {CGROUP_SUPER_MAGIC, "/sys"},
    {CGROUP2_SUPER_MAGIC, "/sys"},
    {DEBUGFS_MAGIC, "/sys"},
    {TRACEFS_MAGIC, "/sys"},
    {SECURITYFS_MAGIC, "/sys"},
    {SELINUX_MAGIC, "/sys"},
    {PSTOREFS_MAGIC, "/sys"},
    {EFIVARFS_MAGIC, "/sys"},
    {BPF_FS_MAGIC, "/sys"},
}};

void refuse_pseudo_files(int fd) {
  struct statfs file_system {};
  if (::fstatfs(fd, &file_system) != 0) fail(std::string("cannot open: ") + std::strerror(errno));
  const auto type = static_cast<unsigned long>(file_system.f_type);
  for (const PseudoFileSystem& pseudo : kPseudoFileSystems) {
    if (type == pseudo.magic) fail("names a file under " + std::string(pseudo.mounted_under));
  }
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
// the text alone, for a message that says so (symbolic links are judged
// while opening, which refuses this too).
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

void check_uri_text(const UriRules& rules, const std::string& decoded_uri) {
  if (decoded_uri.empty()) fail("empty");
  if (decoded_uri.find('\0') != std::string::npos) fail("contains a NUL byte");
  if (has_scheme(decoded_uri)) fail("has a URI scheme; only relative references and data: URIs are read");
  if (rules.allow_external) return;
  if (decoded_uri.front() == '/') {
    fail("is an absolute path; a scene reads only files in its own folder (allow_external_uris lifts this)");
  }
  if (climbs_out(decoded_uri)) fail("leads out of the scene's folder with \"..\" (allow_external_uris lifts this)");
}

[[noreturn]] void fail_open(int error) {
  if (error == ENOENT || error == ENOTDIR) fail("file not found");
  if (error == EXDEV) {
    fail(
        "leads out of the scene's folder through a symbolic link (only relative links that stay inside are "
        "followed; allow_external_uris lifts this)");
  }
  fail(std::string("cannot open: ") + std::strerror(error));
}

// Opens the URI's file with `flags`, from the scene's folder; never leaving
// it unless the rules allow.
FileDescriptor open_uri(const UriRules& rules, const std::string& decoded_uri, int flags) {
  if (rules.allow_external) {
    FileDescriptor fd(::openat(rules.scene_folder, decoded_uri.c_str(), flags | O_CLOEXEC));
    if (!fd.valid()) fail_open(errno);
    return fd;
  }
  OpenResult opened = open_beneath(rules.scene_folder, decoded_uri, flags);
  if (!opened.fd.valid()) fail_open(opened.error);
  return std::move(opened.fd);
}

unsigned char hex_value(char c) {
  if (c >= '0' && c <= '9') return static_cast<unsigned char>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<unsigned char>(c - 'a' + 10);
  if (c >= 'A' && c <= 'F') return static_cast<unsigned char>(c - 'A' + 10);
  return 0;  // as tinygltf: a bad digit counts as 0
}

}  // namespace

FileDescriptor open_scene_folder(const std::filesystem::path& scene_path) {
  const std::filesystem::path folder = scene_path.parent_path();
  FileDescriptor fd(::open(folder.empty() ? "." : folder.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (!fd.valid() && (errno == ENOENT || errno == ENOTDIR)) fail("file not found");
  if (!fd.valid()) fail(std::string("cannot open the scene's folder: ") + std::strerror(errno));
  return fd;
}

std::vector<unsigned char> read_scene_uri(const UriRules& rules, const std::string& decoded_uri,
                                          std::uint64_t max_bytes) {
  check_uri_text(rules, decoded_uri);
  const FileOpener open = [&](int flags) { return open_uri(rules, decoded_uri, flags); };
  return read_regular_file(open, max_bytes, ErrorCode::InvalidScene, &refuse_pseudo_files);
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
