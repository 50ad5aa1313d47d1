#include <cstdio>
#include <optional>

#include "check/check_report_json.h"
#include "cli/commands.h"
#include "cli/limit_options.h"
#include "cli/options.h"
#include "core/printable_text.h"
#include "io/atomic_file.h"
#include "soundpaint/check.h"

namespace sp::cli {
namespace {

constexpr const char* kCheckHelp =
    "usage: soundpaint check SCENE [--config FILE] [--json OUT.json] [--memory-budget SIZE] [--max-triangles N]\n"
    "                        [--allow-external-uris]\n"
    "\n"
    "Tells whether SCENE suits the ray model before you wonder why sound never\n"
    "goes through a wall: open edges, inconsistent winding, degenerate triangles,\n"
    "units that are probably not metres, a short probe simulation that counts\n"
    "how often a ray that penetrates a surface finds no way out of matter, and a\n"
    "config whose rays and indicators need more than the memory budget.\n"
    "Prints one line per finding, each saying what to do about it. Findings are\n"
    "advice: the exit status is 0 whenever the scene and config load.\n"
    "  --config FILE   JSON configuration (its layers decide which are sheets)\n"
    "  --json FILE     also write {\"triangles\", \"findings\": [{\"code\", \"count\", \"message\",\n"
    "                  \"layers\": [{\"name\", \"count\"}]}], \"probe\": {...}}: names exact, in JSON\n"
    "Names from the scene and config (layers) are printed escaped: control\n"
    "characters as \\u{1b}, bytes that are not UTF-8 as \\xff (README: Security).\n";

}  // namespace

int run_check(const std::vector<std::string>& args) {
  ParsedArgs parsed = parse_args(
      args, with_options(with_options({"--config", "--json"}, kSceneLimitValueOptions), kMemoryLimitValueOptions),
      with_options({"--help"}, kSceneLimitFlagOptions));
  if (printed_help(parsed, {kCheckHelp, scene_limit_help(), memory_limit_help()})) return 0;
  const std::string& scene_path = scene_argument(parsed, "check");
  CheckSettings settings;
  settings.memory_budget_bytes = memory_budget(parsed);
  Config config;
  if (auto path = parsed.value("--config")) config = load_config(*path).value();
  std::optional<AtomicFile> json_file;
  if (auto path = parsed.value("--json")) json_file.emplace(*path);  // a refused output fails before the scene is read
  const Scene scene = load_scene(scene_path, scene_load_options(parsed)).value();

  const CheckReport report = check_scene(scene, config, settings).value();
  std::printf("scene: %s\ntriangles: %llu\n", printable_text(scene.path.string()).c_str(),
              static_cast<unsigned long long>(report.triangles));
  std::printf(
      "probe: %llu penetrations, %.1f%% found no way out (%.1f%% within max_wall_thickness); %llu hits, "
      "%llu on the back of a face\n",
      static_cast<unsigned long long>(report.probe.penetrations), 100.0 * report.probe.miss_share(),
      100.0 * report.probe_at_config.miss_share(), static_cast<unsigned long long>(report.probe.hits),
      static_cast<unsigned long long>(report.probe.back_face_hits));
  if (report.findings.empty()) std::printf("no findings: closed, consistently wound solids in metres\n");
  // The library escapes the names in its messages; escaping again changes
  // nothing then, and keeps this one line whatever a message holds.
  for (const CheckFinding& f : report.findings)
    std::printf("%s: %s\n", f.code.c_str(), printable_text(f.message).c_str());
  if (json_file) {
    json_file->write(check_report_json(report));
    json_file->commit();
  }
  return 0;
}

}  // namespace sp::cli
