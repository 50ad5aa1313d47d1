// Writes the rendered picture as a PNG that appears complete or not at all.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

// `rgba`: width * height pixels, 4 bytes each, rows top to bottom. Encodes
// to memory, writes a temporary file beside `path` and renames it over
// `path`; on failure (HostError) no file is left behind.
void write_png(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               std::span<const std::uint8_t> rgba);
