// The soundpaint executable end to end: the contract of SPEC section 4.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "io/output.h"
#include "sp_types.h"
#include "support/run_command.h"
#include "support/vulkan_environment.h"

namespace sp {
namespace {

using test::run_command;
using test::ScratchDir;

const std::string kCli = SP_CLI_PATH;
const std::string kScenes = SP_SCENES_DIR;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) result.push_back(line);
  return result;
}

std::size_t count_files(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

TEST(Cli, SimulateWritesTheContractCsvAndStats) {
  ScratchDir dir("simulate");
  auto r =
      run_command(kCli + " simulate " + kScenes + "/two_rooms.gltf --backend cpu --steps 20 --seed 3 --indicators " +
                      (dir / "ind.csv").string() + " --stats " + (dir / "stats.json").string(),
                  dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  auto csv = lines(test::read_text(dir / "ind.csv"));
  ASSERT_GE(csv.size(), 2u);
  EXPECT_EQ(csv[0], kIndicatorCsvHeader);
  auto stats = nlohmann::json::parse(test::read_text(dir / "stats.json"));
  EXPECT_EQ(stats["steps"], 20);
  EXPECT_EQ(stats["backend"], "cpu");
  EXPECT_EQ(stats["indicators"].get<std::size_t>(), csv.size() - 1);
  EXPECT_GE(stats["casts"].get<std::uint64_t>(), stats["rays_emitted"].get<std::uint64_t>());
  EXPECT_GT(stats["max_casts_per_step"].get<std::uint64_t>(), 0u);
  EXPECT_TRUE(stats["timing"].contains("ms_per_step_median"));
  EXPECT_TRUE(stats["timing"].contains("ms_per_step_p99"));
  std::uint64_t hits = 0;
  for (const auto& [name, layer] : stats["layers"].items()) {
    for (const char* key : {"hits", "reflections", "penetrations", "no_way_out", "backcast_misses"})
      EXPECT_TRUE(layer.contains(key)) << name << " " << key;
    EXPECT_EQ(layer["backcast_misses"], layer["no_way_out"]) << "the deprecated name counts the same";
    hits += layer["hits"].get<std::uint64_t>();
  }
  EXPECT_GE(hits, stats["indicators"].get<std::uint64_t>() / 2);
  // every row has 27 fields and a known kind; the step column counts up;
  // dx,dy,dz is the unit direction of travel: into the surface for a hit
  // (against the normal, which faces the ray's side), out of it for an exit;
  // heard is what arrives at the listener, never more than the spot's
  // energy; ax,ay,az the unit way from the listener to the spot; toward in
  // [0, 1], never without hearing
  int last_step = -1;
  std::size_t heard = 0;
  for (std::size_t k = 1; k < csv.size(); ++k) {
    EXPECT_EQ(std::count(csv[k].begin(), csv[k].end(), ','), 26) << csv[k];
    std::vector<double> f;
    std::stringstream fields(csv[k]);
    for (std::string cell; std::getline(fields, cell, ',');)
      f.push_back(cell == "hit" || cell == "exit" ? 0.0 : std::stod(cell));
    ASSERT_EQ(f.size(), 27u);
    const double dx = f[18], dy = f[19], dz = f[20], along_normal = dx * f[6] + dy * f[7] + dz * f[8];
    EXPECT_NEAR(dx * dx + dy * dy + dz * dz, 1.0, 1e-5) << csv[k];
    EXPECT_TRUE(csv[k].find(",hit,") != std::string::npos ? along_normal < 0.0 : along_normal > 0.0) << csv[k];
    EXPECT_EQ(f[21], 0.0) << "no diffraction without the key";
    EXPECT_GE(f[22], 0.0) << csv[k];
    EXPECT_LE(f[22], f[9]) << csv[k];
    EXPECT_NEAR(f[23] * f[23] + f[24] * f[24] + f[25] * f[25], 1.0, 1e-5) << csv[k];
    EXPECT_GE(f[26], 0.0) << csv[k];
    EXPECT_LE(f[26], 1.0) << csv[k];
    if (f[22] == 0.0) {
      EXPECT_EQ(f[26], 0.0) << csv[k];
    }
    heard += f[22] > 0.0 ? 1 : 0;
    int step = std::stoi(csv[k]);
    EXPECT_GE(step, last_step);
    last_step = step;
    auto kind = csv[k].substr(csv[k].find(',') + 1, 4);
    EXPECT_TRUE(kind == "hit," || kind == "exit") << csv[k];
  }
  EXPECT_GT(heard, 0u) << "the listener, inside the level, hears some spots";
  EXPECT_EQ(count_files(dir.path()), 4u);  // ind.csv, stats.json, stdout, stderr: no temporaries left
}

TEST(Cli, SameSeedGivesTheSameCsv) {
  ScratchDir dir("seed");
  auto run = [&](const std::string& name, const std::string& extra) {
    auto r = run_command(kCli + " simulate " + kScenes + "/closed_room.gltf --backend cpu --steps 5 --seed 9 " + extra +
                             " --indicators " + (dir / name).string(),
                         dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    return test::read_text(dir / name);
  };
  std::string a = run("a.csv", "--threads 1");
  EXPECT_EQ(a, run("b.csv", "--threads 3"));
  EXPECT_GT(lines(a).size(), 10u);
}

// SPEC 1.3.2: with diffraction off (or the key absent) nothing changes, to
// the byte; with it on, the stats count the turns in total and per layer
// and the CSV's last column counts them per indicator.
TEST(Cli, DiffractionOffChangesNothingAndOnIsCounted) {
  ScratchDir dir("diffraction");
  std::ofstream(dir / "off_config.json") << R"({"diffraction": {"enabled": false, "reach": 2.0}})";
  std::ofstream(dir / "on_config.json") << R"({"diffraction": {"enabled": true}})";
  auto run = [&](const std::string& name, const std::string& extra) {
    auto r = run_command(kCli + " simulate " + kScenes + "/level.gltf --backend cpu --steps 10 --seed 4 " + extra +
                             " --indicators " + (dir / (name + ".csv")).string() + " --stats " +
                             (dir / (name + ".json")).string(),
                         dir.path());
    EXPECT_EQ(r.status, 0) << r.err;
    return test::read_text(dir / (name + ".csv"));
  };
  const std::string none = run("none", "");
  EXPECT_EQ(none, run("off", "--config " + (dir / "off_config.json").string()));
  const std::string on = run("on", "--config " + (dir / "on_config.json").string());
  EXPECT_NE(none, on);
  const auto stats = nlohmann::json::parse(test::read_text(dir / "on.json"));
  const auto stats_none = nlohmann::json::parse(test::read_text(dir / "none.json"));
  EXPECT_EQ(stats_none["diffractions"].get<std::uint64_t>(), 0u);
  std::uint64_t per_layer = 0;
  for (const auto& [name, layer] : stats["layers"].items()) per_layer += layer["diffractions"].get<std::uint64_t>();
  EXPECT_GT(stats["diffractions"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(stats["diffractions"].get<std::uint64_t>(), per_layer);
  std::size_t turned_rows = 0;
  for (const std::string& row : lines(on)) turned_rows += row.substr(row.rfind(',') + 1) != "0" && row[0] != 's';
  EXPECT_GT(turned_rows, 0u);
}

TEST(Cli, InfoDescribesTheScene) {
  ScratchDir dir("info");
  auto r = run_command(kCli + " info " + kScenes + "/two_rooms.gltf", dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* needle : {"triangles:", "layers:", "wood", "sources:", "listener:", "bvh:", "nodes"})
    EXPECT_NE(r.out.find(needle), std::string::npos) << needle << "\n" << r.out;
  // The floor's top is y = 0 (scenes/generate_scenes.py): the listener
  // stands at y 1.6, the stereo at 1.2.
  for (const char* needle : {"listener   1.600 m above concrete", "source 0   1.200 m above concrete"})
    EXPECT_NE(r.out.find(needle), std::string::npos) << needle << "\n" << r.out;
}

TEST(Cli, HelpForEveryCommand) {
  ScratchDir dir("help");
  for (const char* command : {"", "simulate ", "info "}) {
    auto r = run_command(kCli + " " + command + "--help", dir.path());
    EXPECT_EQ(r.status, 0) << command;
    EXPECT_NE(r.out.find("usage: soundpaint"), std::string::npos) << command;
  }
}

// Bad input: non-zero exit, one line on stderr naming the problem, no file.
void expect_clean_failure(const std::string& args, const std::string& needle) {
  ScratchDir dir("bad");
  auto out = dir / "out.csv";
  auto r = run_command(kCli + " " + args + " --indicators " + out.string(), dir.path());
  EXPECT_NE(r.status, 0) << args;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << args;
  EXPECT_EQ(count_files(dir.path()), 2u) << args;  // stdout.txt and stderr.txt only
}

TEST(Cli, BadInputFailsCleanly) {
  const std::string scene = kScenes + "/closed_room.gltf";
  expect_clean_failure("simulate /nonexistent/level.gltf", "/nonexistent/level.gltf");
  expect_clean_failure("simulate " + scene + " --steps ten", "--steps");
  expect_clean_failure("simulate " + scene + " --steps -3", "--steps");
  expect_clean_failure("simulate " + scene + " --seed 99999999999", "--seed");
  expect_clean_failure("simulate " + scene + " --frobnicate 1", "--frobnicate");
  expect_clean_failure("simulate " + scene + " --backend quantum", "--backend");
  expect_clean_failure("simulate " + scene + " --config /nonexistent.json", "/nonexistent.json");
  expect_clean_failure("simulate " + scene + " --steps", "--steps");
  expect_clean_failure("simulate", "SCENE");
  expect_clean_failure("explode " + scene, "explode");
}

TEST(Cli, BadConfigNamesTheKey) {
  ScratchDir dir("config");
  auto config = dir / "c.json";
  std::ofstream(config) << R"({"ray_budget": 100, "max_wall_thicknes": 0.3})";
  expect_clean_failure("simulate " + kScenes + "/closed_room.gltf --config " + config.string(), "max_wall_thicknes");
  std::ofstream(config, std::ios::trunc) << R"({"bounce_energy_loss": 1.5})";
  expect_clean_failure("simulate " + kScenes + "/closed_room.gltf --config " + config.string(), "bounce_energy_loss");
}

TEST(Cli, UnwritableOutputFailsBeforeSimulating) {
  ScratchDir dir("unwritable");
  auto r = run_command(kCli + " simulate " + kScenes +
                           "/closed_room.gltf --steps 5 --indicators /nonexistent-dir/x.csv --stats " +
                           (dir / "s.json").string(),
                       dir.path());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("/nonexistent-dir/x.csv"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "s.json"));
  auto into_dir = run_command(
      kCli + " simulate " + kScenes + "/closed_room.gltf --steps 1 --stats " + dir.path().string(), dir.path());
  EXPECT_NE(into_dir.status, 0);
  EXPECT_NE(into_dir.err.find("directory"), std::string::npos) << into_dir.err;
}

TEST(Cli, WithoutAVulkanDeviceGpuFailsAndAutoFallsBackToCpu) {
  ScratchDir dir("novulkan");
  // Points the Vulkan loader at a driver manifest that does not exist.
  const std::string no_driver = "VK_DRIVER_FILES=/nonexistent/icd.json VK_ICD_FILENAMES=/nonexistent/icd.json ";
  const std::string scene = kScenes + "/closed_room.gltf";
  auto gpu = run_command(no_driver + kCli + " simulate " + scene + " --backend gpu --steps 2 --stats " +
                             (dir / "gpu.json").string(),
                         dir.path());
  EXPECT_NE(gpu.status, 0);
  EXPECT_NE(gpu.err.find("no Vulkan device"), std::string::npos) << gpu.err;
  EXPECT_EQ(std::count(gpu.err.begin(), gpu.err.end(), '\n'), 1) << gpu.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "gpu.json"));

  auto fallback = run_command(
      no_driver + kCli + " simulate " + scene + " --steps 2 --stats " + (dir / "auto.json").string(), dir.path());
  ASSERT_EQ(fallback.status, 0) << fallback.err;
  EXPECT_NE(fallback.err.find("using the CPU backend"), std::string::npos) << fallback.err;
  EXPECT_EQ(nlohmann::json::parse(test::read_text(dir / "auto.json"))["backend"], "cpu");
}

TEST(Cli, AutoNeverPicksACpuVulkanDevice) {
  // lavapipe is a CPU behind Vulkan: there the CPU backend is faster, so
  // auto must use it (and say why); on a hardware GPU auto uses the GPU.
  ScratchDir dir("auto");
  auto r = run_command(
      kCli + " simulate " + kScenes + "/closed_room.gltf --steps 2 --stats " + (dir / "s.json").string(), dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  auto stats = nlohmann::json::parse(test::read_text(dir / "s.json"));
  if (stats["backend"] == "gpu") {
    EXPECT_EQ(stats["device"].get<std::string>().find("llvmpipe"), std::string::npos) << stats["device"];
  } else {
    EXPECT_NE(r.err.find("using the CPU backend"), std::string::npos) << r.err;
  }
}

TEST(Cli, GpuBackendRunsCleanUnderTheValidationLayer) {
  ScratchDir dir("gpu");
  // Validation messages go to stderr, so a clean run leaves it empty.
  auto r = run_command("SOUNDPAINT_VALIDATION=1 " + kCli + " simulate " + kScenes +
                           "/two_rooms.gltf --backend gpu --steps 5 --stats " + (dir / "s.json").string() +
                           " --indicators " + (dir / "i.csv").string(),
                       dir.path());
  SKIP_WITHOUT_VULKAN(r);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  auto stats = nlohmann::json::parse(test::read_text(dir / "s.json"));
  EXPECT_EQ(stats["backend"], "gpu");
  EXPECT_TRUE(stats["timing"].contains("gpu_ms_per_step_median"));
  EXPECT_EQ(stats["indicators"].get<std::size_t>() + 1, lines(test::read_text(dir / "i.csv")).size());
}


// ------------------------------------------------------------ check (issue 10)

const std::string kTestData = SP_TEST_DATA_DIR;

std::vector<std::string> finding_codes(const nlohmann::json& report) {
  std::vector<std::string> codes;
  for (const auto& f : report["findings"]) {
    EXPECT_FALSE(f["message"].get<std::string>().empty());
    EXPECT_GT(f["count"].get<std::uint64_t>(), 0u);
    codes.push_back(f["code"].get<std::string>());
  }
  return codes;
}

TEST(Cli, CheckFindsNothingOnAClosedBoxRoom) {
  ScratchDir dir("check-closed");
  auto r =
      run_command(kCli + " check " + kScenes + "/closed_room.gltf --json " + (dir / "c.json").string(), dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("no findings"), std::string::npos) << r.out;
  auto report = nlohmann::json::parse(test::read_text(dir / "c.json"));
  EXPECT_EQ(report["triangles"], 72);
  EXPECT_TRUE(report["findings"].empty()) << report.dump();
}

TEST(Cli, CheckFlagsTheRenderMeshAsOpen) {
  ScratchDir dir("check-render");
  auto r = run_command(kCli + " check " + kTestData + "/issue-10-render-mesh.gltf --json " + (dir / "c.json").string(),
                       dir.path());
  ASSERT_EQ(r.status, 0) << r.err;  // findings are advice
  auto codes = finding_codes(nlohmann::json::parse(test::read_text(dir / "c.json")));
  EXPECT_NE(std::find(codes.begin(), codes.end(), "open_edges"), codes.end());
  EXPECT_NE(std::find(codes.begin(), codes.end(), "penetration_misses"), codes.end());
  EXPECT_NE(r.out.find("open_edges: "), std::string::npos) << r.out;
  // The same place built from closed brushes is not open.
  auto brushes = run_command(kCli + " check " + kTestData + "/issue-10-touching-brushes.gltf", dir.path());
  ASSERT_EQ(brushes.status, 0) << brushes.err;
  EXPECT_EQ(brushes.out.find("open_edges"), std::string::npos) << brushes.out;
  EXPECT_EQ(brushes.out.find("penetration_misses"), std::string::npos) << brushes.out;
}

TEST(Cli, CheckRejectsBadInputInOneLine) {
  ScratchDir dir("check-bad");
  auto none = run_command(kCli + " check", dir.path());
  EXPECT_EQ(none.status, 2);
  auto missing =
      run_command(kCli + " check " + (dir / "nope.gltf").string() + " --json " + (dir / "c.json").string(), dir.path());
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("nope.gltf"), std::string::npos) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.json"));
}

TEST(Cli, TouchingBrushesNeverExitAtTheirContact) {
  // Wall brushes at x in [1, 1.2] and [1.2, 1.5] that always let rays in:
  // rays through them leave at x = 1.5 (or their top and sides), never at
  // the contact plane x = 1.2.
  ScratchDir dir("touching");
  std::ofstream(dir / "c.json") << R"({"layers": {"concrete": {"reflect_probability": 0, "attenuation": 0.5}},
                                       "max_wall_thickness": 1.0, "air_attenuation": 0})";
  auto r = run_command(kCli + " simulate " + kTestData + "/issue-10-touching-brushes.gltf --backend cpu --steps 30 " +
                           "--config " + (dir / "c.json").string() + " --indicators " + (dir / "i.csv").string(),
                       dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  int at_far_side = 0;
  for (const std::string& row : lines(test::read_text(dir / "i.csv"))) {
    std::vector<std::string> f;
    std::stringstream fields(row);
    for (std::string cell; std::getline(fields, cell, ',');) f.push_back(cell);
    if (f.size() < 9 || f[1] != "exit") continue;
    const double x = std::stod(f[3]), y = std::stod(f[4]), z = std::stod(f[5]);
    const bool on_wall = y > 0.01 && y < 2.99 && z > -2.99 && z < 2.99;
    EXPECT_FALSE(on_wall && std::abs(x - 1.2) < 1e-3) << row;
    at_far_side += on_wall && std::abs(x - 1.5) < 1e-3;
  }
  EXPECT_GT(at_far_side, 20);
}

}  // namespace
}  // namespace sp
