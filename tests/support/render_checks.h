// Pixel-level checks for rendered pictures: colour tests, pixel rays, and
// the golden-image comparison (tolerance, saved actual and diff images).
#pragma once

#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>

#include "render/png_writer.h"
#include "render/render_target.h"

namespace sp::test {

struct Rgb {
  int r = 0, g = 0, b = 0;
};

inline Rgb pixel(const draw::RgbaImage& image, std::uint32_t x, std::uint32_t y) {
  const std::uint8_t* p = image.at(x, y);
  return {p[0], p[1], p[2]};
}

// Far from grey: an indicator's colour, never the concrete the test scenes use.
inline bool is_saturated(Rgb c) { return std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b}) > 50; }

template <class Predicate>
std::size_t count_pixels(const draw::RgbaImage& image, Predicate&& predicate) {
  std::size_t n = 0;
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) n += predicate(pixel(image, x, y)) ? 1 : 0;
  return n;
}

// Pixels where some channel differs by more than `tolerance`; `diff`, if
// given, becomes the actual picture darkened with those pixels in magenta.
inline std::size_t differing_pixels(const draw::RgbaImage& actual, const draw::RgbaImage& expected, int tolerance,
                                    draw::RgbaImage* diff) {
  if (actual.width != expected.width || actual.height != expected.height) return actual.pixels.size() / 4;
  if (diff != nullptr) *diff = actual;
  std::size_t n = 0;
  for (std::size_t i = 0; i < actual.pixels.size(); i += 4) {
    bool differs = false;
    for (std::size_t c = 0; c < 3; ++c) differs |= std::abs(actual.pixels[i + c] - expected.pixels[i + c]) > tolerance;
    n += differs ? 1 : 0;
    if (diff == nullptr) continue;
    for (std::size_t c = 0; c < 3; ++c)
      diff->pixels[i + c] = static_cast<std::uint8_t>(differs ? (c == 1 ? 0 : 255) : actual.pixels[i + c] / 4);
  }
  return n;
}

// Where the ray through the centre of pixel (x, y) meets the plane x = `plane_x`,
// given the inverse of the camera's view-projection (Vulkan clip space).
inline std::optional<glm::vec3> pixel_ray_hits_plane_x(const glm::mat4& inverse_view_projection, std::uint32_t x,
                                                       std::uint32_t y, std::uint32_t width, std::uint32_t height,
                                                       float plane_x) {
  const float nx = (static_cast<float>(x) + 0.5f) / static_cast<float>(width) * 2.0f - 1.0f;
  const float ny = (static_cast<float>(y) + 0.5f) / static_cast<float>(height) * 2.0f - 1.0f;
  const glm::vec4 near_h = inverse_view_projection * glm::vec4(nx, ny, 0.0f, 1.0f);
  const glm::vec4 far_h = inverse_view_projection * glm::vec4(nx, ny, 1.0f, 1.0f);
  const glm::vec3 a = glm::vec3(near_h) / near_h.w;
  const glm::vec3 b = glm::vec3(far_h) / far_h.w;
  if (a.x == b.x) return std::nullopt;
  const float t = (plane_x - a.x) / (b.x - a.x);
  if (t < 0.0f || t > 1.0f) return std::nullopt;
  return a + t * (b - a);
}

inline std::optional<draw::RgbaImage> load_png(const std::filesystem::path& path) {
  int width = 0, height = 0, channels = 0;
  stbi_uc* data = stbi_load(path.string().c_str(), &width, &height, &channels, 4);
  if (data == nullptr) return std::nullopt;
  draw::RgbaImage image;
  image.width = static_cast<std::uint32_t>(width);
  image.height = static_cast<std::uint32_t>(height);
  image.pixels.assign(data, data + static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  stbi_image_free(data);
  return image;
}

// At most 0.5% of pixels may differ by more than 8 in a channel (rounding
// across lavapipe versions, not a different picture). On failure writes
// <name>-actual.png and <name>-diff.png into `failure_dir`.
inline void expect_matches_golden(const draw::RgbaImage& actual, const std::filesystem::path& golden,
                                  const std::filesystem::path& failure_dir) {
  const std::optional<draw::RgbaImage> expected = load_png(golden);
  draw::RgbaImage diff;
  const std::size_t differing = expected ? differing_pixels(actual, *expected, 8, &diff) : actual.pixels.size() / 4;
  const std::size_t allowed = actual.pixels.size() / 4 / 200;
  if (expected && differing <= allowed) return;
  std::filesystem::create_directories(failure_dir);
  const std::string stem = golden.stem().string();
  draw::write_png(failure_dir / (stem + "-actual.png"), actual);
  if (expected && expected->width == actual.width && expected->height == actual.height)
    draw::write_png(failure_dir / (stem + "-diff.png"), diff);
  ADD_FAILURE() << (expected ? std::to_string(differing) + " pixels differ from " + golden.string() + " (at most " +
                                   std::to_string(allowed) + " may)"
                             : "cannot read golden image " + golden.string() + " (scripts/rebless-golden.sh writes it)")
                << "; actual and diff images in " << failure_dir;
}

}  // namespace sp::test
