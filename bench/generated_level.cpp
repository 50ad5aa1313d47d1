#include "generated_level.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace spbench {
namespace {

constexpr int kRooms = 4;        // per side
constexpr float kCell = 8.0f;    // room pitch, metres
constexpr float kHeight = 3.0f;  // floor top to ceiling bottom
constexpr float kWall = 0.2f;    // wall and slab thickness
constexpr float kDoorWidth = 1.2f;
constexpr float kDoorHeight = 2.2f;
constexpr std::uint32_t kSources = 15;

enum Layer : std::uint32_t { kConcrete, kBrick, kWood, kMetal };

struct Box {
  glm::vec3 lo, hi;
  std::uint32_t layer;
};

// A small deterministic generator (64-bit LCG, high bits), so the level does
// not depend on the standard library's distributions.
class Random {
 public:
  float uniform(float lo, float hi) {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    const float unit = static_cast<float>(state_ >> 40) / 16777216.0f;  // 24 bits in [0, 1)
    return lo + (hi - lo) * unit;
  }

 private:
  std::uint64_t state_ = 0x5eed5eedull;
};

// Cells along an edge of length `length` for cell size `h`.
std::size_t cells(float length, double h) {
  return static_cast<std::size_t>(std::max(1.0, std::ceil(static_cast<double>(length) / h)));
}

// The three axis pairs (u, v) spanning a box's faces, and the normal axis.
constexpr int kFaceAxes[3][3] = {{1, 2, 0}, {2, 0, 1}, {0, 1, 2}};

std::size_t triangle_count(const std::vector<Box>& boxes, double h) {
  std::size_t total = 0;
  for (const Box& box : boxes) {
    const glm::vec3 size = box.hi - box.lo;
    for (const auto& axes : kFaceAxes) total += 2 * 2 * cells(size[axes[0]], h) * cells(size[axes[1]], h);
  }
  return total;
}

void emit_quad(sp::Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, std::uint32_t layer) {
  for (glm::vec3 v : {a, b, c, a, c, d}) scene.vertices.push_back(v);
  scene.triangle_layers.push_back(layer);
  scene.triangle_layers.push_back(layer);
}

// Both faces of the box normal to axes[2], each split into nu x nv cells,
// wound counter-clockwise seen from outside.
void emit_faces(sp::Scene& scene, const Box& box, const int axes[3], double h) {
  const int u = axes[0], v = axes[1], n = axes[2];
  const glm::vec3 size = box.hi - box.lo;
  const std::size_t nu = cells(size[u], h), nv = cells(size[v], h);
  for (int side = 0; side < 2; ++side) {
    for (std::size_t i = 0; i < nu; ++i) {
      for (std::size_t j = 0; j < nv; ++j) {
        auto corner = [&](std::size_t ci, std::size_t cj) {
          glm::vec3 p;
          p[n] = side ? box.hi[n] : box.lo[n];
          p[u] = ci == nu ? box.hi[u] : box.lo[u] + size[u] * static_cast<float>(ci) / static_cast<float>(nu);
          p[v] = cj == nv ? box.hi[v] : box.lo[v] + size[v] * static_cast<float>(cj) / static_cast<float>(nv);
          return p;
        };
        // (u, v, n) is right-handed, so u-then-v winds towards +n.
        if (side) emit_quad(scene, corner(i, j), corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1), box.layer);
        else emit_quad(scene, corner(i, j), corner(i, j + 1), corner(i + 1, j + 1), corner(i + 1, j), box.layer);
      }
    }
  }
}

// A wall along `axis` (0: x, 2: z) centred on `line`, from `from` to `to`,
// with a door centred at each of `doors`.
void add_wall(std::vector<Box>& boxes, int axis, float line, float from, float to, const std::vector<float>& doors,
              std::uint32_t layer) {
  const int across = axis == 0 ? 2 : 0;
  auto box = [&](float a, float b, float y0, float y1) {
    glm::vec3 lo(0.0f), hi(0.0f);
    lo[axis] = a;
    hi[axis] = b;
    lo[across] = line - kWall / 2;
    hi[across] = line + kWall / 2;
    lo.y = y0;
    hi.y = y1;
    boxes.push_back({lo, hi, layer});
  };
  float cursor = from;
  for (float door : doors) {
    box(cursor, door - kDoorWidth / 2, 0.0f, kHeight);
    box(door - kDoorWidth / 2, door + kDoorWidth / 2, kDoorHeight, kHeight);  // lintel
    cursor = door + kDoorWidth / 2;
  }
  box(cursor, to, 0.0f, kHeight);
}

bool near_box(glm::vec3 p, const Box& box, float margin) {
  for (int i = 0; i < 3; ++i)
    if (p[i] < box.lo[i] - margin || p[i] > box.hi[i] + margin) return false;
  return true;
}

}  // namespace

sp::Scene generate_level(std::size_t target_triangles) {
  const float extent = kRooms * kCell;
  std::vector<Box> boxes;
  boxes.push_back({{-kWall / 2, -kWall, -kWall / 2}, {extent + kWall / 2, 0.0f, extent + kWall / 2}, kConcrete});
  boxes.push_back(
      {{-kWall / 2, kHeight, -kWall / 2}, {extent + kWall / 2, kHeight + kWall, extent + kWall / 2}, kConcrete});
  // Walls along x run the full width; walls along z fit between them.
  for (int line = 0; line <= kRooms; ++line) {
    const bool outer = line == 0 || line == kRooms;
    std::vector<float> doors;
    if (!outer)
      for (int room = 0; room < kRooms; ++room) doors.push_back((static_cast<float>(room) + 0.5f) * kCell);
    add_wall(boxes, 0, static_cast<float>(line) * kCell, -kWall / 2, extent + kWall / 2, doors,
             outer ? kConcrete : kBrick);
    for (int room = 0; room < kRooms; ++room) {
      std::vector<float> door;
      if (!outer) door.push_back((static_cast<float>(room) + 0.3f) * kCell);
      add_wall(boxes, 2, static_cast<float>(line) * kCell, static_cast<float>(room) * kCell + kWall / 2,
               static_cast<float>(room + 1) * kCell - kWall / 2, door, outer ? kConcrete : kWood);
    }
  }

  sp::Scene scene;
  scene.layer_names = {"concrete", "brick", "wood", "metal"};
  Random random;
  for (std::uint32_t i = 0; i < kSources; ++i) {
    const float x0 = static_cast<float>(i % kRooms) * kCell, z0 = static_cast<float>(i / kRooms) * kCell;
    sp::SourceDesc source;
    source.name = "Source" + std::to_string(i);
    source.position = {x0 + kCell / 2 + random.uniform(-2.0f, 2.0f), random.uniform(0.3f, 2.5f),
                       z0 + kCell / 2 + random.uniform(-2.0f, 2.0f)};
    source.color = {1.0f, 0.2f + 0.05f * static_cast<float>(i), 0.1f};
    source.max_distance = 30.0f;
    source.duration = 0.1;
    source.interval = 0.25;
    source.phase = 0.25 * i / kSources;
    scene.sources.push_back(source);
  }
  for (int room = 0; room < kRooms * kRooms; ++room) {
    const float x0 = static_cast<float>(room % kRooms) * kCell, z0 = static_cast<float>(room / kRooms) * kCell;
    const int pieces = 2 + room % 2;
    for (int placed = 0; placed < pieces;) {
      const float w = random.uniform(0.5f, 2.0f), d = random.uniform(0.5f, 2.0f), h = random.uniform(0.4f, 1.8f);
      const float x = x0 + random.uniform(0.6f, kCell - 0.6f - w), z = z0 + random.uniform(0.6f, kCell - 0.6f - d);
      Box box{{x, 0.0f, z}, {x + w, h, z + d}, placed % 2 ? kMetal : kWood};
      bool clear = true;
      for (const sp::SourceDesc& source : scene.sources) clear = clear && !near_box(source.position, box, 0.5f);
      if (!clear) continue;
      boxes.push_back(box);
      ++placed;
    }
  }

  // The cell size whose triangle count comes closest to the target
  // (the count falls as h grows).
  double lo = 1e-3, hi = 100.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = std::sqrt(lo * hi);
    (triangle_count(boxes, mid) > target_triangles ? lo : hi) = mid;
  }
  auto miss = [&](double cell) {
    const std::size_t count = triangle_count(boxes, cell);
    return count > target_triangles ? count - target_triangles : target_triangles - count;
  };
  const double h = miss(lo) < miss(hi) ? lo : hi;

  scene.path = "gen:" + std::to_string(target_triangles);
  scene.vertices.reserve(triangle_count(boxes, h) * 3);
  for (const Box& box : boxes)
    for (const auto& axes : kFaceAxes) emit_faces(scene, box, axes, h);
  sp::Camera camera;
  camera.world[3][0] = kCell + 5.0f;
  camera.world[3][1] = 1.7f;
  camera.world[3][2] = kCell + 5.0f;
  scene.camera = camera;
  return scene;
}

}  // namespace spbench
