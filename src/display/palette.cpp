// Palettes, written once as the sRGB hex codes people know them by, and
// converted to linear RGB on first use.
//
// Okabe-Ito: M. Okabe and K. Ito, "Color Universal Design (CUD): how to make
// figures and presentations that are friendly to colorblind people" (2002,
// revised 2008), the colour-blind-safe set of eight.
//
// Every colour of every palette has a relative luminance of at least 0.1, so
// that it keeps 3:1 contrast against the dark ring of the halo drawn around
// each spot (src/display/contrast.h): the spot's own edge always shows.
#include "display/palette.h"

#include <array>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "display/categories.h"

namespace sp {
namespace {

// Entries 0..7 in the order of builtin_categories(): footsteps, gunfire,
// voice, explosion, alarm, music, machinery, door. Then other categories.

// Okabe-Ito's seven colours with white in place of its black, which would be
// invisible on a dark level. The danger sounds (gunfire, explosion, alarm)
// take the warm colours; footsteps, the cue players act on most, take white,
// the brightest. The three extra entries were chosen (a search over the sRGB
// cube) to stay at least CIEDE2000 10 from every other entry for normal vision
// and under simulated protanopia, deuteranopia and tritanopia.
constexpr std::array<std::uint32_t, 11> kOkabeItoSrgb = {
    0xFFFFFF,  // footsteps: white (replaces Okabe-Ito's black)
    0xD55E00,  // gunfire: vermillion
    0x56B4E9,  // voice: sky blue
    0xE69F00,  // explosion: orange
    0xF0E442,  // alarm: yellow
    0xCC79A7,  // music: reddish purple
    0x0072B2,  // machinery: blue
    0x009E73,  // door: bluish green
    0x22EEFF,  // other: cyan
    0x8877FF,  // other: violet
    0xBBDDAA,  // other: pale green
};

// Saturated colours (CIELAB chroma >= 60, cyan 46: the most sRGB allows at
// its hue and brightness) with the same meanings, far from the greys and
// browns of most level geometry. Chosen by a search within a hue range per
// category so that, like Okabe-Ito, every pair stays at least CIEDE2000 10
// apart for all four kinds of vision.
constexpr std::array<std::uint32_t, 10> kHighContrastSrgb = {
    0x44FFFF,  // footsteps: cyan
    0xFF0022,  // gunfire: red
    0xAAFF99,  // voice: light green
    0xFF8800,  // explosion: orange
    0xFFFF00,  // alarm: yellow
    0xFF33AA,  // music: pink
    0x0077FF,  // machinery: azure
    0xEE99FF,  // door: orchid
    0x22CC88,  // other: jade
    0xBB0099,  // other: magenta
};

// One hue, amber (CIELAB hue 83 degrees, that of #FFBF00), at CIELAB
// lightness 96, 90, 84, 76, 68, 61, 54, 47, 40, each at the greatest chroma
// sRGB holds there: lightness falls along the built-in order, which is
// roughly how often a player must act on the sound. Colour says little
// here; the shapes tell the categories apart. The darkest stays at relative
// luminance 0.11, above the halo's 0.1 floor.
constexpr std::array<std::uint32_t, 9> kSingleHueSrgb = {
    0xFFF2DF,  // footsteps
    0xFFDEA8,  // gunfire
    0xFFCA5B,  // voice
    0xEEB200,  // explosion
    0xD39D00,  // alarm
    0xBB8C00,  // music
    0xA57A00,  // machinery
    0x8F6900,  // door
    0x795900,  // other
};

static_assert(kOkabeItoSrgb.size() > kBuiltinCategoryCount);
static_assert(kHighContrastSrgb.size() > kBuiltinCategoryCount);
static_assert(kSingleHueSrgb.size() > kBuiltinCategoryCount);

float srgb_channel_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

float linear_channel_to_srgb(float c) {
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

glm::vec3 linear_from_hex(std::uint32_t rgb) {
  const auto channel = [rgb](int shift) { return static_cast<float>((rgb >> shift) & 0xFFu) / 255.0f; };
  return srgb_to_linear(glm::vec3(channel(16), channel(8), channel(0)));
}

template <std::size_t N>
std::array<glm::vec3, N> linear_from_hex(const std::array<std::uint32_t, N>& hex) {
  std::array<glm::vec3, N> linear{};
  for (std::size_t i = 0; i < N; ++i) linear[i] = linear_from_hex(hex[i]);
  return linear;
}

}  // namespace

glm::vec3 srgb_to_linear(glm::vec3 srgb) {
  return {srgb_channel_to_linear(srgb.x), srgb_channel_to_linear(srgb.y), srgb_channel_to_linear(srgb.z)};
}

glm::vec3 linear_to_srgb(glm::vec3 linear) {
  return {linear_channel_to_srgb(linear.x), linear_channel_to_srgb(linear.y), linear_channel_to_srgb(linear.z)};
}

std::span<const glm::vec3> palette_colors(Palette palette) {
  // Function-local statics: converted once, on first use, thread-safely.
  switch (palette) {
    case Palette::HighContrast: {
      static const auto colors = linear_from_hex(kHighContrastSrgb);
      return colors;
    }
    case Palette::SingleHue: {
      static const auto colors = linear_from_hex(kSingleHueSrgb);
      return colors;
    }
    case Palette::OkabeIto:
      break;
  }
  static const auto colors = linear_from_hex(kOkabeItoSrgb);
  return colors;
}

}  // namespace sp
