// WCAG 2.x contrast: W3C, "Web Content Accessibility Guidelines (WCAG) 2.1"
// (2018), definitions of relative luminance and contrast ratio; success
// criterion 1.4.11 asks 3:1 for graphical objects.
#include "display/contrast.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace sp {

float relative_luminance(glm::vec3 linear_rgb) {
  return 0.2126f * linear_rgb.x + 0.7152f * linear_rgb.y + 0.0722f * linear_rgb.z;
}

float contrast_ratio(float luminance_a, float luminance_b) {
  // 0.05: the flare of a typical display, which keeps black's ratio finite.
  return (std::max(luminance_a, luminance_b) + 0.05f) / (std::min(luminance_a, luminance_b) + 0.05f);
}

float halo_worst_case_contrast() {
  return std::sqrt(contrast_ratio(relative_luminance(kHaloLight), relative_luminance(kHaloDark)));
}

}  // namespace sp
