// Where an output file goes (README "Command line"): regular files through
// a temporary file and a rename, symbolic links written through, "-" as
// standard output, and never a device, FIFO, /proc link or directory
// turned into a regular file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/output_path.h"
#include "io/output.h"
#include "soundpaint/result.h"
#include "support/test_directory.h"

namespace {

namespace fs = std::filesystem;

class OutputPath : public sp::test::TestDirectory {
 protected:
  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  static void write_atomically(const fs::path& path, const std::string& text) {
    sp::AtomicFile file(path);
    file.write(text);
    file.commit();
  }
  // The Io error `path` gets, which must name it and say `why`.
  static void expect_refused(const fs::path& path, const std::string& why) {
    SCOPED_TRACE(path.string());
    try {
      (void)sp::resolve_output(path);
      ADD_FAILURE() << "accepted";
    } catch (const sp::Exception& e) {
      EXPECT_EQ(e.error().code, sp::ErrorCode::Io);
      EXPECT_EQ(std::string(e.what()).rfind("cannot write " + path.string() + ": ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
    EXPECT_THROW(sp::AtomicFile file(path), sp::Exception);
  }
  // No temporary file was left (or created) in `folder`.
  static void expect_no_temporaries(const fs::path& folder) {
    for (const auto& entry : fs::directory_iterator(folder)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    }
  }
};

TEST_F(OutputPath, RegularFilesResolveToTheirAbsolutePath) {
  // As the kernel resolves paths: "sub/.." needs "sub".
  expect_refused(dir_ / "sub" / ".." / "out.csv", "its folder");
  EXPECT_TRUE(fs::create_directory(dir_ / "sub"));
  const sp::OutputTarget resolved = sp::resolve_output(dir_ / "sub" / ".." / "out.csv");
  EXPECT_FALSE(resolved.to_stdout);
  EXPECT_EQ(resolved.file, dir_ / "out.csv");
  write_atomically(dir_ / "out.csv", "a");
  write_atomically(dir_ / "out.csv", "bc");  // replaced whole
  EXPECT_EQ(read(dir_ / "out.csv"), "bc");
  expect_no_temporaries(dir_);
}

TEST_F(OutputPath, DashIsStandardOutput) {
  EXPECT_TRUE(sp::names_stdout("-"));
  EXPECT_FALSE(sp::names_stdout("./-"));
  EXPECT_TRUE(sp::resolve_output("-").to_stdout);
  ::testing::internal::CaptureStdout();
  write_atomically("-", "to stdout\n");
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "to stdout\n");
}

// A link is written through: the file it names gets the bytes and the link
// stays a link, even when the target does not exist yet or the link is
// relative to its own folder.
TEST_F(OutputPath, WritesThroughSymbolicLinks) {
  fs::create_directory(dir_ / "data");
  fs::create_symlink("data/run.json", dir_ / "latest.json");
  fs::create_symlink(dir_ / "latest.json", dir_ / "chain.json");
  EXPECT_EQ(sp::resolve_output(dir_ / "chain.json").file, dir_ / "data" / "run.json");
  write_atomically(dir_ / "chain.json", "first");
  EXPECT_TRUE(fs::is_symlink(dir_ / "latest.json"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "chain.json"));
  EXPECT_EQ(read(dir_ / "data" / "run.json"), "first");
  write_atomically(dir_ / "latest.json", "second");
  EXPECT_EQ(read(dir_ / "data" / "run.json"), "second");
  expect_no_temporaries(dir_);
  expect_no_temporaries(dir_ / "data");
  fs::create_symlink("loop.json", dir_ / "loop.json");
  expect_refused(dir_ / "loop.json", "too many levels of symbolic links");
}

// Run as root, a rename onto /dev/null used to replace the device node.
TEST_F(OutputPath, RefusesDevicesFifosAndDirectories) {
  expect_refused("/dev/null", "not a regular file");
  expect_no_temporaries("/dev");
  ASSERT_EQ(::mkfifo((dir_ / "pipe").c_str(), 0600), 0);
  expect_refused(dir_ / "pipe", "not a regular file");
  expect_refused(dir_, "it is a directory");
  expect_refused(dir_ / ".", "it is a directory");
  expect_refused(dir_ / "missing" / "out.csv", "its folder");
  fs::create_symlink("/dev/null", dir_ / "null.csv");
  expect_refused(dir_ / "null.csv", "not a regular file");
  expect_no_temporaries(dir_);
}

// /dev/stdout is a link into /proc/self/fd: followed, it would replace
// whatever file the shell redirected standard output to.
TEST_F(OutputPath, RefusesLinksIntoProc) {
  expect_refused("/dev/stdout", "/proc");
  expect_refused("/proc/self/fd/1", "/proc");
  fs::create_symlink("/proc/self/fd/2", dir_ / "err.csv");
  expect_refused(dir_ / "err.csv", "/proc");
}

TEST_F(OutputPath, TwoOutputsMayNotShareAFile) {
  fs::create_symlink("stats.json", dir_ / "alias.json");
  const std::vector<std::pair<fs::path, fs::path>> same = {
      {dir_ / "stats.json", dir_ / "stats.json"},
      {dir_ / "stats.json", dir_ / "." / "stats.json"},
      {dir_ / "stats.json", dir_ / "alias.json"},
      {"-", "-"},
  };
  for (const auto& [first, second] : same) {
    SCOPED_TRACE(first.string() + " / " + second.string());
    const std::vector<sp::NamedOutput> outputs = {{"--indicators", first}, {"--stats", second}};
    try {
      sp::check_distinct_outputs(outputs);
      ADD_FAILURE() << "accepted";
    } catch (const sp::Exception& e) {
      EXPECT_EQ(e.error().code, sp::ErrorCode::InvalidArgument);
      EXPECT_EQ(std::string(e.what()), "options --indicators and --stats name the same output " + second.string());
    }
  }
  const std::vector<sp::NamedOutput> distinct = {{"--indicators", dir_ / "a.csv"}, {"--stats", "-"}};
  EXPECT_NO_THROW(sp::check_distinct_outputs(distinct));
}

}  // namespace

namespace {

// The public writers return errors instead of throwing (issue 14).
TEST(PublicWriters, ReturnIoErrorsNamingThePath) {
  const auto csv = sp::IndicatorCsvWriter::open("/nonexistent-folder/indicators.csv");
  ASSERT_FALSE(csv.ok());
  EXPECT_EQ(csv.error().code, sp::ErrorCode::Io);
  EXPECT_NE(csv.error().message.find("/nonexistent-folder/indicators.csv"), std::string::npos) << csv.error().message;
  const auto text = sp::write_file_atomically("/nonexistent-folder/stats.json", "{}");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error().code, sp::ErrorCode::Io);

  const fs::path dir = fs::temp_directory_path() / ("soundpaint-writers-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto writer = sp::IndicatorCsvWriter::open(dir / "ok.csv").value();
  EXPECT_FALSE(fs::exists(dir / "ok.csv"));  // not before commit
  ASSERT_TRUE(writer->write({}).ok());
  ASSERT_TRUE(writer->commit().ok());
  std::ifstream in(dir / "ok.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, sp::kIndicatorCsvHeader);
  fs::remove_all(dir);
}

}  // namespace
