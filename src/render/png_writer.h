// PNG output of rendered frames (stb_image_write, from Debian's compiled
// libstb), written atomically so no partial file ever appears.
#pragma once

#include <filesystem>
#include <string>

#include "render/render_target.h"

namespace sp::draw {

// The image as an 8-bit RGB PNG (alpha dropped: frames are opaque).
// Throws sp::Exception(Io) if encoding fails.
std::string encode_png(const RgbaImage& image);

// encode_png() written to `path` through a temporary file and a rename.
// Throws sp::Exception(Io) naming the path.
void write_png(const std::filesystem::path& path, const RgbaImage& image);

}  // namespace sp::draw
