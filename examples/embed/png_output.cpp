#include "png_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>
#include <unistd.h>

// Debian's libstb ships the implementation compiled; this is the header only.
#include <stb_image_write.h>

#include "host_error.h"

namespace {

void append(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

// Removes the temporary file unless it was renamed into place.
struct TemporaryFile {
  std::filesystem::path path;
  std::FILE* file = nullptr;
  bool kept = true;  // until this program has created it
  ~TemporaryFile() {
    if (file != nullptr) std::fclose(file);
    std::error_code ignored;
    if (!kept) std::filesystem::remove(path, ignored);
  }
};

}  // namespace

void write_png(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               std::span<const std::uint8_t> rgba) {
  std::string png;
  const int w = static_cast<int>(width);
  const int h = static_cast<int>(height);
  if (stbi_write_png_to_func(append, &png, w, h, 4, rgba.data(), w * 4) == 0 || png.empty())
    fail("cannot encode the " + std::to_string(width) + "x" + std::to_string(height) + " picture as PNG");

  const std::string target = path.string();
  TemporaryFile temporary;
  temporary.path = target + ".tmp-" + std::to_string(::getpid());
  // "x": never write through a file someone else created under that name.
  temporary.file = std::fopen(temporary.path.c_str(), "wbx");
  if (temporary.file == nullptr) fail("cannot write " + target + ": " + std::strerror(errno));
  temporary.kept = false;
  errno = 0;
  const bool written = std::fwrite(png.data(), 1, png.size(), temporary.file) == png.size() &&
                       std::fflush(temporary.file) == 0 && ::fsync(::fileno(temporary.file)) == 0;
  const bool closed = std::fclose(temporary.file) == 0;
  const int saved_errno = errno;
  temporary.file = nullptr;
  if (!written || !closed) fail("cannot write " + target + ": " + std::strerror(saved_errno != 0 ? saved_errno : EIO));
  std::error_code error;
  std::filesystem::rename(temporary.path, path, error);
  if (error) fail("cannot write " + target + ": " + error.message());
  temporary.kept = true;
}
