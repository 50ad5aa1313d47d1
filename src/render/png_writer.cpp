#include "render/png_writer.h"

#include <stb_image_write.h>

#include <cstdint>
#include <vector>

#include "io/output.h"
#include "soundpaint/result.h"

namespace sp::draw {
namespace {

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

std::string encode_png(const RgbaImage& image) {
  const std::size_t pixels = std::size_t{image.width} * image.height;
  if (pixels == 0 || image.pixels.size() != pixels * 4)
    throw Exception(ErrorCode::InvalidArgument, "encode_png: the image's pixel data does not match its size");
  std::vector<std::uint8_t> rgb(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    rgb[3 * i + 0] = image.pixels[4 * i + 0];
    rgb[3 * i + 1] = image.pixels[4 * i + 1];
    rgb[3 * i + 2] = image.pixels[4 * i + 2];
  }
  std::string png;
  const int width = static_cast<int>(image.width);
  const int height = static_cast<int>(image.height);
  if (stbi_write_png_to_func(append_bytes, &png, width, height, 3, rgb.data(), width * 3) == 0 || png.empty())
    throw Exception(ErrorCode::Io,
                    "PNG encoding of a " + std::to_string(width) + "x" + std::to_string(height) + " image failed");
  return png;
}

void write_png(const std::filesystem::path& path, const RgbaImage& image) {
  write_file_atomically(path, encode_png(image)).value();
}

}  // namespace sp::draw
