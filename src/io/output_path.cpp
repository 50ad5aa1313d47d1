#include "io/output_path.h"

#include <algorithm>
#include <system_error>

#include "soundpaint/result.h"

namespace sp {
namespace {

// As the kernel's own limit on links followed in one lookup (ELOOP).
constexpr int kMaxSymlinkHops = 40;

// /proc's links (/dev/stdout -> /proc/self/fd/1 -> wherever standard output
// goes) name another file's descriptor, not a place to put a new file: a
// rename there would replace whatever the shell redirected to.
bool under_pseudo_file_system(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
  for (const char* root : {"/proc", "/sys"}) {
    const std::filesystem::path prefix(root);
    if (std::mismatch(prefix.begin(), prefix.end(), absolute.begin(), absolute.end()).first == prefix.end())
      return true;
  }
  return false;
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw Exception(ErrorCode::Io, "cannot write " + path.string() + ": " + what);
}

}  // namespace

bool names_stdout(const std::filesystem::path& path) { return path == "-"; }

OutputTarget resolve_output(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (names_stdout(path)) return OutputTarget{true, {}};
  if (path.empty()) throw Exception(ErrorCode::Io, "output path is empty");
  // Follow the link chain by hand: the file to replace is the one at its
  // end, which need not exist yet (a link to a file still to be written).
  fs::path file = path;
  std::error_code ec;
  for (int hops = 0;; ++hops) {
    if (under_pseudo_file_system(file)) fail(path, "it leads into /proc or /sys; give - for standard output");
    if (!fs::is_symlink(fs::symlink_status(file, ec))) break;
    if (hops == kMaxSymlinkHops) fail(path, "too many levels of symbolic links");
    const fs::path target = fs::read_symlink(file, ec);
    if (ec) fail(path, "cannot read the symbolic link: " + ec.message());
    file = target.is_absolute() ? target : file.parent_path() / target;
  }
  const fs::path name = file.filename();
  if (name.empty() || name == "." || name == "..") fail(path, "it is a directory");
  const fs::path folder = fs::canonical(file.has_parent_path() ? file.parent_path() : fs::path("."), ec);
  if (ec)
    fail(path, "its folder " + (file.has_parent_path() ? file.parent_path().string() : std::string(".")) + ": " +
                   ec.message());
  file = folder / name;
  if (under_pseudo_file_system(file)) fail(path, "it leads into /proc or /sys; give - for standard output");
  const fs::file_status status = fs::symlink_status(file, ec);
  if (fs::is_directory(status)) fail(path, "it is a directory");
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    fail(path, "not a regular file (a device, FIFO or socket); give - for standard output");
  }
  return OutputTarget{false, file};
}

void check_distinct_outputs(std::span<const NamedOutput> outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      OutputTarget a;
      OutputTarget b;
      try {
        a = resolve_output(outputs[j].path);
        b = resolve_output(outputs[i].path);
      } catch (const Exception&) {
        continue;  // the writer reports it, naming its own option's path
      }
      if (a.to_stdout == b.to_stdout && a.file == b.file) {
        throw Exception(ErrorCode::InvalidArgument, "options " + outputs[j].option + " and " + outputs[i].option +
                                                        " name the same output " + outputs[i].path.string());
      }
    }
  }
}

}  // namespace sp
