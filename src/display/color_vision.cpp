// Colour-vision-deficiency simulation, CIELAB and CIEDE2000.
//
// G. M. Machado, M. M. Oliveira and L. A. F. Fernandes, "A Physiologically-
// based Model for Simulation of Color Vision Deficiency", IEEE Transactions
// on Visualization and Computer Graphics 15(6), 2009, pp. 1291-1298: the
// severity-1.0 matrices for protanopia, deuteranopia and tritanopia, which
// act on linear RGB.
//
// G. Sharma, W. Wu and E. N. Dalal, "The CIEDE2000 Color-Difference Formula:
// Implementation Notes, Supplementary Test Data, and Mathematical
// Observations", Color Research and Application 30(1), 2005, pp. 21-30: the
// formula as implemented here, with its notes on hue at zero chroma and
// across 0/360 degrees; tests/test_palette.cpp checks its test pairs.
//
// CIE 15:2004 (Colorimetry) for L*a*b*; IEC 61966-2-1 for the sRGB primaries.
#include "display/color_vision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace sp {
namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;  // rows

constexpr Matrix3 kProtanopia = {{
    {0.152286, 1.052583, -0.204868},
    {0.114503, 0.786281, 0.099216},
    {-0.003882, -0.048116, 1.051998},
}};
constexpr Matrix3 kDeuteranopia = {{
    {0.367322, 0.860646, -0.227968},
    {0.280085, 0.672501, 0.047413},
    {-0.011820, 0.042940, 0.968881},
}};
constexpr Matrix3 kTritanopia = {{
    {1.255528, -0.076749, -0.178779},
    {-0.078411, 0.930809, 0.147602},
    {0.004733, 0.691367, 0.303900},
}};

// Linear sRGB to CIE XYZ (D65), IEC 61966-2-1.
constexpr Matrix3 kSrgbToXyz = {{
    {0.4124564, 0.3575761, 0.1804375},
    {0.2126729, 0.7151522, 0.0721750},
    {0.0193339, 0.1191920, 0.9503041},
}};

std::array<double, 3> multiply(const Matrix3& m, const std::array<double, 3>& v) {
  std::array<double, 3> out{};
  for (std::size_t row = 0; row < 3; ++row) out[row] = m[row][0] * v[0] + m[row][1] * v[1] + m[row][2] * v[2];
  return out;
}

std::array<double, 3> to_array(glm::vec3 v) { return {v.x, v.y, v.z}; }

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// CIELAB's compressive function, with its linear segment near black.
double lab_f(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

// Hue angle in degrees, [0, 360); 0 where a and b are both 0 (Sharma eq. 7).
double hue_degrees(double b, double a) {
  if (a == 0.0 && b == 0.0) return 0.0;
  const double h = std::atan2(b, a) * 180.0 / std::numbers::pi;
  return h < 0.0 ? h + 360.0 : h;
}

// The chroma weight shared by G and R_C: sqrt(C^7 / (C^7 + 25^7)).
double chroma_weight(double chroma) {
  const double c7 = std::pow(chroma, 7.0);
  return std::sqrt(c7 / (c7 + std::pow(25.0, 7.0)));
}

}  // namespace

glm::vec3 simulate_color_vision(glm::vec3 linear_rgb, ColorVision vision) {
  const Matrix3* matrix = nullptr;
  switch (vision) {
    case ColorVision::Normal:
      return linear_rgb;
    case ColorVision::Protanopia:
      matrix = &kProtanopia;
      break;
    case ColorVision::Deuteranopia:
      matrix = &kDeuteranopia;
      break;
    case ColorVision::Tritanopia:
      matrix = &kTritanopia;
      break;
  }
  const std::array<double, 3> seen = multiply(*matrix, to_array(linear_rgb));
  const auto shown = [](double c) { return static_cast<float>(std::clamp(c, 0.0, 1.0)); };
  return {shown(seen[0]), shown(seen[1]), shown(seen[2])};
}

Lab lab_from_linear_srgb(glm::vec3 linear_rgb) {
  // The white point is the XYZ of RGB white, the matrix's row sums (D65 to
  // the matrix's precision), so that white has a* = b* = 0 exactly.
  const std::array<double, 3> white = multiply(kSrgbToXyz, {1.0, 1.0, 1.0});
  const std::array<double, 3> xyz = multiply(kSrgbToXyz, to_array(linear_rgb));
  const double fx = lab_f(xyz[0] / white[0]);
  const double fy = lab_f(xyz[1] / white[1]);
  const double fz = lab_f(xyz[2] / white[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ciede2000(const Lab& first, const Lab& second) {
  // Sharma et al. eqs. 2-4: a* stretched for neutral colours.
  const double mean_chroma = (std::hypot(first.a, first.b) + std::hypot(second.a, second.b)) / 2.0;
  const double g = 0.5 * (1.0 - chroma_weight(mean_chroma));
  const double a1 = (1.0 + g) * first.a;
  const double a2 = (1.0 + g) * second.a;
  const double c1 = std::hypot(a1, first.b);
  const double c2 = std::hypot(a2, second.b);
  const double h1 = hue_degrees(first.b, a1);
  const double h2 = hue_degrees(second.b, a2);

  // Eqs. 8-11: differences; hue takes the short way round the circle.
  const bool neutral = c1 * c2 == 0.0;
  double dh = neutral ? 0.0 : h2 - h1;
  if (dh > 180.0) dh -= 360.0;
  if (dh < -180.0) dh += 360.0;
  const double delta_l = second.l - first.l;
  const double delta_c = c2 - c1;
  const double delta_h = 2.0 * std::sqrt(c1 * c2) * std::sin(radians(dh / 2.0));

  // Eqs. 12-14: means; the mean hue also takes the short way round.
  const double mean_l = (first.l + second.l) / 2.0;
  const double mean_c = (c1 + c2) / 2.0;
  double mean_h = h1 + h2;
  if (!neutral) {
    if (std::abs(h1 - h2) <= 180.0) {
      mean_h /= 2.0;
    } else {
      mean_h = (mean_h < 360.0 ? mean_h + 360.0 : mean_h - 360.0) / 2.0;
    }
  }

  // Eqs. 15-22: weights, and the rotation term for blues.
  const double t = 1.0 - 0.17 * std::cos(radians(mean_h - 30.0)) + 0.24 * std::cos(radians(2.0 * mean_h)) +
                   0.32 * std::cos(radians(3.0 * mean_h + 6.0)) - 0.20 * std::cos(radians(4.0 * mean_h - 63.0));
  const double rotation_degrees = 30.0 * std::exp(-std::pow((mean_h - 275.0) / 25.0, 2.0));
  const double r_c = 2.0 * chroma_weight(mean_c);
  const double l_offset = (mean_l - 50.0) * (mean_l - 50.0);
  const double s_l = 1.0 + 0.015 * l_offset / std::sqrt(20.0 + l_offset);
  const double s_c = 1.0 + 0.045 * mean_c;
  const double s_h = 1.0 + 0.015 * mean_c * t;
  const double r_t = -std::sin(radians(2.0 * rotation_degrees)) * r_c;

  const double l_term = delta_l / s_l;
  const double c_term = delta_c / s_c;
  const double h_term = delta_h / s_h;
  return std::sqrt(l_term * l_term + c_term * c_term + h_term * h_term + r_t * c_term * h_term);
}

}  // namespace sp
