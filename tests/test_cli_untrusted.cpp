// The soundpaint executable given hostile input (README "Security"): every
// input of the attack that found issue 16, kept in tests/data/issue-16-*,
// gets a clean non-zero exit with a one-line message, or succeeds by a
// documented rule; outputs never replace what is not a regular file; names
// from levels and configs are printed escaped (issue 39); check reports a
// config over the memory budget as advice it can follow (issue 39).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sp_types.h"
#include "support/gltf_builder.h"
#include "support/run_command.h"

namespace {

namespace fs = std::filesystem;
using sp::test::run_command;
using sp::test::ScratchDir;

const std::string kCli = SP_CLI_PATH;
const std::string kData = SP_TEST_DATA_DIR;
const std::string kRoom = std::string(SP_SCENES_DIR) + "/closed_room.gltf";

// Exit status 1 (bad input) with exactly one line on stderr naming `what`.
void expect_clean_failure(const std::string& args, const std::string& what, int status = 1) {
  SCOPED_TRACE(args);
  ScratchDir dir("cli-untrusted");
  const auto r = run_command(kCli + " " + args, dir.path());
  EXPECT_EQ(r.status, status) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("soundpaint: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
}

TEST(CliUntrusted, SceneUrisLeavingTheFolderAreRefusedNamingThem) {
  expect_clean_failure("info " + kData + "/issue-16-uri-parent.gltf",
                       "buffer URI \"../../../../../../../../../../etc/passwd\": leads out of the scene's folder");
  expect_clean_failure("info " + kData + "/issue-16-uri-absolute.gltf",
                       "buffer URI \"/etc/passwd\": is an absolute path");
  expect_clean_failure(
      "simulate " + kData + "/issue-16-uri-percent.gltf --steps 1",
      "buffer URI \"%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/passwd\"");
  expect_clean_failure("info " + kData + "/issue-16-uri-proc.gltf", "buffer URI \"/proc/self/environ\"");
  expect_clean_failure("info " + kData + "/issue-16-uri-proc.gltf --allow-external-uris",
                       "buffer URI \"/proc/self/environ\": names a file under /proc");
}

// Images are never read, so a texture pointing anywhere is no error.
TEST(CliUntrusted, ImagesAreNeverReadSoTheirUrisDoNotMatter) {
  ScratchDir dir("cli-image");
  const auto r = run_command(kCli + " info " + kData + "/issue-16-image-shadow.gltf", dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("triangles: 1"), std::string::npos) << r.out;
}

TEST(CliUntrusted, DeepJsonFailsInsteadOfCrashing) {
  expect_clean_failure("info " + kData + "/issue-16-deep-extras.gltf",
                       "issue-16-deep-extras.gltf: cannot load glTF: JSON nested deeper than 128 levels");
  expect_clean_failure("simulate " + kRoom + " --config " + kData + "/issue-16-deep-config.json",
                       "issue-16-deep-config.json: JSON nested deeper than 128 levels at \"listener[0]");
}

TEST(CliUntrusted, ImpossibleConfigFailsAtOnceNamingTheKnobs) {
  expect_clean_failure("simulate " + kRoom + " --backend cpu --config " + kData + "/issue-16-max-config.json",
                       "over the memory budget of 2.0 GiB: lower those keys, or raise the budget (--memory-budget");
  ScratchDir dir("cli-budget");
  const auto raised =
      run_command(kCli + " simulate " + kRoom + " --backend cpu --steps 1 --memory-budget 64M", dir.path());
  EXPECT_EQ(raised.status, 0) << raised.err;
  expect_clean_failure("simulate " + kRoom + " --backend cpu --memory-budget 1M", "memory budget of 1.0 MiB");
  expect_clean_failure("simulate " + kRoom + " --memory-budget 4Q", "option --memory-budget", 2);
}

TEST(CliUntrusted, DevicesAreNeverReadAsScenesOrConfigs) {
  expect_clean_failure("info /dev/zero", "/dev/zero: is not a regular file");
  expect_clean_failure("info " + kRoom + " --config /dev/zero",
                       "/dev/zero: cannot read config file: is not a regular file");
}

TEST(CliUntrusted, TriangleLimitIsAnOption) {
  expect_clean_failure("info " + kRoom + " --max-triangles 71", "more than 71 triangles over its");
  ScratchDir dir("cli-triangles");
  const auto r = run_command(kCli + " info " + kRoom + " --max-triangles 72", dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  expect_clean_failure("info " + kRoom + " --max-triangles 0", "option --max-triangles", 2);
}

TEST(CliUntrusted, OutputsAreRegularFilesOrStandardOutput) {
  expect_clean_failure(
      "simulate " + kRoom + " --steps 1 --stats /dev/null",
      "cannot write /dev/null: not a regular file (a device, FIFO or socket); give - for standard output");
  expect_clean_failure("simulate " + kRoom + " --steps 1 --stats /dev/stdout",
                       "cannot write /dev/stdout: it leads into /proc");
  ScratchDir dir("cli-outputs");
  const std::string same = (dir / "x.json").string();
  expect_clean_failure("simulate " + kRoom + " --indicators " + same + " --stats " + same,
                       "options --indicators and --stats name the same output", 2);
  EXPECT_FALSE(fs::exists(dir / "x.json"));

  // "-": the stats on standard output, the summary line on stderr.
  const auto to_stdout = run_command(kCli + " simulate " + kRoom + " --backend cpu --steps 2 --stats -", dir.path());
  ASSERT_EQ(to_stdout.status, 0) << to_stdout.err;
  EXPECT_EQ(nlohmann::json::parse(to_stdout.out)["steps"], 2);
  EXPECT_NE(to_stdout.err.find("2 steps on cpu"), std::string::npos) << to_stdout.err;

  // A symbolic link is written through; it stays a link.
  fs::create_symlink("runs/latest.csv", dir / "link.csv");
  fs::create_directory(dir / "runs");
  const auto through = run_command(
      kCli + " simulate " + kRoom + " --backend cpu --steps 1 --indicators " + (dir / "link.csv").string(), dir.path());
  ASSERT_EQ(through.status, 0) << through.err;
  EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
  EXPECT_EQ(sp::test::read_text(dir / "runs" / "latest.csv").rfind("step,kind,source,", 0), 0u);
}

// A name as a hostile level writes it: a new terminal title, a cleared
// screen, a red pen, and a forged line of output after a line feed.
const std::string kHostileName = "wood\x1b]0;pwned\x07\x1b[2J\nsoundpaint: no findings\r\x1b[31m";
const std::string kHostileNameEscaped =
    "wood\\u{1b}]0;pwned\\u{7}\\u{1b}[2J\\u{a}soundpaint: no findings\\u{d}\\u{1b}[31m";

void write_file(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// One triangle of a material named `name`, and a sound source whose node
// and category are named `name` too.
void write_hostile_level(const fs::path& path, const std::string& name) {
  sp::test::GltfBuilder b;
  b.doc["materials"] = nlohmann::json::array({{{"name", name}}});
  b.root(b.node({{"mesh", b.unit_triangle_mesh({{"material", 0}})}}));
  b.root(
      b.node({{"name", name}, {"translation", {0.2, 0.2, 0.2}}, {"extras", {{"sound_source", {{"category", name}}}}}}));
  write_file(path, b.gltf());
}

// Neither stream holds a control character but the line feeds that end
// lines, and no line starts with the forged text.
void expect_no_escapes(const sp::test::CommandResult& r) {
  for (const std::string* stream : {&r.out, &r.err}) {
    EXPECT_EQ(std::count_if(stream->begin(), stream->end(),
                            [](char c) { return (static_cast<unsigned char>(c) < 0x20 && c != '\n') || c == 0x7f; }),
              0)
        << *stream;
    EXPECT_EQ(stream->find("\nsoundpaint: no findings"), std::string::npos) << *stream;
    EXPECT_NE(stream->rfind("soundpaint: no findings", 0), 0u) << *stream;
  }
}

TEST(CliUntrusted, InfoPrintsNamesFromTheLevelAndConfigEscaped) {
  ScratchDir dir("cli-names-info");
  write_hostile_level(dir / "level.gltf", kHostileName);
  const std::string category = "cat\x1b]0;config\x07\n";
  write_file(dir / "config.json",
             nlohmann::json({{"sources", {{{"position", {0, 0.5, 0}}, {"category", category}}}}}).dump());
  const auto r = run_command(
      kCli + " info " + (dir / "level.gltf").string() + " --config " + (dir / "config.json").string(), dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_escapes(r);
  EXPECT_NE(r.out.find("\n  " + kHostileNameEscaped + " "), std::string::npos) << r.out;  // the layer
  EXPECT_NE(r.out.find("  0 " + kHostileNameEscaped + " " + kHostileNameEscaped + " at "), std::string::npos)
      << r.out;  // the level's source: its node's name and its category
  EXPECT_NE(r.out.find("cat\\u{1b}]0;config\\u{7}\\u{a}"), std::string::npos) << r.out;  // the config's category
}

// Error messages quote what they could not read: a config cut off inside a
// string that holds escape sequences, and a scene whose glTF JSON breaks
// inside one, reach stderr escaped, on one line.
TEST(CliUntrusted, ErrorsQuotingTheInputAreEscaped) {
  ScratchDir dir("cli-names-errors");
  write_file(dir / "config.json", "{\"ray_budget\": 1, \"x\": \"\xff\x1b]0;title\x07\x1b[2J\n");
  write_file(dir / "scene.gltf", "{\"asset\": {\"version\": \"\xff\x1b[2J");
  for (const std::string& args :
       {"simulate " + kRoom + " --config " + (dir / "config.json").string(), "info " + (dir / "scene.gltf").string()}) {
    SCOPED_TRACE(args);
    const auto r = run_command(kCli + " " + args, dir.path());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    expect_no_escapes(r);
    EXPECT_EQ(r.err.find('\xff'), std::string::npos) << r.err;
  }
}

TEST(CliUntrusted, CheckPrintsNamesEscapedAndWritesThemExactlyInJson) {
  ScratchDir dir("cli-names-check");
  write_hostile_level(dir / "level.gltf", kHostileName);
  const auto r = run_command(
      kCli + " check " + (dir / "level.gltf").string() + " --json " + (dir / "check.json").string(), dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_escapes(r);
  EXPECT_NE(r.out.find("open_edges: 3 edges have surface on one side only (" + kHostileNameEscaped + " 3)"),
            std::string::npos)
      << r.out;
  const nlohmann::json report = nlohmann::json::parse(sp::test::read_text(dir / "check.json"));
  bool found = false;
  for (const nlohmann::json& finding : report["findings"]) {
    if (finding["code"] != "open_edges") continue;
    found = true;
    ASSERT_EQ(finding["layers"].size(), 1u) << finding;
    EXPECT_EQ(finding["layers"][0]["name"], kHostileName);
    EXPECT_EQ(finding["layers"][0]["count"], 3);
  }
  EXPECT_TRUE(found) << report;
}

TEST(CliUntrusted, CheckAdvisesABudgetForAConfigOverItAndTheAdviceWorks) {
  ScratchDir dir("cli-check-budget");
  const std::string config = (dir / "big.json").string();
  write_file(config, R"({"max_indicators": 16777216})");
  const auto over = run_command(kCli + " check " + kRoom + " --config " + config, dir.path());
  ASSERT_EQ(over.status, 0) << over.err;
  const std::size_t line = over.out.find("\nmemory_budget: ");
  ASSERT_NE(line, std::string::npos) << over.out;
  const std::string finding = over.out.substr(line + 1, over.out.find('\n', line + 1) - line - 1);
  EXPECT_NE(finding.find("max_indicators 16777216"), std::string::npos) << finding;
  EXPECT_NE(finding.find("ray_budget 500 with max_bounces 4"), std::string::npos) << finding;  // the config's
  EXPECT_EQ(finding.find("ray_budget 2000"), std::string::npos) << finding;                    // not the probe's
  const std::string option = "--memory-budget ";
  const std::size_t at = finding.find(option);
  ASSERT_NE(at, std::string::npos) << finding;
  const std::string advised =
      finding.substr(at + option.size(), finding.find(' ', at + option.size()) - at - option.size());

  const auto raised =
      run_command(kCli + " check " + kRoom + " --config " + config + " --memory-budget " + advised, dir.path());
  ASSERT_EQ(raised.status, 0) << raised.err;
  EXPECT_EQ(raised.out.find("memory_budget"), std::string::npos) << advised << ": " << raised.out;
  const auto lowered = run_command(kCli + " check " + kRoom + " --memory-budget 1M", dir.path());
  ASSERT_EQ(lowered.status, 0) << lowered.err;
  EXPECT_NE(lowered.out.find("over the memory budget of 1.0 MiB"), std::string::npos) << lowered.out;
  expect_clean_failure("check " + kRoom + " --memory-budget 4Q", "option --memory-budget", 2);
}

// The load's refusal names --memory-budget; info takes it as every command
// that loads a scene does, and the advice works there too.
TEST(CliUntrusted, InfoTakesTheMemoryBudgetItsRefusalNames) {
  ScratchDir dir("cli-info-budget");
  const auto tight = run_command(kCli + " info " + kRoom + " --memory-budget 1K", dir.path());
  EXPECT_EQ(tight.status, 1) << tight.out;
  EXPECT_NE(tight.err.find("--memory-budget"), std::string::npos) << tight.err;
  const auto raised = run_command(kCli + " info " + kRoom + " --memory-budget 64M", dir.path());
  EXPECT_EQ(raised.status, 0) << raised.err;
  expect_clean_failure("info " + kRoom + " --memory-budget 4Q", "option --memory-budget", 2);
}

TEST(CliUntrusted, CheckCountsALevelBeyondFloatRangeSanely) {
  ScratchDir dir("cli-check-huge");
  // One triangle from -3e38 to 3e38: 6e38 across, more than a float holds.
  sp::test::GltfBuilder b;
  const nlohmann::json primitive = {
      {"attributes", {{"POSITION", b.positions({{-3e38f, 0, 0}, {3e38f, 0, 0}, {0, 3e38f, 0}})}}}};
  b.root(b.node({{"mesh", b.mesh(nlohmann::json::array({primitive}))}}));
  write_file(dir / "huge.gltf", b.gltf());
  const auto r = run_command(
      kCli + " check " + (dir / "huge.gltf").string() + " --json " + (dir / "check.json").string(), dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(sp::test::read_text(dir / "check.json"));
  bool scale = false;
  for (const nlohmann::json& finding : report["findings"]) {
    EXPECT_LE(finding["count"].get<std::uint64_t>(), std::uint64_t{1} << 53) << finding;
    if (finding["code"] == "scale") {
      scale = true;
      EXPECT_EQ(finding["count"].get<std::uint64_t>(), std::uint64_t{1} << 53) << finding;  // 6e38, clamped
    }
  }
  EXPECT_TRUE(scale) << report;
}

}  // namespace
