// What spots could tell a player who faces a source, at best (issue 34).
// Not a timing: an upper bound on `../shared/tools/fidelity/`'s facing
// score that no admission, guide or drawing can beat under the ray model.
//
// It runs a scene on the CPU backend at a large budget and keeps every spot
// created (not only what a ring would keep). A spot the player could see is
// one whose surface faces the listener and whose way to the listener is
// open, whatever energy would arrive. Per audible source it takes the
// facing frame the fidelity tool draws (the eye at the listener turned to
// the source's yaw, pitch 0, --hfov wide, --aspect) and the spots it could
// see in that frame. The tool's estimate is a weighted centroid of spot
// pixels, so the best any picture could do is the point of the spots'
// convex hull (in the image plane) nearest the source's direction: 0 when
// the source's point lies inside the hull. A source whose best is over
// 15 degrees cannot count towards "facing <= 15" whatever is drawn.
//
//   facing_bound --scene ../shared/levels/listeners/oa_dm1-draw-L0.glb --rays 20000 --steps 30
//
// docs/model.md#cues-for-the-player and bench/RESULTS.md section 35 say what
// it found on the shared maps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bench_common.h"
#include "soundpaint/config.h"
#include "soundpaint/ray_query.h"
#include "soundpaint/scene.h"
#include "soundpaint/simulation.h"
#include "soundpaint/world.h"

namespace {

using spbench::CommandLine;

constexpr const char* kUsage =
    "usage: facing_bound [--scene FILE] [--config FILE] [--rays R] [--steps N] [--hfov DEG] [--aspect W/H]\n"
    "  --rays R     ray budget a step (default 20000: 40 times the default)\n"
    "  --steps N    steps simulated; every spot of every step is kept (default 30)\n"
    "  --hfov DEG   the facing frame's horizontal field of view (default 90)\n"
    "  --aspect A   its width over height (default 1.7778, the fidelity tool's 1280 x 720)\n";

struct Options {
  std::string scene = SP_DEFAULT_SCENE;
  std::string config;
  std::uint32_t rays = 20000;
  std::uint32_t steps = 30;
  double hfov_deg = 90.0;
  double aspect = 1280.0 / 720.0;
};

Options parse(const CommandLine& cli, int argc, char** argv) {
  Options o;
  cli.parse(argc, argv, [&](const std::string& flag, const std::string& value) {
    if (flag == "--scene") o.scene = value;
    else if (flag == "--config") o.config = value;
    else if (flag == "--rays") o.rays = cli.to_uint(value, flag);
    else if (flag == "--steps") o.steps = cli.to_uint(value, flag);
    else if (flag == "--hfov") o.hfov_deg = cli.to_double(value, flag);
    else if (flag == "--aspect") o.aspect = cli.to_double(value, flag);
    else return false;
    return true;
  });
  if (o.steps == 0) cli.fail("--steps must be > 0");
  if (!(o.hfov_deg > 0.0 && o.hfov_deg < 180.0)) cli.fail("--hfov must lie in (0, 180)");
  if (!(o.aspect > 0.0)) cli.fail("--aspect must be > 0");
  return o;
}

glm::dvec3 to_dvec(const sp::Vec3& v) { return {v.x, v.y, v.z}; }

// The fidelity tool's facing frame for one source: forward along the
// source's yaw, level; points are in the image plane, [-1, 1] on each axis.
struct FacingFrame {
  glm::dvec3 eye, forward, right, up{0.0, 1.0, 0.0}, to_source;
  double tan_h = 1.0, tan_v = 1.0;

  FacingFrame(glm::dvec3 eye_, glm::dvec3 source, double hfov_deg, double aspect)
      : eye(eye_), to_source(source - eye_) {
    const glm::dvec3 level(to_source.x, 0.0, to_source.z);
    forward = glm::length(level) > 0.0 ? glm::normalize(level) : glm::dvec3(0.0, 0.0, -1.0);
    right = glm::dvec3(-forward.z, 0.0, forward.x);
    tan_h = std::tan(glm::radians(hfov_deg * 0.5));
    tan_v = tan_h / aspect;
  }

  // The point's place in the picture, or false when it is out of frame.
  bool project(glm::dvec3 point, glm::dvec2& image) const {
    const glm::dvec3 v = point - eye;
    const double depth = glm::dot(v, forward);
    if (!(depth > 1e-6)) return false;
    image = {glm::dot(v, right) / depth / tan_h, glm::dot(v, up) / depth / tan_v};
    return std::abs(image.x) <= 1.0 && std::abs(image.y) <= 1.0;
  }

  // Degrees at the eye between the picture's point and the source.
  double error_deg(glm::dvec2 image) const {
    const glm::dvec3 way = forward + image.x * tan_h * right + image.y * tan_v * up;
    const double c = glm::dot(glm::normalize(way), glm::normalize(to_source));
    return glm::degrees(std::acos(std::clamp(c, -1.0, 1.0)));
  }

  // Where the source itself would be drawn (it may be out of frame).
  glm::dvec2 source_image() const {
    const double level = std::hypot(to_source.x, to_source.z);
    return {0.0, (level > 0.0 ? to_source.y / level : 1e9) / tan_v};
  }
};

double cross(glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Counter-clockwise convex hull (Andrew's monotone chain).
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> points) {
  std::sort(points.begin(), points.end(),
            [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// The smallest error any weighted centroid of `points` can have: 0 when the
// source's point is inside their hull, else the least along its edges
// (sampled finely: the error is smooth along an edge).
double best_centroid_error(const std::vector<glm::dvec2>& points, const FacingFrame& frame) {
  if (points.empty()) return INFINITY;
  const std::vector<glm::dvec2> hull = convex_hull(points);
  const glm::dvec2 source = frame.source_image();
  bool inside = hull.size() >= 3;
  for (std::size_t i = 0; inside && i < hull.size(); ++i)
    inside = cross(hull[i], hull[(i + 1) % hull.size()], source) >= 0.0;
  if (inside) return 0.0;
  double best = INFINITY;
  constexpr int kSamples = 256;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    for (int s = 0; s <= kSamples; ++s) best = std::min(best, frame.error_deg(a + (b - a) * (double(s) / kSamples)));
  }
  return best;
}

// "12.3", or "-" for no spot at all.
std::string degrees(double value) {
  if (!std::isfinite(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

struct SourceTally {
  std::uint64_t created = 0, heard = 0, seen = 0, in_frame = 0, within15 = 0;
  std::vector<glm::dvec2> heard_points, seen_points;
};

int run(const CommandLine&, const Options& options) {
  const auto scene = sp::load_scene(options.scene);
  if (!scene) throw std::runtime_error(scene.error().message);
  sp::Config config;
  if (!options.config.empty()) {
    auto loaded = sp::load_config(options.config);
    if (!loaded) throw std::runtime_error(loaded.error().message);
    config = *loaded;
  }
  config.ray_budget = options.rays;
  auto world = sp::make_world(*scene, config);
  if (!world) throw std::runtime_error(world.error().message);
  const sp::World probe = *world;  // shares the geometry: the ways to the listener are cast on it
  auto simulator = sp::create_cpu_simulator(std::move(*world));
  if (!simulator) throw std::runtime_error(simulator.error().message);

  const glm::dvec3 eye = to_dvec(probe.listener);
  std::vector<FacingFrame> frames;
  std::vector<bool> audible;
  for (const sp::SourceDesc& source : probe.sources) {
    frames.emplace_back(eye, to_dvec(source.position), options.hfov_deg, options.aspect);
    const double distance = glm::length(to_dvec(source.position) - eye);
    audible.push_back(distance <= std::min<double>(source.max_distance, config.scan_radius));
  }
  std::vector<SourceTally> tally(probe.sources.size());

  for (std::uint32_t n = 0; n < options.steps; ++n) {
    if (auto stepped = (*simulator)->step(); !stepped) throw std::runtime_error(stepped.error().message);
    auto spots = (*simulator)->last_step_indicators();
    if (!spots) throw std::runtime_error(spots.error().message);
    for (const sp::Indicator& spot : *spots) {
      SourceTally& t = tally.at(spot.source_id);
      t.created += 1;
      const glm::dvec3 position = to_dvec(spot.position), normal = to_dvec(spot.normal);
      const glm::dvec3 off = position + normal * 1e-4;  // as a reflected ray starts (SP_EPSILON)
      const glm::dvec3 way = off - eye;
      const double length = glm::length(way);
      if (!(glm::dot(normal, -way) > 0.0) || !(length > 0.0)) continue;  // faces away
      const glm::dvec3 dir = way / length;
      auto hit = sp::cast_ray(probe, sp::Vec3(float(eye.x), float(eye.y), float(eye.z)),
                              sp::Vec3(float(dir.x), float(dir.y), float(dir.z)), float(length));
      if (!hit) throw std::runtime_error(hit.error().message);
      if (hit->has_value()) continue;  // something lies between
      t.seen += 1;
      const FacingFrame& frame = frames[spot.source_id];
      glm::dvec2 image;
      if (!frame.project(position, image)) continue;
      t.in_frame += 1;
      if (frame.error_deg(image) <= 15.0) t.within15 += 1;
      t.seen_points.push_back(image);
      if (spot.heard_energy > 0.0f) {
        t.heard += 1;
        t.heard_points.push_back(image);
      }
    }
  }

  std::printf("scene %s: %u rays a step, %u steps, facing frame %.0f deg wide at %.4f:1\n", options.scene.c_str(),
              options.rays, options.steps, options.hfov_deg, options.aspect);
  // Per audible source: spots created; seen from the eye; seen in the
  // facing frame; of those, within 15 degrees and heard; then the best
  // centroid error, in degrees, from the spots seen and from those heard.
  std::printf("%6s %9s %10s %10s %10s %10s %10s %11s %11s\n", "source", "distance", "spots", "seen", "in frame",
              "<= 15 deg", "heard", "best seen", "best heard");
  std::uint32_t sources = 0, seen15 = 0, seen30 = 0, heard15 = 0, heard30 = 0;
  for (std::size_t id = 0; id < tally.size(); ++id) {
    if (!audible[id]) continue;
    const SourceTally& t = tally[id];
    const double best_seen = best_centroid_error(t.seen_points, frames[id]);
    const double best_heard = best_centroid_error(t.heard_points, frames[id]);
    sources += 1;
    seen15 += best_seen <= 15.0;
    seen30 += best_seen <= 30.0;
    heard15 += best_heard <= 15.0;
    heard30 += best_heard <= 30.0;
    std::printf("%6zu %8.1fm %10llu %10llu %10llu %10llu %10llu %11s %11s\n", id, glm::length(frames[id].to_source),
                static_cast<unsigned long long>(t.created), static_cast<unsigned long long>(t.seen),
                static_cast<unsigned long long>(t.in_frame), static_cast<unsigned long long>(t.within15),
                static_cast<unsigned long long>(t.heard), degrees(best_seen).c_str(), degrees(best_heard).c_str());
  }
  std::printf("audible %u; facing <= 15 at best: %u from spots seen, %u from spots heard; <= 30: %u and %u\n", sources,
              seen15, heard15, seen30, heard30);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return spbench::bench_main(argc, argv, "facing_bound", kUsage, parse, run); }
