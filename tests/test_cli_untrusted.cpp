// The soundpaint executable given hostile input (README "Security"): every
// input of the attack that found issue 16, kept in tests/data/issue-16-*,
// gets a clean non-zero exit with a one-line message, or succeeds by a
// documented rule; outputs never replace what is not a regular file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sp_types.h"
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

}  // namespace
