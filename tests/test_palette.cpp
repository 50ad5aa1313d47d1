// Colours and categories of the display: CIEDE2000 against the published test
// pairs, the colour-vision simulation, the palettes' distinguishability for
// normal and colour-blind vision, the halo's contrast on any surface, the
// names, the numbering of categories, and the bounds on the display's
// category lists. Expected values are published or
// derived by hand in the comments, never taken from the code's own output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "display/categories.h"
#include "display/color_vision.h"
#include "display/contrast.h"
#include "display/display_checks.h"
#include "display/palette.h"
#include "soundpaint/display.h"
#include "soundpaint/result.h"

namespace sp {
namespace {

constexpr ColorVision kVisions[] = {ColorVision::Normal, ColorVision::Protanopia, ColorVision::Deuteranopia,
                                    ColorVision::Tritanopia};
constexpr const char* kVisionNames[] = {"normal", "protanopia", "deuteranopia", "tritanopia"};
constexpr Palette kPalettes[] = {Palette::OkabeIto, Palette::HighContrast, Palette::SingleHue};

// The least CIEDE2000 over pairs of colours[0 .. count), as a dichromat sees them.
struct ClosestPair {
  double delta_e = 1e9;
  std::size_t first = 0;
  std::size_t second = 0;
};
ClosestPair closest_pair(std::span<const glm::vec3> colors, std::size_t count, ColorVision vision) {
  ClosestPair closest;
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t j = i + 1; j < count; ++j) {
      const double d = ciede2000(lab_from_linear_srgb(simulate_color_vision(colors[i], vision)),
                                 lab_from_linear_srgb(simulate_color_vision(colors[j], vision)));
      if (d < closest.delta_e) closest = {d, i, j};
    }
  return closest;
}

std::uint32_t srgb_hex(glm::vec3 linear) {
  const glm::vec3 srgb = linear_to_srgb(linear);
  const auto byte = [](float c) { return static_cast<std::uint32_t>(std::lround(c * 255.0f)); };
  return byte(srgb.x) << 16 | byte(srgb.y) << 8 | byte(srgb.z);
}

// --- CIEDE2000 and CIELAB ---

// Sharma, Wu & Dalal (2005), Table 1: all 34 pairs, to the 4 decimals published.
struct SharmaPair {
  Lab first;
  Lab second;
  double delta_e;
};
const SharmaPair kSharmaPairs[] = {
    {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {{50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {{50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {{50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {{61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {{35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {{36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {{90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {{90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {{6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};

TEST(Ciede2000, MatchesSharmaTestPairs) {
  for (std::size_t i = 0; i < std::size(kSharmaPairs); ++i) {
    const SharmaPair& pair = kSharmaPairs[i];
    // Half a unit in the 4th decimal: the published rounding.
    EXPECT_NEAR(ciede2000(pair.first, pair.second), pair.delta_e, 0.5e-4) << "pair " << i + 1;
    EXPECT_NEAR(ciede2000(pair.second, pair.first), pair.delta_e, 0.5e-4) << "pair " << i + 1 << " swapped";
  }
}

TEST(Ciede2000, ZeroForEqualColours) {
  const Lab colour{61.2901, 3.7196, -5.3901};
  EXPECT_EQ(ciede2000(colour, colour), 0.0);
  EXPECT_EQ(ciede2000(Lab{}, Lab{}), 0.0);
}

TEST(Lab, WhiteBlackGreyAndRed) {
  const Lab white = lab_from_linear_srgb(glm::vec3(1.0f));
  EXPECT_NEAR(white.l, 100.0, 1e-9);
  EXPECT_NEAR(white.a, 0.0, 1e-9);
  EXPECT_NEAR(white.b, 0.0, 1e-9);
  const Lab black = lab_from_linear_srgb(glm::vec3(0.0f));
  EXPECT_NEAR(black.l, 0.0, 1e-12);
  // A neutral at Y = 0.18: L* = 116 * 0.18^(1/3) - 16 = 116 * 0.5646216 - 16 = 49.4961.
  const Lab grey = lab_from_linear_srgb(glm::vec3(0.18f));
  EXPECT_NEAR(grey.l, 49.4961, 1e-3);
  EXPECT_NEAR(grey.a, 0.0, 1e-5);
  EXPECT_NEAR(grey.b, 0.0, 1e-5);
  // sRGB red, D65: the widely published L* 53.24, a* 80.09, b* 67.20.
  const Lab red = lab_from_linear_srgb(glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_NEAR(red.l, 53.24, 0.01);
  EXPECT_NEAR(red.a, 80.09, 0.01);
  EXPECT_NEAR(red.b, 67.20, 0.01);
}

TEST(Srgb, TransferFunction) {
  // ((0.5 + 0.055) / 1.055)^2.4 = 0.5260664^2.4 = 0.2140411.
  EXPECT_NEAR(srgb_to_linear(glm::vec3(0.5f)).x, 0.2140411f, 1e-6f);
  // The linear segment: 0.04 / 12.92.
  EXPECT_NEAR(srgb_to_linear(glm::vec3(0.04f)).y, 0.04f / 12.92f, 1e-7f);
  EXPECT_EQ(srgb_to_linear(glm::vec3(0.0f)).z, 0.0f);
  EXPECT_NEAR(srgb_to_linear(glm::vec3(1.0f)).z, 1.0f, 1e-6f);
  for (int i = 0; i <= 255; ++i) {
    const float s = static_cast<float>(i) / 255.0f;
    EXPECT_NEAR(linear_to_srgb(srgb_to_linear(glm::vec3(s))).x, s, 1e-5f) << i;
  }
}

// --- Colour-vision simulation ---

TEST(ColorVision, WhiteStaysWhiteAndRedFollowsTheMatrix) {
  // Machado's matrices have rows summing to 1: neutrals are unchanged.
  for (ColorVision vision : kVisions) {
    const glm::vec3 white = simulate_color_vision(glm::vec3(1.0f), vision);
    EXPECT_NEAR(white.x, 1.0f, 1e-5f);
    EXPECT_NEAR(white.y, 1.0f, 1e-5f);
    EXPECT_NEAR(white.z, 1.0f, 1e-5f);
  }
  // Pure red gives the matrix's first column, clamped to [0, 1] (-0.003882 -> 0).
  const glm::vec3 red = simulate_color_vision(glm::vec3(1.0f, 0.0f, 0.0f), ColorVision::Protanopia);
  EXPECT_FLOAT_EQ(red.x, 0.152286f);
  EXPECT_FLOAT_EQ(red.y, 0.114503f);
  EXPECT_EQ(red.z, 0.0f);
  const glm::vec3 green = simulate_color_vision(glm::vec3(0.0f, 1.0f, 0.0f), ColorVision::Tritanopia);
  EXPECT_EQ(green.x, 0.0f);  // -0.076749, clamped
  EXPECT_FLOAT_EQ(green.y, 0.930809f);
  EXPECT_FLOAT_EQ(green.z, 0.691367f);
  const glm::vec3 some = {0.2f, 0.4f, 0.6f};
  EXPECT_EQ(simulate_color_vision(some, ColorVision::Normal), some);
}

TEST(ColorVision, CollapsesARedAndGreenADeuteranopeConfuses) {
  // #990000 and #006600 lie near one deutan confusion line: far apart for
  // normal vision, close once simulated. Proof that the palette checks below
  // can fail.
  const Lab red = lab_from_linear_srgb(srgb_to_linear(glm::vec3(0x99, 0, 0) / 255.0f));
  const Lab green = lab_from_linear_srgb(srgb_to_linear(glm::vec3(0, 0x66, 0) / 255.0f));
  EXPECT_GT(ciede2000(red, green), 50.0);
  const auto seen = [](glm::vec3 srgb) {
    return lab_from_linear_srgb(simulate_color_vision(srgb_to_linear(srgb / 255.0f), ColorVision::Deuteranopia));
  };
  EXPECT_LT(ciede2000(seen(glm::vec3(0x99, 0, 0)), seen(glm::vec3(0, 0x66, 0))), 5.0);
}

// --- Palettes ---

TEST(Palette, OkabeItoIsThePublishedSetWithWhiteForBlack) {
  const std::span<const glm::vec3> colors = palette_colors(Palette::OkabeIto);
  // Entry i is builtin_categories()[i]'s: footsteps, gunfire, voice,
  // explosion, alarm, music, machinery, door.
  const std::uint32_t expected[] = {0xFFFFFF, 0xD55E00, 0x56B4E9, 0xE69F00, 0xF0E442, 0xCC79A7, 0x0072B2, 0x009E73};
  ASSERT_GE(colors.size(), std::size(expected));
  for (std::size_t i = 0; i < std::size(expected); ++i) EXPECT_EQ(srgb_hex(colors[i]), expected[i]) << i;
}

TEST(Palette, EveryPaletteIsLongEnoughInGamutAndVisibleAgainstTheDarkHalo) {
  for (Palette palette : kPalettes) {
    const std::span<const glm::vec3> colors = palette_colors(palette);
    EXPECT_GE(colors.size(), kBuiltinCategoryCount + 1) << palette_name(palette);
    for (std::size_t i = 0; i < colors.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(colors[i][c], 0.0f);
        EXPECT_LE(colors[i][c], 1.0f);
      }
      // 3:1 against the dark ring needs (Y + 0.05) / 0.05 >= 3, i.e. Y >= 0.1.
      EXPECT_GE(contrast_ratio(relative_luminance(colors[i]), relative_luminance(kHaloDark)), 3.0f)
          << palette_name(palette) << " entry " << i;
    }
  }
}

TEST(Palette, SingleHueIsOneHue) {
  // Every entry within 3 degrees of amber's CIELAB hue (#FFBF00: 83 degrees).
  for (const glm::vec3& color : palette_colors(Palette::SingleHue)) {
    const Lab lab = lab_from_linear_srgb(color);
    EXPECT_NEAR(std::atan2(lab.b, lab.a) * 180.0 / 3.14159265358979, 83.0, 3.0) << srgb_hex(color);
  }
}

// Distinguishable: CIEDE2000 >= 10 between every two entries. 1 is about a
// just-noticeable difference for large patches side by side; discrimination
// is much poorer for small, brief marks on a busy background, above all along
// blue-yellow, so the floor is ten times that.
constexpr double kDistinguishable = 10.0;
// The single-hue palette varies lightness only and leaves the category to
// the shapes; its entries need only stay visibly different steps.
constexpr double kDistinctStep = 5.0;

TEST(Palette, EveryPairStaysDistinguishableForEveryKindOfVision) {
  for (Palette palette : kPalettes) {
    const std::span<const glm::vec3> colors = palette_colors(palette);
    for (std::size_t v = 0; v < std::size(kVisions); ++v) {
      const ClosestPair builtins = closest_pair(colors, kBuiltinCategoryCount, kVisions[v]);
      const ClosestPair all = closest_pair(colors, colors.size(), kVisions[v]);
      std::printf("%-13s %-12s built-ins: min dE00 %5.2f (%s, %s); all %zu entries: %5.2f (%zu, %zu)\n",
                  palette_name(palette), kVisionNames[v], builtins.delta_e, builtin_categories()[builtins.first].name,
                  builtin_categories()[builtins.second].name, colors.size(), all.delta_e, all.first, all.second);
      const double floor = palette == Palette::SingleHue ? kDistinctStep : kDistinguishable;
      EXPECT_GE(all.delta_e, floor) << palette_name(palette) << ", " << kVisionNames[v] << ": entries " << all.first
                                    << " and " << all.second;
    }
  }
}

// --- Halo ---

TEST(Contrast, WcagReferenceValues) {
  EXPECT_FLOAT_EQ(relative_luminance(glm::vec3(1.0f)), 1.0f);
  EXPECT_FLOAT_EQ(relative_luminance(glm::vec3(0.0f, 1.0f, 0.0f)), 0.7152f);
  EXPECT_FLOAT_EQ(contrast_ratio(1.0f, 0.0f), 21.0f);
  EXPECT_FLOAT_EQ(contrast_ratio(0.0f, 1.0f), 21.0f);
  // Grey #767676, the darkest that passes 4.5:1 on white: 118/255 = 0.46275
  // -> linear 0.18116; 1.05 / 0.23116 = 4.542.
  const float grey = relative_luminance(srgb_to_linear(glm::vec3(118.0f / 255.0f)));
  EXPECT_NEAR(contrast_ratio(grey, 1.0f), 4.542f, 2e-3f);
}

TEST(Contrast, HaloKeepsThreeToOneOnEverySurface) {
  const float dark = relative_luminance(kHaloDark);
  const float light = relative_luminance(kHaloLight);
  float worst = 1e9f;
  constexpr int kSamples = 100000;
  for (int i = 0; i <= kSamples; ++i) {
    const float surface = static_cast<float>(i) / kSamples;
    const float best_ring = std::max(contrast_ratio(surface, dark), contrast_ratio(surface, light));
    EXPECT_GE(best_ring, 3.0f) << "surface luminance " << surface;
    worst = std::min(worst, best_ring);
  }
  // Black and white rings: worst at (Y + 0.05)^2 = 0.05 * 1.05, where the
  // contrast is sqrt(21) = 4.5826.
  EXPECT_NEAR(worst, 4.5826f, 1e-3f);
  EXPECT_NEAR(halo_worst_case_contrast(), 4.5826f, 1e-4f);
}

// --- Names ---

TEST(Names, ShapesRoundTrip) {
  const char* names[] = {"disc", "ring", "diamond", "cross", "plus", "triangle", "square", "star", "hexagon", "clover"};
  ASSERT_EQ(std::size(names), kShapeCount);
  for (std::uint32_t id = 0; id < kShapeCount; ++id) {
    EXPECT_STREQ(shape_name(Shape(id)), names[id]);
    EXPECT_EQ(shape_from_name(names[id]), Shape(id));
  }
  EXPECT_EQ(shape_from_name("circle"), std::nullopt);
  EXPECT_EQ(shape_from_name("Disc"), std::nullopt);
  EXPECT_EQ(shape_from_name(""), std::nullopt);
  EXPECT_STREQ(shape_name(Shape(kShapeCount)), "unknown");
}

TEST(Names, PalettesRoundTrip) {
  EXPECT_STREQ(palette_name(Palette::OkabeIto), "okabe-ito");
  EXPECT_STREQ(palette_name(Palette::HighContrast), "high-contrast");
  EXPECT_STREQ(palette_name(Palette::SingleHue), "single-hue");
  for (Palette palette : kPalettes) EXPECT_EQ(palette_from_name(palette_name(palette)), palette);
  EXPECT_EQ(palette_from_name("okabe_ito"), std::nullopt);
  EXPECT_EQ(palette_from_name("viridis"), std::nullopt);
}

// --- Categories ---

TEST(Categories, BuiltinsHaveTheirShapesAndEntries) {
  const std::span<const BuiltinCategory> builtins = builtin_categories();
  ASSERT_EQ(builtins.size(), 8u);
  const std::string names[] = {"footsteps", "gunfire", "voice", "explosion", "alarm", "music", "machinery", "door"};
  const Shape shapes[] = {Shape::Diamond,  Shape::Cross,  Shape::Ring,    Shape::Star,
                          Shape::Triangle, Shape::Clover, Shape::Hexagon, Shape::Square};
  for (std::uint32_t i = 0; i < builtins.size(); ++i) {
    EXPECT_EQ(builtins[i].name, names[i]);
    EXPECT_EQ(builtins[i].shape, shapes[i]) << names[i];
    EXPECT_EQ(builtins[i].palette_entry, i) << names[i];
  }
}

TEST(Categories, BuiltinsFirstThenOthersInOrderOfAppearance) {
  CategoryTable table;
  EXPECT_EQ(table.size(), 8u);
  EXPECT_EQ(table.index_of("gunfire"), 1u);
  EXPECT_EQ(table.index_of("door"), 7u);
  EXPECT_EQ(table.index_of("sound"), 8u);
  EXPECT_EQ(table.index_of("ambience"), 9u);
  EXPECT_EQ(table.index_of("sound"), 8u);   // known: not added again
  EXPECT_EQ(table.index_of("Sound"), 10u);  // names match exactly
  EXPECT_EQ(table.size(), 11u);
  EXPECT_EQ(table.name(9), "ambience");
  EXPECT_EQ(table.name(0), "footsteps");
}

TEST(Categories, OthersTakeTheEntriesAfterTheBuiltinsThenCycle) {
  // Built-ins keep their own entries whatever the palette's size.
  for (std::uint32_t i = 0; i < 8; ++i) EXPECT_EQ(palette_entry_of(i, 9), i);
  // A palette of 11: others 8, 9, 10 take entries 8, 9, 10; the fourth other
  // (index 11) starts over at 0, the fifth takes 1.
  EXPECT_EQ(palette_entry_of(8, 11), 8u);
  EXPECT_EQ(palette_entry_of(10, 11), 10u);
  EXPECT_EQ(palette_entry_of(11, 11), 0u);
  EXPECT_EQ(palette_entry_of(12, 11), 1u);
  EXPECT_EQ(palette_entry_of(22, 11), 0u);
  // A palette of 9: one entry for others, then 0, 1, ...
  EXPECT_EQ(palette_entry_of(8, 9), 8u);
  EXPECT_EQ(palette_entry_of(9, 9), 0u);
  EXPECT_EQ(palette_entry_of(10, 9), 1u);

  const std::span<const glm::vec3> okabe_ito = palette_colors(Palette::OkabeIto);
  EXPECT_EQ(srgb_hex(category_color(1, Palette::OkabeIto)), 0xD55E00u);  // gunfire: vermillion
  EXPECT_EQ(category_color(8, Palette::OkabeIto), okabe_ito[8]);
  EXPECT_EQ(category_color(static_cast<std::uint32_t>(okabe_ito.size()), Palette::OkabeIto), okabe_ito[0]);
}

TEST(Categories, ShapeOverridesWinThenBuiltinsThenDisc) {
  CategoryTable table;
  const std::uint32_t sound = table.index_of("sound");
  const std::uint32_t radio = table.index_of("radio");
  const std::map<std::string, Shape> none;
  EXPECT_EQ(table.shape_of(table.index_of("footsteps"), none), Shape::Diamond);
  EXPECT_EQ(table.shape_of(table.index_of("voice"), none), Shape::Ring);
  EXPECT_EQ(table.shape_of(sound, none), Shape::Disc);
  const std::map<std::string, Shape> overrides = {{"sound", Shape::Star}, {"gunfire", Shape::Plus}};
  EXPECT_EQ(table.shape_of(sound, overrides), Shape::Star);
  EXPECT_EQ(table.shape_of(table.index_of("gunfire"), overrides), Shape::Plus);
  EXPECT_EQ(table.shape_of(table.index_of("explosion"), overrides), Shape::Star);
  EXPECT_EQ(table.shape_of(radio, overrides), Shape::Disc);
}

// "c<i>", built by appending: GCC 12's -Wrestrict misfires on "c" + std::to_string(i).
std::string numbered_name(std::size_t i) {
  std::string name = "c";
  name += std::to_string(i);
  return name;
}

// Numbering many names keeps first-appearance order and finds each again
// (the table is hashed: 10,000 names is what a world of 10,000 sources with
// their own categories needs).
TEST(Categories, ThousandsOfNamesKeepTheirNumbers) {
  CategoryTable table;
  for (std::uint32_t i = 0; i < 10000; ++i) ASSERT_EQ(table.index_of(numbered_name(i)), 8u + i);
  EXPECT_EQ(table.size(), 10008u);
  for (std::uint32_t i = 0; i < 10000; i += 997) {
    EXPECT_EQ(table.index_of(numbered_name(i)), 8u + i);
    EXPECT_EQ(table.name(8u + i), numbered_name(i));
  }
  EXPECT_EQ(table.index_of("alarm"), 4u);
  EXPECT_EQ(table.size(), 10008u);
  // A copy numbers on by itself.
  CategoryTable copy = table;
  EXPECT_EQ(copy.index_of("new"), 10008u);
  EXPECT_EQ(copy.index_of("c5"), 13u);
  EXPECT_EQ(table.size(), 10008u);
}

// --- Display checks (settings made in code: make_world, set_display) ---

std::string check_error(const DisplaySettings& settings) {
  try {
    check_display_settings(settings);
  } catch (const Exception& e) {
    EXPECT_EQ(e.error().code, ErrorCode::InvalidConfig);
    return e.what();
  }
  return "";
}

std::vector<std::string> numbered_names(std::size_t count) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < count; ++i) names.push_back(numbered_name(i));
  return names;
}

TEST(DisplayChecks, CategoryListsHoldAtMostTheirLimit) {
  DisplaySettings settings;
  settings.hide_categories = numbered_names(kMaxDisplayCategories);
  for (const std::string& name : numbered_names(kMaxDisplayCategories)) settings.shapes[name] = Shape::Star;
  EXPECT_EQ(check_error(settings), "");
  settings.hide_categories.push_back("one more");
  EXPECT_EQ(check_error(settings), "display.hide_categories has 4097 entries, at most 4096");
  settings.hide_categories.pop_back();
  settings.shapes["one more"] = Shape::Ring;
  EXPECT_EQ(check_error(settings), "display.shapes has 4097 entries, at most 4096");
}

TEST(DisplayChecks, CategoryNamesHaveAtMost256Bytes) {
  DisplaySettings settings;
  settings.hide_categories = {"footsteps", std::string(256, 'x')};
  settings.shapes[std::string(256, 'y')] = Shape::Star;
  EXPECT_EQ(check_error(settings), "");
  settings.hide_categories.push_back(std::string(257, 'x'));
  EXPECT_EQ(check_error(settings), "display.hide_categories[2] is 257 bytes long, at most 256");
  settings.hide_categories.pop_back();
  settings.shapes[std::string(100000, 'z')] = Shape::Star;
  EXPECT_EQ(check_error(settings), "display.shapes has a category name 100000 bytes long, at most 256");
}

}  // namespace
}  // namespace sp
