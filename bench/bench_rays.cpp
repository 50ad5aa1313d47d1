// Ray-casting benchmark: soundpaint's closest_hit against Embree (the ceiling
// of CPU ray casting) on the same rays, BVH build times, and the backends'
// casts per second, on a bundled level and on generated levels of growing
// triangle count.
//
// The rays are the emitted rays of consecutive steps at --budget rays per
// step, i.e. the casts of the backends' first wavefront iteration: origin =
// source position, direction = sp_emission_direction, (tmin, tmax] =
// (0, sp_active_reach), computed here with
// plan_step and sp_emit_ray as the backends do. Both casters run on the same
// thread pool (the CPU backend's), in chunks of 64 rays; Embree as one
// rtcIntersect1 per ray and as rtcIntersect16 packets. Before timing, Embree's
// hits must agree with soundpaint's (both miss, or both hit within 1e-4
// relative distance) for at least 99.9 % of the rays.
//
// Build times: sp::build_bvh (binned SAH, single-threaded) against
// rtcCommitScene at RTC_BUILD_QUALITY_MEDIUM (binned SAH, Embree's default)
// and RTC_BUILD_QUALITY_HIGH (adds spatial splits) on --threads threads, and
// MEDIUM on one thread; medians of --build-runs builds.
//
//   bench_rays --scenes scenes/level.gltf,gen:10000,gen:100000,gen:1000000 --rays 500000 --runs 5
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "bench_common.h"
#include "core/glm_interop.h"
#include "embree_cast.h"
#include "sim/step_plan.h"
#include "sim/thread_pool.h"
#include "io/output.h"
#include "sim/world_geometry.h"
#include "bvh/wide_bvh.h"
#include "sp_ray_model.h"

namespace {

using spbench::CastHit;
using spbench::CastRay;
using spbench::CommandLine;
using spbench::EmbreeQuality;
using spbench::Json;

constexpr const char* kUsage =
    "usage: bench_rays [--scenes SPEC,...] [--rays N] [--budget B] [--runs R] [--build-runs R] [--threads T]\n"
    "                  [--backends cpu,gpu|none] [--sim-steps N] [--sim-max-seconds S] [--pattern paper|burst|scene]\n"
    "                  [--cpu-walk best|baseline|avx512|avx512-8wide] [--embree-accel NAME] [--traversal-cost C] "
    "[--json OUT.json]\n"
    "  --scenes      glTF files and gen:N generated levels of about N triangles\n"
    "                (default: scenes/level.gltf,gen:10000,gen:100000,gen:1000000)\n"
    "  --rays        emitted rays cast per pass (default 500000), gathered from steps at --budget rays (default 2500)\n"
    "  --runs        timed passes per caster after one warm-up pass; medians (default 5)\n"
    "  --build-runs  BVH builds per builder after one warm-up build; medians (default 3)\n"
    "  --backends    simulation backends stepped on each scene for casts/s (default cpu,gpu; none skips)\n"
    "  --sim-steps   frames measured per backend (default 60, after 10 of warm-up)\n"
    "  --cpu-walk    soundpaint's CPU traversal: best (default: the fastest this CPU runs), baseline, avx512\n"
    "                (4-wide), avx512-8wide\n"
    "  --embree-accel  the tree Embree builds (its tri_accel setting), e.g. bvh4.triangle4 to compare 4-wide\n"
    "                nodes with ours (default: Embree's choice, bvh8.triangle4 on AVX2 and AVX-512 CPUs)\n"
    "  --traversal-cost  our BVH's SAH cost of a node visit (BvhBuildSettings::traversal_cost; default the\n"
    "                library's), for the casts and the builds\n";

struct Options {
  std::vector<std::string> scenes = {SP_DEFAULT_SCENE, "gen:10000", "gen:100000", "gen:1000000"};
  std::uint32_t rays = 500000;
  std::uint32_t budget = 2500;
  std::uint32_t runs = 5;
  std::uint32_t build_runs = 3;
  unsigned threads = 0;
  std::vector<std::string> backends = {"cpu", "gpu"};
  spbench::LoopSettings loop{10, 60, 0.0};
  spbench::Pattern pattern = spbench::Pattern::Paper;
  std::string json;
  std::string cpu_walk = "best";
  std::string embree_accel;  // empty: Embree's default for this CPU
  sp::BvhBuildSettings bvh;  // our tree, for the casts and the builds
};

Options parse(const CommandLine& cli, int argc, char** argv) {
  Options o;
  cli.parse(argc, argv, [&](const std::string& flag, const std::string& value) {
    if (flag == "--scenes") o.scenes = CommandLine::split(value);
    else if (flag == "--rays") o.rays = cli.to_uint(value, flag);
    else if (flag == "--budget") o.budget = cli.to_uint(value, flag);
    else if (flag == "--runs") o.runs = cli.to_uint(value, flag);
    else if (flag == "--build-runs") o.build_runs = cli.to_uint(value, flag);
    else if (flag == "--threads") o.threads = cli.to_uint(value, flag);
    else if (flag == "--backends")
      o.backends = value == "none" ? std::vector<std::string>{} : CommandLine::split(value);
    else if (flag == "--sim-steps") o.loop.steps = cli.to_uint(value, flag);
    else if (flag == "--sim-max-seconds") o.loop.max_seconds = cli.to_double(value, flag);
    else if (flag == "--json") o.json = value;
    else if (flag == "--cpu-walk") o.cpu_walk = value;
    else if (flag == "--embree-accel") o.embree_accel = value;
    else if (flag == "--traversal-cost") {
      const double cost = cli.to_double(value, flag);
      if (!(cost >= 0.0 && cost <= 1000.0)) cli.fail("--traversal-cost must be in [0, 1000]");
      o.bvh.traversal_cost = static_cast<float>(cost);
    } else if (flag == "--pattern") o.pattern = spbench::parse_pattern(cli, value);
    else return false;
    return true;
  });
  if (o.scenes.empty() || o.rays == 0 || o.budget == 0 || o.runs == 0 || o.build_runs == 0 || o.loop.steps == 0)
    cli.fail("--scenes, --rays, --budget, --runs, --build-runs and --sim-steps must not be empty or 0");
  if (!spbench::is_accel_name(o.embree_accel))
    cli.fail("--embree-accel must be one word (letters, digits, '.', '_'), such as bvh4.triangle4");
  for (const auto& b : o.backends)
    if (b != "cpu" && b != "gpu") cli.fail("unknown backend " + b);
  return o;
}

// The emitted rays of steps 0, 1, ... until `count` are gathered, exactly as
// the backends emit them (their first wavefront iteration's casts).
std::vector<CastRay> emitted_rays(const sp::World& world, std::size_t count) {
  using namespace sp::shader;
  std::vector<CastRay> rays;
  const std::vector<sp::PlayWindow> no_play(world.sources.size());
  for (std::uint64_t step = 0; rays.size() < count; ++step) {
    const sp::StepPlan plan = sp::plan_step(world, step, world.listener, no_play);
    if (step > 100000 && rays.empty()) break;  // no source ever plays
    const SimParams params = sp::make_sim_params(world.config, step, plan.listener);
    for (std::uint32_t slot = 0; slot < plan.sources.size(); ++slot) {
      const StepSource& source = plan.sources[slot];
      for (std::uint32_t i = source.first_ray; i < source.first_ray + source.ray_count && rays.size() < count; ++i) {
        const glm::vec3 dir = sp_emission_direction(params.seed, params.step, i);
        const RayState ray = sp_emit_ray(source, slot, i, dir, 0u);
        rays.push_back({ray.origin, 0.0f, ray.dir, sp_active_reach(ray, params)});
      }
    }
  }
  return rays;
}

// Embree's single-ray entry point, the fair match for closest_hit (the
// others trace packets of rays together).
bool caster_is_single_ray(const char* entry) { return std::string(entry) == "rtcIntersect1"; }

using Caster = std::function<void(const CastRay* rays, std::size_t count, CastHit* hits)>;

// Casts all rays on the pool in chunks of 64.
void cast_all(sp::ThreadPool& pool, const Caster& caster, const std::vector<CastRay>& rays,
              std::vector<CastHit>& hits) {
  hits.resize(rays.size());
  pool.parallel_for(rays.size(), 64, [&](std::size_t first, std::size_t last, unsigned) {
    caster(rays.data() + first, last - first, hits.data() + first);
  });
}

// Rays per second: one warm-up pass, then the median of `runs` passes.
double rays_per_second(sp::ThreadPool& pool, const Caster& caster, const std::vector<CastRay>& rays,
                       std::uint32_t runs) {
  std::vector<CastHit> hits;
  cast_all(pool, caster, rays, hits);
  std::vector<double> seconds;
  for (std::uint32_t r = 0; r < runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    cast_all(pool, caster, rays, hits);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return static_cast<double>(rays.size()) / sp::median(seconds);
}

// Fraction of rays on which two casters agree: both miss, or both hit within
// 1e-4 relative distance.
double agreement(const std::vector<CastHit>& a, const std::vector<CastHit>& b) {
  std::size_t agree = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool hit_a = a[i].triangle != spbench::kMiss, hit_b = b[i].triangle != spbench::kMiss;
    if (hit_a != hit_b) continue;
    agree += !hit_a || std::abs(a[i].t - b[i].t) <= 1e-4f * std::max(a[i].t, b[i].t);
  }
  return a.empty() ? 1.0 : static_cast<double>(agree) / static_cast<double>(a.size());
}

constexpr double kRequiredAgreement = 0.999;

struct EmbreeBuild {
  EmbreeQuality quality;
  unsigned threads;
  bool cast;  // also cast with this tree
};

int run(const CommandLine& cli, const Options& options) {
  const unsigned threads = spbench::resolve_threads(options.threads);
  sp::ThreadPool pool(threads);
  const auto embree = spbench::embree_version();
  spbench::select_cpu_walk(cli, options.cpu_walk);
  std::printf("host: %s\n", spbench::host_description().c_str());
  std::printf("soundpaint CPU walk: %s; BVH SAH traversal cost %g\n", spbench::cpu_walk_name(),
              static_cast<double>(options.bvh.traversal_cost));
  std::printf("casting on %u threads; %u emitted rays per pass (budget %u per step), median of %u passes\n", threads,
              options.rays, options.budget, options.runs);
  if (embree)
    std::printf("Embree %s, tree %s\n", embree->c_str(),
                options.embree_accel.empty() ? "Embree's default" : options.embree_accel.c_str());
  else std::printf("Embree not available: built without libembree-dev\n");
  const std::vector<EmbreeBuild> embree_builds = {
      {EmbreeQuality::Medium, threads, true}, {EmbreeQuality::High, threads, true}, {EmbreeQuality::Medium, 1, false}};

  Json scenes = Json::array();
  for (const std::string& spec : options.scenes) {
    sp::Scene scene = spbench::load_scene_or_exit(cli, spec);
    const std::vector<glm::vec3> vertices = sp::to_glm(scene.vertices);  // what build_bvh and Embree take
    sp::Config config;
    config.ray_budget = options.budget;
    spbench::apply_pattern(scene, options.pattern, config.dt);
    auto made = sp::make_world(scene, config, options.bvh);
    if (!made) {
      std::fprintf(stderr, "bench_rays: %s: %s\n", spec.c_str(), made.error().message.c_str());
      return 1;
    }
    const sp::World& world = *made;
    std::printf("\nscene %s: %zu triangles, %zu sources; BVH %zu nodes, depth %u\n", spec.c_str(),
                scene.triangle_count(), scene.sources.size(), world.geometry->bvh.nodes.size(),
                world.geometry->bvh.depth);
    Json row = {{"spec", spec}, {"triangles", scene.triangle_count()}, {"sources", scene.sources.size()}};
    if (const auto& wide = world.geometry->bvh.wide) {
      // Which tree the CPU walk takes: the 8-wide one exists only up to
      // sp::kWide8MaxTreeBytes.
      constexpr double kMiB = 1024.0 * 1024.0;
      std::printf("  CPU trees: 4-wide nodes and packets %.1f MiB, 8-wide nodes %.1f MiB%s\n",
                  static_cast<double>(wide->wide4_bytes()) / kMiB,
                  static_cast<double>(wide->nodes8.size() * sizeof(sp::WideNode8)) / kMiB,
                  wide->nodes8.empty() ? " (none: the 4-wide tree is walked)" : "");
    }

    // BVH builds.
    // build_bvh builds the subtrees below the root on all cores by default;
    // threads = 1 is the serial build, for comparison with Embree's.
    Json builds = Json::array();
    for (unsigned build_threads : {0u, 1u}) {
      sp::BvhBuildSettings settings = options.bvh;
      settings.threads = build_threads;
      std::vector<double> build_ms;
      // Run 0 warms up (the heap's first growth, thread stacks) unmeasured:
      // the first builds of a process took twice as long as the rest.
      for (std::uint32_t r = 0; r <= options.build_runs; ++r) {
        const double ms = sp::build_bvh(vertices, scene.triangle_layers, {}, settings).build_ms;
        if (r > 0) build_ms.push_back(ms);
      }
      const unsigned used = build_threads ? build_threads : std::max(1u, std::thread::hardware_concurrency());
      builds.push_back({{"builder", "soundpaint"}, {"threads", used}, {"ms", sp::median(build_ms)}});
      std::printf("  BVH build  soundpaint (binned SAH, %u thread%s) %*.2f ms\n", used, used == 1 ? "" : "s",
                  used == 1 ? 10 : 9, sp::median(build_ms));
    }

    // The rays, and soundpaint's hits as the reference.
    const std::vector<CastRay> rays = emitted_rays(world, options.rays);
    if (rays.empty()) {
      std::fprintf(stderr, "bench_rays: %s: no source emits within reach of the listener\n", spec.c_str());
      return 1;
    }
    const Caster soundpaint = [&](const CastRay* r, std::size_t count, CastHit* out) {
      for (std::size_t i = 0; i < count; ++i) {
        const sp::HitInfo hit = sp::closest_hit(world.geometry->bvh, r[i].origin, r[i].dir, r[i].tmin, r[i].tmax);
        // The leaf-order index, as the CPU backend uses it; mapping it to
        // the scene's order would add a cache miss per ray that Embree's
        // caster, returning its own primID, does not pay.
        out[i] = hit.triangle == SP_INVALID ? CastHit{} : CastHit{hit.t, hit.triangle};
      }
    };
    std::vector<CastHit> reference;
    cast_all(pool, soundpaint, rays, reference);
    const double hit_fraction =
        static_cast<double>(std::count_if(reference.begin(), reference.end(),
                                          [](const CastHit& h) { return h.triangle != spbench::kMiss; })) /
        static_cast<double>(rays.size());
    const double soundpaint_rate = rays_per_second(pool, soundpaint, rays, options.runs);
    Json casts = Json::array();
    casts.push_back({{"caster", "soundpaint closest_hit"}, {"rays_per_second", soundpaint_rate}, {"agreement", 1.0}});

    // Embree: build, validate against soundpaint, then time.
    double best_embree = 0.0;
    double best_single_ray = 0.0;  // rtcIntersect1: one ray per call, as our closest_hit
    for (const EmbreeBuild& config_e : embree ? embree_builds : std::vector<EmbreeBuild>{}) {
      std::vector<double> ms;
      std::unique_ptr<spbench::EmbreeScene> tree;
      for (std::uint32_t r = 0; r <= options.build_runs; ++r) {  // run 0 warms up, as above
        tree.reset();
        tree =
            std::make_unique<spbench::EmbreeScene>(vertices, config_e.quality, config_e.threads, options.embree_accel);
        if (r > 0) ms.push_back(tree->build_ms());
      }
      const std::string name = std::string("embree ") + spbench::quality_name(config_e.quality);
      builds.push_back({{"builder", name}, {"threads", config_e.threads}, {"ms", sp::median(ms)}});
      std::printf(
          "  BVH build  %-34s %10.2f ms\n",
          (name + " (" + std::to_string(config_e.threads) + " thread" + (config_e.threads == 1 ? ")" : "s)")).c_str(),
          sp::median(ms));
      if (!config_e.cast) continue;
      const spbench::EmbreeScene& e = *tree;
      const std::pair<const char*, Caster> entry_points[] = {
          {"rtcIntersect1", [&](const CastRay* r, std::size_t n, CastHit* h) { e.intersect1(r, n, h); }},
          {"rtcIntersect16", [&](const CastRay* r, std::size_t n, CastHit* h) { e.intersect16(r, n, h); }}};
      for (const auto& [entry, caster] : entry_points) {
        std::vector<CastHit> hits;
        cast_all(pool, caster, rays, hits);
        const double agree = agreement(reference, hits);
        const std::string label = name + " " + entry;
        if (agree < kRequiredAgreement) {
          std::fprintf(stderr, "bench_rays: %s: %s agrees with soundpaint on only %.4f %% of the rays\n", spec.c_str(),
                       label.c_str(), agree * 100.0);
          return 1;
        }
        const double rate = rays_per_second(pool, caster, rays, options.runs);
        best_embree = std::max(best_embree, rate);
        if (caster_is_single_ray(entry)) best_single_ray = std::max(best_single_ray, rate);
        casts.push_back({{"caster", label}, {"rays_per_second", rate}, {"agreement", agree}});
      }
    }
    std::printf("  cast %zu rays (%.1f %% hit)   Mrays/s   agreement   soundpaint / this\n", rays.size(),
                hit_fraction * 100.0);
    for (const Json& c : casts)
      std::printf("    %-32s %9.3f %10.4f %% %10.3f\n", c["caster"].get<std::string>().c_str(),
                  c["rays_per_second"].get<double>() * 1e-6, c["agreement"].get<double>() * 100.0,
                  soundpaint_rate / c["rays_per_second"].get<double>());
    if (embree) {
      std::printf("  CPU backend rays/s (closest_hit) / Embree rays/s (best above) = %.3f\n",
                  soundpaint_rate / best_embree);
      std::printf("  CPU backend rays/s (closest_hit) / Embree rays/s (best rtcIntersect1) = %.3f\n",
                  soundpaint_rate / best_single_ray);
    }
    row["rays"] = rays.size();
    row["hit_fraction"] = hit_fraction;
    row["bvh_builds"] = builds;
    row["casts"] = casts;
    row["soundpaint_over_best_embree"] = embree ? Json(soundpaint_rate / best_embree) : Json(nullptr);
    row["soundpaint_over_best_single_ray_embree"] = embree ? Json(soundpaint_rate / best_single_ray) : Json(nullptr);

    // The simulation backends stepping the same scene.
    Json backends_json = Json::array();
    if (!options.backends.empty()) {
      const auto backends = spbench::usable_backends(world, options.backends, threads);
      const std::string disagreement = spbench::backends_disagree(world, spbench::names(backends), threads, 3);
      if (!disagreement.empty()) {
        std::fprintf(stderr, "bench_rays: %s: backends disagree: %s\n", spec.c_str(), disagreement.c_str());
        return 1;
      }
      for (const spbench::BackendInfo& backend : backends) {
        auto sim = spbench::make_simulator(world, backend.name, threads).value();
        const spbench::LoopSummary s = spbench::summarize({spbench::run_frame_loop(*sim, options.loop)});
        std::printf("  %s backend at %u rays/step: %.3f ms/step median, %.0f casts/step, %.3f Mcasts/s\n",
                    backend.name.c_str(), options.budget, s.ms_median, s.casts_per_step, s.casts_per_second * 1e-6);
        Json b = {{"backend", backend.name}, {"device", backend.device}, {"budget", options.budget}};
        b.update(spbench::to_json(s));
        backends_json.push_back(b);
      }
    }
    row["backends"] = backends_json;
    scenes.push_back(row);
    std::fflush(stdout);
  }

  if (!options.json.empty()) {
    Json document = {{"benchmark", "bench_rays"},
                     {"host", spbench::host_description()},
                     {"cpu_walk", spbench::cpu_walk_name()},
                     {"embree", embree ? Json(*embree) : Json(nullptr)},
                     {"embree_accel", options.embree_accel.empty() ? Json(nullptr) : Json(options.embree_accel)},
                     {"settings",
                      {{"threads", threads},
                       {"rays", options.rays},
                       {"budget", options.budget},
                       {"runs", options.runs},
                       {"build_runs", options.build_runs},
                       {"traversal_cost", options.bvh.traversal_cost},
                       {"pattern", spbench::pattern_name(options.pattern)},
                       {"sim_steps", options.loop.steps},
                       {"sim_warmup", options.loop.warmup},
                       {"sim_max_seconds", options.loop.max_seconds}}},
                     {"rays_definition",
                      "emitted rays of consecutive steps (first wavefront iteration): origin = source position, "
                      "direction = sp_emission_direction, tmin = 0, tmax = sp_active_reach"},
                     {"agreement_definition", "both miss, or both hit with |t1 - t2| <= 1e-4 * max(t1, t2)"},
                     {"scenes", scenes}};
    spbench::write_json(cli, options.json, document);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return spbench::bench_main(argc, argv, "bench_rays", kUsage, parse, run); }
