// The indicator shapes (shaders/shared/sp_shapes.h) compiled as C++ and
// rasterised as the fragment shader draws them: each fits the unit disc,
// weighs about the same as the others, keeps its strokes, is an exact
// distance, and differs from every other shape under any rotation (the
// spot's frame turns with the sound's direction) from SP_SHAPE_MIN_PIXELS up.
// Also writes a contact sheet of all shapes for people to judge.
//
// "Differs" is measured twice:
//  - geometry: the Hausdorff distance between two outlines at their
//    best-matching rotation, i.e. the largest feature one shape has and the
//    other lacks, must be a whole pixel at the minimum size;
//  - pixels: at the minimum size and above, two coverage masks, whatever
//    their rotation, differ by half a pixel's coverage in at least 2 pixels,
//    and in at least 12% of their union (intersection over union <= 0.88).
//    A bound of 0.75 cannot hold: equal-area convex shapes overlap more than
//    that at any size (the disc and the square: 0.84).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sp_shapes.h"

// The contact sheet is a PNG when the test is built with stb's include
// directory and library, a binary PGM otherwise.
#if __has_include(<stb_image_write.h>)
#include <stb_image_write.h>

#include <glm/glm.hpp>
#define SP_CONTACT_SHEET_PNG 1
#endif

namespace {

using sp::shader::sp_shape_distance;
using sp::shader::vec2;
using Shape = std::uint32_t;

constexpr std::array<const char*, SP_SHAPE_COUNT> kShapeNames = {"disc",     "ring",   "diamond", "cross",   "plus",
                                                                 "triangle", "square", "star",    "hexagon", "clover"};
constexpr float kPi = SP_PI;
constexpr float kDegree = kPi / 180.0f;
// The minimum size and above (larger ones only have more pixels to differ by).
constexpr std::array<int, 3> kCheckedDiameters = {static_cast<int>(SP_SHAPE_MIN_PIXELS), 24, 48};

vec2 turned(vec2 p, float radians) {
  float c = std::cos(radians), s = std::sin(radians);
  return vec2(c * p.x - s * p.y, s * p.x + c * p.y);
}

// Distance to `shape` drawn turned by `radians` on screen.
float turned_distance(Shape shape, vec2 p, float radians) { return sp_shape_distance(shape, turned(p, -radians)); }

// Coverage of each pixel of a diameter_px square around the spot, from 4x4
// samples per pixel (the fragment shader's anti-aliasing covers the same).
struct Mask {
  int size = 0;
  std::vector<float> coverage;  // row-major, +y up
  float at(int x, int y) const { return coverage[static_cast<std::size_t>(y * size + x)]; }
};

Mask rasterise(Shape shape, int diameter_px, float radians = 0.0f) {
  constexpr int kSub = 4;
  Mask mask{diameter_px, std::vector<float>(static_cast<std::size_t>(diameter_px * diameter_px))};
  for (int y = 0; y < diameter_px; ++y) {
    for (int x = 0; x < diameter_px; ++x) {
      int inside = 0;
      for (int j = 0; j < kSub; ++j) {
        for (int i = 0; i < kSub; ++i) {
          vec2 p = vec2(static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / kSub,
                        static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / kSub) *
                       (2.0f / static_cast<float>(diameter_px)) -
                   vec2(1.0f);
          inside += turned_distance(shape, p, radians) <= 0.0f ? 1 : 0;
        }
      }
      mask.coverage[static_cast<std::size_t>(y * diameter_px + x)] = static_cast<float>(inside) / (kSub * kSub);
    }
  }
  return mask;
}

float covered_pixels(const Mask& mask) {
  float sum = 0.0f;
  for (float c : mask.coverage) sum += c;
  return sum;
}

float intersection_over_union(const Mask& a, const Mask& b) {
  float both = 0.0f, either = 0.0f;
  for (std::size_t k = 0; k < a.coverage.size(); ++k) {
    both += std::min(a.coverage[k], b.coverage[k]);
    either += std::max(a.coverage[k], b.coverage[k]);
  }
  return both / either;
}

int pixels_differing_by_half(const Mask& a, const Mask& b) {
  int count = 0;
  for (std::size_t k = 0; k < a.coverage.size(); ++k) count += std::abs(a.coverage[k] - b.coverage[k]) >= 0.5f ? 1 : 0;
  return count;
}

// Points on the outline: where the inside test changes between neighbours
// of a fine grid, found by bisection (so they rely on the sign alone).
std::vector<vec2> outline_points(Shape shape) {
  constexpr int kSteps = 250;
  constexpr float kExtent = 1.1f;
  const float step = 2.0f * kExtent / kSteps;
  auto inside = [shape](vec2 p) { return sp_shape_distance(shape, p) <= 0.0f; };
  std::vector<vec2> points;
  for (int j = 0; j < kSteps; ++j) {
    for (int i = 0; i < kSteps; ++i) {
      vec2 p = vec2(-kExtent) + step * vec2(static_cast<float>(i), static_cast<float>(j));
      for (vec2 neighbour : {p + vec2(step, 0.0f), p + vec2(0.0f, step)}) {
        if (inside(p) == inside(neighbour)) continue;
        vec2 in = inside(p) ? p : neighbour, out = inside(p) ? neighbour : p;
        for (int k = 0; k < 24; ++k) {
          vec2 mid = 0.5f * (in + out);
          (inside(mid) ? in : out) = mid;
        }
        points.push_back(0.5f * (in + out));
      }
    }
  }
  return points;
}

// Hausdorff distance between the outlines of a and of b turned by `radians`.
// The distance functions are 1-Lipschitz (ExactDistances checks), so this
// never overstates the true one.
float outline_gap(Shape a, const std::vector<vec2>& outline_a, Shape b, const std::vector<vec2>& outline_b,
                  float radians) {
  float gap = 0.0f;
  for (vec2 p : outline_a) gap = std::max(gap, std::abs(turned_distance(b, p, radians)));
  for (vec2 p : outline_b) gap = std::max(gap, std::abs(sp_shape_distance(a, turned(p, radians))));
  return gap;
}

// The gap at the best-matching rotation: every 3 degrees, then refined.
float outline_gap_any_rotation(Shape a, const std::vector<vec2>& outline_a, Shape b,
                               const std::vector<vec2>& outline_b) {
  float best = 1e9f, best_radians = 0.0f;
  for (int k = 0; k < 120; ++k) {
    float radians = static_cast<float>(3 * k) * kDegree;
    float gap = outline_gap(a, outline_a, b, outline_b, radians);
    if (gap < best) best = gap, best_radians = radians;
  }
  for (int k = -30; k <= 30; ++k) {
    best =
        std::min(best, outline_gap(a, outline_a, b, outline_b, best_radians + static_cast<float>(k) * 0.1f * kDegree));
  }
  return best;
}

std::string pair_name(Shape a, Shape b) { return std::string(kShapeNames[a]) + "/" + kShapeNames[b]; }

TEST(Shapes, HandDerivedSigns) {
  struct Probe {
    Shape shape;
    vec2 p;
    bool inside;
  };
  const float c60 = 0.5f, s60 = 0.8660254f;
  const Probe probes[] = {
      {SP_SHAPE_DISC, vec2(0.0f), true},
      {SP_SHAPE_DISC, vec2(0.55f, 0.0f), true},
      {SP_SHAPE_DISC, vec2(0.0f, -0.65f), false},
      {SP_SHAPE_DISC, vec2(1.1f, 0.0f), false},
      {SP_SHAPE_RING, vec2(0.0f), false},
      {SP_SHAPE_RING, vec2(0.3f, 0.0f), false},  // the hole
      {SP_SHAPE_RING, vec2(0.0f, 0.59f), true},
      {SP_SHAPE_RING, vec2(0.9f, 0.0f), false},
      {SP_SHAPE_DIAMOND, vec2(0.9f, 0.0f), true},  // long along the travel direction
      {SP_SHAPE_DIAMOND, vec2(0.0f, 0.6f), true},
      {SP_SHAPE_DIAMOND, vec2(0.0f, 0.7f), false},
      {SP_SHAPE_DIAMOND, vec2(0.5f, 0.5f), false},
      {SP_SHAPE_CROSS, vec2(0.0f), true},
      {SP_SHAPE_CROSS, 0.8f * vec2(c60, s60), true},  // on an arm
      {SP_SHAPE_CROSS, vec2(0.8f, 0.0f), false},
      {SP_SHAPE_CROSS, vec2(0.0f, -0.8f), false},  // between arms
      {SP_SHAPE_PLUS, vec2(0.0f), true},
      {SP_SHAPE_PLUS, vec2(0.7f, 0.0f), true},
      {SP_SHAPE_PLUS, vec2(0.0f, -0.7f), true},
      {SP_SHAPE_PLUS, vec2(0.5f, 0.5f), false},
      {SP_SHAPE_TRIANGLE, vec2(0.0f), true},
      {SP_SHAPE_TRIANGLE, vec2(0.95f, 0.0f), true},  // the tip
      {SP_SHAPE_TRIANGLE, vec2(-0.45f, 0.0f), true},
      {SP_SHAPE_TRIANGLE, vec2(-0.55f, 0.0f), false},  // the base
      {SP_SHAPE_TRIANGLE, vec2(0.0f, 0.8f), false},
      {SP_SHAPE_SQUARE, vec2(0.55f, 0.55f), true},
      {SP_SHAPE_SQUARE, vec2(0.6f, 0.0f), false},
      {SP_SHAPE_STAR, vec2(0.0f), true},
      {SP_SHAPE_STAR, vec2(0.9f, 0.0f), true},                     // a point
      {SP_SHAPE_STAR, 0.6f * vec2(0.809017f, 0.5877853f), false},  // between two points
      {SP_SHAPE_HEXAGON, vec2(0.0f), true},
      {SP_SHAPE_HEXAGON, vec2(0.7f, 0.0f), true},    // a corner
      {SP_SHAPE_HEXAGON, vec2(0.0f, 0.66f), false},  // beyond a flat side
      {SP_SHAPE_CLOVER, vec2(0.0f), false},
      {SP_SHAPE_CLOVER, vec2(-0.62f, 0.0f), true},  // the back lobe
      {SP_SHAPE_CLOVER, 0.62f * vec2(c60, s60), true},
      {SP_SHAPE_CLOVER, vec2(0.62f, 0.0f), false},
  };
  for (const Probe& probe : probes) {
    float d = sp_shape_distance(probe.shape, probe.p);
    EXPECT_EQ(d < 0.0f, probe.inside) << kShapeNames[probe.shape] << " at (" << probe.p.x << ", " << probe.p.y
                                      << "): distance " << d;
  }
  EXPECT_EQ(sp_shape_distance(SP_SHAPE_COUNT, vec2(0.3f)), sp_shape_distance(SP_SHAPE_DISC, vec2(0.3f)))
      << "unknown ids draw as discs";
}

// 1-Lipschitz everywhere, and where the distance is differentiable (all but
// the medial axis), a unit gradient whose step lands on the outline.
TEST(Shapes, ExactDistances) {
  constexpr float kStep = 0.013f, kE = 1e-3f;
  for (Shape shape = 0; shape < SP_SHAPE_COUNT; ++shape) {
    int near_outline = 0, exact = 0;
    for (float y = -1.2f; y <= 1.2f; y += kStep) {
      for (float x = -1.2f; x <= 1.2f; x += kStep) {
        vec2 p(x, y);
        float d = sp_shape_distance(shape, p);
        for (vec2 q : {p + vec2(kStep, 0.0f), p + vec2(0.0f, kStep), p + vec2(kStep)}) {
          ASSERT_LE(std::abs(sp_shape_distance(shape, q) - d), glm::length(q - p) * 1.0001f + 1e-6f)
              << kShapeNames[shape] << " at (" << x << ", " << y << ")";
        }
        if (std::abs(d) > 0.3f) continue;
        ++near_outline;
        vec2 gradient =
            vec2(sp_shape_distance(shape, p + vec2(kE, 0.0f)) - sp_shape_distance(shape, p - vec2(kE, 0.0f)),
                 sp_shape_distance(shape, p + vec2(0.0f, kE)) - sp_shape_distance(shape, p - vec2(0.0f, kE))) /
            (2.0f * kE);
        bool unit = std::abs(glm::length(gradient) - 1.0f) < 0.01f;
        bool lands = std::abs(sp_shape_distance(shape, p - gradient * d)) < 2e-3f;
        exact += unit && lands ? 1 : 0;
      }
    }
    // Samples within kE of the medial axis see a kink instead of a gradient.
    EXPECT_GE(exact, near_outline * 99 / 100) << kShapeNames[shape] << ": " << exact << " of " << near_outline;
  }
}

TEST(Shapes, FitTheDiscWithTheSameWeight) {
  // A fine grid: nothing inside beyond the rim (SP_RIM_RADIUS, plus the
  // grid's half cell), the area within 10% of SP_SHAPE_AREA_SHARE (plus the
  // grid's own error, < 0.5%).
  constexpr int kSteps = 800;
  for (Shape shape = 0; shape < SP_SHAPE_COUNT; ++shape) {
    int inside = 0;
    for (int j = 0; j < kSteps; ++j) {
      for (int i = 0; i < kSteps; ++i) {
        vec2 p = (vec2(static_cast<float>(i), static_cast<float>(j)) + 0.5f) * (2.0f / kSteps) - vec2(1.0f);
        if (sp_shape_distance(shape, p) > 0.0f) continue;
        ++inside;
        ASSERT_LE(glm::length(p), SP_RIM_RADIUS + 0.005f) << kShapeNames[shape];
      }
    }
    float share = static_cast<float>(inside) * 4.0f / (kSteps * kSteps) / kPi;
    EXPECT_GE(share, 0.9f * SP_SHAPE_AREA_SHARE - 0.005f) << kShapeNames[shape];
    EXPECT_LE(share, 1.1f * SP_SHAPE_AREA_SHARE + 0.005f) << kShapeNames[shape];
  }
  // Drawn small, each keeps its weight: coverage between 0.32 and 0.48 of the disc.
  for (int diameter : {12, 16, 24, 48}) {
    for (Shape shape = 0; shape < SP_SHAPE_COUNT; ++shape) {
      float share = covered_pixels(rasterise(shape, diameter)) / (kPi * static_cast<float>(diameter * diameter) / 4.0f);
      EXPECT_GE(share, 0.32f) << kShapeNames[shape] << " at " << diameter << " px";
      EXPECT_LE(share, 0.48f) << kShapeNames[shape] << " at " << diameter << " px";
    }
  }
}

// The vertex shader sizes each spot's quad to sp_shape_extent: nothing of
// the shape may lie beyond it (it would be cut off), and it must be tight
// (a loose extent only costs fill). An unknown id is drawn as the disc, and
// must be sized as one.
TEST(Shapes, ExtentHoldsTheShapeTightly) {
  using sp::shader::sp_shape_extent;
  constexpr int kSteps = 800;
  for (Shape shape = 0; shape <= SP_SHAPE_COUNT; ++shape) {
    const float extent = sp_shape_extent(shape);
    ASSERT_GT(extent, 0.5f);
    ASSERT_LE(extent, SP_RIM_RADIUS);
    float farthest = 0.0f;
    for (int j = 0; j < kSteps; ++j) {
      for (int i = 0; i < kSteps; ++i) {
        vec2 p = (vec2(static_cast<float>(i), static_cast<float>(j)) + 0.5f) * (2.0f / kSteps) - vec2(1.0f);
        if (sp_shape_distance(shape, p) <= 0.0f) farthest = std::max(farthest, glm::length(p));
      }
    }
    const char* name = shape < SP_SHAPE_COUNT ? kShapeNames[shape] : "unknown id";
    EXPECT_LE(farthest, extent + 1e-4f) << name << " reaches beyond its extent";
    EXPECT_GE(farthest, extent - 2.0f * 2.0f / kSteps) << name << ": extent " << extent << ", shape " << farthest;
  }
  EXPECT_EQ(sp_shape_extent(SP_SHAPE_COUNT + 7), sp_shape_extent(SP_SHAPE_DISC));
}

// Width of the run of inside points through `centre` along `direction`.
float stroke_width(Shape shape, vec2 centre, vec2 direction) {
  constexpr float kStep = 1e-4f;
  float width = 0.0f;
  for (float sign : {1.0f, -1.0f}) {
    for (float t = 0.0f; sp_shape_distance(shape, centre + direction * (sign * t)) <= 0.0f; t += kStep) width += kStep;
  }
  return width;
}

TEST(Shapes, StrokesStayThick) {
  static_assert(SP_SHAPE_STROKE * SP_SHAPE_MIN_PIXELS / 2.0f >= 2.0f, "strokes of at least 2 px at the minimum size");
  const float tolerance = 1e-3f;
  for (float degrees : {0.0f, 45.0f, 100.0f, 200.0f}) {
    vec2 out = turned(vec2(1.0f, 0.0f), degrees * kDegree);
    float mid = 0.5f * SP_SHAPE_AREA_SHARE / SP_SHAPE_STROKE;  // the ring's middle, where its area puts it
    EXPECT_NEAR(stroke_width(SP_SHAPE_RING, mid * out, out), SP_SHAPE_STROKE, tolerance) << degrees;
  }
  vec2 arm = turned(vec2(1.0f, 0.0f), 60.0f * kDegree);
  EXPECT_NEAR(stroke_width(SP_SHAPE_CROSS, 0.6f * arm, turned(arm, 90.0f * kDegree)), SP_SHAPE_STROKE, tolerance);
  for (vec2 across : {vec2(0.0f, 1.0f), vec2(1.0f, 0.0f)}) {
    vec2 along = vec2(across.y, across.x);
    EXPECT_GE(stroke_width(SP_SHAPE_PLUS, 0.6f * along, across), SP_SHAPE_STROKE);
  }
}

TEST(Shapes, TrianglePointsAlongTheSound) {
  Mask mask = rasterise(SP_SHAPE_TRIANGLE, 48);
  Mask mirrored = mask;
  int leftmost = mask.size, rightmost = -1;
  for (int y = 0; y < mask.size; ++y) {
    for (int x = 0; x < mask.size; ++x) {
      mirrored.coverage[static_cast<std::size_t>(y * mask.size + x)] = mask.at(mask.size - 1 - x, y);
      if (mask.at(x, y) > 0.0f) leftmost = std::min(leftmost, x), rightmost = std::max(rightmost, x);
    }
  }
  EXPECT_LE(intersection_over_union(mask, mirrored), 0.6f) << "not symmetric under x -> -x";
  float ahead = static_cast<float>(rightmost + 1) - 24.0f, behind = 24.0f - static_cast<float>(leftmost);
  EXPECT_GT(ahead, 1.5f * behind) << "the tip is on +x, the base behind the centre";
}

// The minimum size is where every pair, at its best-matching rotation,
// differs by a whole pixel: 2 / (smallest outline gap) pixels of diameter.
TEST(Shapes, MinimumSizeIsMeasured) {
  std::vector<std::vector<vec2>> outlines;
  for (Shape shape = 0; shape < SP_SHAPE_COUNT; ++shape) outlines.push_back(outline_points(shape));
  float smallest = 1e9f;
  std::string closest;
  for (Shape a = 0; a < SP_SHAPE_COUNT; ++a) {
    for (Shape b = a + 1; b < SP_SHAPE_COUNT; ++b) {
      float gap = outline_gap_any_rotation(a, outlines[a], b, outlines[b]);
      std::printf("%-17s outline gap %.3f of the radius: a pixel from %.1f px\n", pair_name(a, b).c_str(), gap,
                  2.0f / gap);
      if (gap < smallest) smallest = gap, closest = pair_name(a, b);
    }
  }
  float measured = 2.0f / smallest;
  std::printf("closest pair %s: the minimum size is %.1f px\n", closest.c_str(), measured);
  EXPECT_EQ(SP_SHAPE_MIN_PIXELS, std::ceil(measured)) << "update SP_SHAPE_MIN_PIXELS: closest pair " << closest;
}

TEST(Shapes, MasksDifferUnderAnyRotation) {
  constexpr int kTurns = 72;  // every 5 degrees
  for (int diameter : kCheckedDiameters) {
    std::vector<Mask> upright;
    std::vector<std::vector<Mask>> turns(SP_SHAPE_COUNT);
    for (Shape shape = 0; shape < SP_SHAPE_COUNT; ++shape) {
      upright.push_back(rasterise(shape, diameter));
      ASSERT_GT(covered_pixels(upright.back()), 0.0f);
      for (int k = 0; k < kTurns; ++k) {
        turns[shape].push_back(rasterise(shape, diameter, static_cast<float>(k) * 2.0f * kPi / kTurns));
      }
    }
    float worst_overlap = 0.0f;
    int fewest_differing = diameter * diameter;
    for (Shape a = 0; a < SP_SHAPE_COUNT; ++a) {
      for (Shape b = a + 1; b < SP_SHAPE_COUNT; ++b) {
        for (const Mask& turned_b : turns[b]) {
          float overlap = intersection_over_union(upright[a], turned_b);
          int differing = pixels_differing_by_half(upright[a], turned_b);
          worst_overlap = std::max(worst_overlap, overlap);
          fewest_differing = std::min(fewest_differing, differing);
          ASSERT_LE(overlap, 0.88f) << pair_name(a, b) << " at " << diameter << " px";
          ASSERT_GE(differing, 2) << pair_name(a, b) << " at " << diameter << " px";
        }
      }
    }
    std::printf("%2d px: largest overlap %.2f, fewest pixels differing by half %d\n", diameter, worst_overlap,
                fewest_differing);
  }
}

// Sizes 12, 16, 24 and 48 px, upright and turned by 30 degrees; one column
// per shape in id order. Written at 1:1 (what a player sees) and at 4x.
TEST(Shapes, ContactSheet) {
  constexpr std::array<int, 4> kDiameters = {12, 16, 24, 48};
  constexpr int kCell = 56, kScale = 4;
  const int width = kCell * static_cast<int>(SP_SHAPE_COUNT), height = kCell * 2 * static_cast<int>(kDiameters.size());
  std::vector<std::uint8_t> sheet(static_cast<std::size_t>(width * height), 32);
  for (int block = 0; block < 2; ++block) {
    for (std::size_t row = 0; row < kDiameters.size(); ++row) {
      int diameter = kDiameters[row];
      for (Shape shape = 0; shape < SP_SHAPE_COUNT; ++shape) {
        Mask mask = rasterise(shape, diameter, static_cast<float>(block) * 30.0f * kDegree);
        int left = static_cast<int>(shape) * kCell + (kCell - diameter) / 2;
        int top =
            (block * static_cast<int>(kDiameters.size()) + static_cast<int>(row)) * kCell + (kCell - diameter) / 2;
        for (int y = 0; y < diameter; ++y) {
          for (int x = 0; x < diameter; ++x) {  // image rows run down, +y runs up
            sheet[static_cast<std::size_t>((top + diameter - 1 - y) * width + left + x)] =
                static_cast<std::uint8_t>(32.0f + 223.0f * mask.at(x, y));
          }
        }
      }
    }
  }
  std::vector<std::uint8_t> zoomed(sheet.size() * kScale * kScale);
  for (int y = 0; y < height * kScale; ++y) {
    for (int x = 0; x < width * kScale; ++x) {
      zoomed[static_cast<std::size_t>(y * width * kScale + x)] =
          sheet[static_cast<std::size_t>(y / kScale * width + x / kScale)];
    }
  }
#ifdef SP_TEST_OUTPUT_DIR
  const std::filesystem::path dir = SP_TEST_OUTPUT_DIR;
#else
  const std::filesystem::path dir = std::filesystem::current_path();  // ctest runs tests in their binary dir
#endif
  auto write = [&dir](const std::string& name, const std::vector<std::uint8_t>& grey, int w, int h) {
#ifdef SP_CONTACT_SHEET_PNG
    std::filesystem::path path = dir / (name + ".png");
    EXPECT_NE(stbi_write_png(path.string().c_str(), w, h, 1, grey.data(), w), 0) << path;
#else
    std::filesystem::path path = dir / (name + ".pgm");
    std::FILE* file = std::fopen(path.string().c_str(), "wb");
    ASSERT_NE(file, nullptr) << path;
    std::fprintf(file, "P5\n%d %d\n255\n", w, h);
    EXPECT_EQ(std::fwrite(grey.data(), 1, grey.size(), file), grey.size()) << path;
    std::fclose(file);
#endif
    EXPECT_GT(std::filesystem::file_size(path), 0u) << path;
    std::printf("contact sheet: %s\n", path.string().c_str());
  };
  write("shapes_contact_sheet", sheet, width, height);
  write("shapes_contact_sheet_x4", zoomed, width * kScale, height * kScale);
}

}  // namespace
