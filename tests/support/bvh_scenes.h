// Triangle soups and ray sets shared by the BVH tests (test_bvh.cpp,
// test_wide_bvh.cpp): boxes cut into grids, spheres, rooms with coincident
// walls, random soups, and rays from inside, from surfaces and along planes.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bvh/bvh.h"

namespace sp::test {

using glm::vec3;

// "Unlimited" tmax for most tests; TmaxAtSpFarMissesEmptySpace covers
// tmax == SP_FAR itself.
inline constexpr float kNoLimit = 1.0e6f;

// Three draws from `dist`, in a fixed order: z, y, then x. Written as
// vec3(dist(rng), dist(rng), dist(rng)) the order is the compiler's (GCC
// draws z first, clang x first), so one seed gave GCC and clang different
// scenes; this is GCC's order, the one the tests were written against.
template <typename Distribution>
vec3 draw_vec3(Distribution& dist, std::mt19937& rng) {
  const float z = dist(rng);
  const float y = dist(rng);
  const float x = dist(rng);
  return vec3(x, y, z);
}

// A triangle soup under construction: 3 vertices and 1 layer per triangle.
struct Soup {
  std::vector<vec3> vertices;
  std::vector<std::uint32_t> layers;

  void tri(vec3 a, vec3 b, vec3 c, std::uint32_t layer = 0) {
    vertices.insert(vertices.end(), {a, b, c});
    layers.push_back(layer);
  }
  std::uint32_t size() const { return static_cast<std::uint32_t>(layers.size()); }
  sp::Bvh build(const sp::BvhBuildSettings& s = {}) const { return sp::build_bvh(vertices, layers, {}, s); }
};

// An axis-aligned box with each face cut into n x n quads (2 triangles each).
// Grid coordinates come from one function per axis, so faces meeting at an
// edge share bit-identical vertices and the box is closed (watertight).
inline void add_box(Soup& soup, vec3 lo, vec3 hi, int n, std::uint32_t layer = 0) {
  auto coord = [&](int axis, int i) {  // exact at both ends: lo + (hi - lo) may round away from hi
    return i == n ? hi[axis] : lo[axis] + (hi[axis] - lo[axis]) * float(i) / float(n);
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          vec3 p[4];
          const int corner[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int k = 0; k < 4; ++k) {
            p[k][axis] = side ? hi[axis] : lo[axis];
            p[k][u] = coord(u, corner[k][0]);
            p[k][v] = coord(v, corner[k][1]);
          }
          if ((i + j) % 2) {  // alternate the diagonal for variety
            soup.tri(p[0], p[1], p[2], layer);
            soup.tri(p[0], p[2], p[3], layer);
          } else {
            soup.tri(p[0], p[1], p[3], layer);
            soup.tri(p[1], p[2], p[3], layer);
          }
        }
      }
    }
  }
}

// A sphere from an octahedron whose faces are cut into n^2 triangles. Grid
// points are integer vectors normalised, so shared edges match bit for bit.
inline void add_sphere(Soup& soup, vec3 centre, float radius, int n) {
  auto point = [&](vec3 a, vec3 b, vec3 c, int i, int j) {
    vec3 p = float(i) * a + float(j) * b + float(n - i - j) * c;
    return centre + radius * glm::normalize(p);
  };
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      for (int sz = -1; sz <= 1; sz += 2) {
        vec3 a(float(sx), 0, 0), b(0, float(sy), 0), c(0, 0, float(sz));
        for (int i = 0; i < n; ++i)
          for (int j = 0; i + j < n; ++j) {
            soup.tri(point(a, b, c, i, j), point(a, b, c, i + 1, j), point(a, b, c, i, j + 1));
            if (i + j + 1 < n)
              soup.tri(point(a, b, c, i + 1, j), point(a, b, c, i + 1, j + 1), point(a, b, c, i, j + 1));
          }
      }
}

// A grid of rooms with coincident walls between neighbours: identical
// triangles along y and z (exact ties between scene indices), a finer grid in
// every second room along x (T-junctions).
inline Soup make_rooms(int nx, int ny, int nz, int subdivisions) {
  Soup soup;
  const vec3 size(5.0f, 4.0f, 3.0f);
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z) {
        vec3 lo = vec3(float(x), float(y), float(z)) * size;
        int n = subdivisions * (1 + x % 2);
        add_box(soup, lo, lo + size, n, std::uint32_t((x + y + z) % 3));
      }
  return soup;
}

inline Soup make_random_soup(std::uint32_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f), off(-1.5f, 1.5f);
  Soup soup;
  for (std::uint32_t i = 0; i < count; ++i) {
    const vec3 c = draw_vec3(pos, rng);
    const vec3 third = draw_vec3(off, rng);  // drawn last vertex first, as GCC did
    const vec3 second = draw_vec3(off, rng);
    const vec3 first = draw_vec3(off, rng);
    soup.tri(c + first, c + second, c + third, i % 4);
  }
  return soup;
}

struct Ray {
  vec3 origin, dir;
  float tmin, tmax;
};

// Random unit direction; one in four is axis-parallel and one in eight has
// exactly one zero component, the cases where the slab test divides by zero.
inline vec3 random_dir(std::mt19937& rng) {
  std::normal_distribution<float> g;
  std::uniform_int_distribution<int> kind(0, 7), axis(0, 2), sign(0, 1);
  vec3 d = draw_vec3(g, rng);
  int k = kind(rng);
  if (k < 2) {
    d = vec3(0.0f);
    d[axis(rng)] = sign(rng) ? 1.0f : -1.0f;
  } else if (k == 2) {
    d[axis(rng)] = 0.0f;
  }
  return glm::normalize(d);
}

// Rays from inside `lo..hi`; some with a finite tmax.
inline std::vector<Ray> rays_in_box(vec3 lo, vec3 hi, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < count; ++i) {
    vec3 o = lo + (hi - lo) * draw_vec3(u, rng);
    float tmax = (i % 5 == 0) ? 0.5f + 10.0f * u(rng) : kNoLimit;
    rays.push_back({o, random_dir(rng), 0.0f, tmax});
  }
  return rays;
}

// Rays that start on triangles (like reflected rays), half of them aimed at
// vertices (through edges and corners). Directions have no zero component:
// rays parallel to the plane they start on belong to rays_along_planes().
inline std::vector<Ray> rays_from_surfaces(const Soup& soup, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> g;
  std::uniform_int_distribution<std::size_t> vertex(0, soup.vertices.size() - 1);
  std::vector<Ray> rays;
  while (rays.size() < count) {
    std::size_t t = vertex(rng) / 3 * 3;
    float a = u(rng), b = u(rng) * (1.0f - a);
    vec3 o = soup.vertices[t] + a * (soup.vertices[t + 1] - soup.vertices[t]) +
             b * (soup.vertices[t + 2] - soup.vertices[t]);
    vec3 d = rays.size() % 2 ? soup.vertices[vertex(rng)] - o : draw_vec3(g, rng);
    if (d.x == 0.0f || d.y == 0.0f || d.z == 0.0f) continue;
    float tmin = (rays.size() % 3 == 0) ? SP_EPSILON : 0.0f;
    float tmax = (rays.size() % 7 == 0) ? 1.0f + 5.0f * u(rng) : kNoLimit;
    rays.push_back({o, glm::normalize(d), tmin, tmax});
  }
  return rays;
}

// Rays from vertices, along axes or at other vertices: many run inside a
// wall's plane, with an exactly zero direction component and the origin on
// node bounds planes.
inline std::vector<Ray> rays_along_planes(const Soup& soup, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> vertex(0, soup.vertices.size() - 1);
  std::vector<Ray> rays;
  while (rays.size() < count) {
    vec3 o = soup.vertices[vertex(rng)];
    vec3 d = rays.size() % 2 ? soup.vertices[vertex(rng)] - o : random_dir(rng);
    if (d != vec3(0.0f)) rays.push_back({o, glm::normalize(d), rays.size() % 3 ? 0.0f : SP_EPSILON, kNoLimit});
  }
  return rays;
}

// The unit square at z = 5 split along its diagonal (0,0)-(1,1).
inline Soup unit_square() {
  Soup soup;
  soup.tri(vec3(0, 0, 5), vec3(1, 0, 5), vec3(1, 1, 5));  // below the diagonal
  soup.tri(vec3(0, 0, 5), vec3(1, 1, 5), vec3(0, 1, 5));  // above it
  return soup;
}

// 5000 triangles whose bound centres coincide: no plane separates them, so
// only the median fallback and the depth cap keep the build finite.
inline Soup make_identical_centroids(std::uint32_t count) {
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> k(1, 64), s(0, 1);
  const vec3 c(1.0f, 2.0f, 3.0f);
  Soup soup;
  for (std::uint32_t i = 0; i < count; ++i) {
    vec3 a, b;
    for (int axis = 0; axis < 3; ++axis) {  // dyadic, so lo + hi == 2c exactly
      a[axis] = float(k(rng)) / 64.0f;
      const float sign = s(rng) ? 1.0f : -1.0f;  // drawn before the scale, in its own statement
      b[axis] = sign * a[axis] * float(k(rng)) / 64.0f;
    }
    soup.tri(c + a, c - a, c + b);
  }
  return soup;
}

}  // namespace sp::test
