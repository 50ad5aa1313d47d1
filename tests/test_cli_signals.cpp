// The soundpaint executable stopped or starved of its standard output
// (issue 39, README "Security"): Ctrl-C, SIGTERM, SIGHUP and a broken pipe
// leave no temporary file behind and kill it with the same signal; a closed
// or failing standard output is exit status 1, never a 0, and never lets
// the text meant for it into another output file.
#include <algorithm>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.h"

namespace {

namespace fs = std::filesystem;
using sp::test::read_text;
using sp::test::ScratchDir;

const std::string kCli = SP_CLI_PATH;
const std::string kLevel = std::string(SP_SCENES_DIR) + "/level.gltf";

// What the child's descriptor 1 is.
struct Stdout {
  enum Kind { kFile, kClosed, kDescriptor } kind = kFile;
  int fd = -1;  // kDescriptor: dup2'ed onto 1
};

// Starts the CLI with `args`, stderr to `err`, stdout as `out` (kFile:
// `out_file`); every fatal signal at its default action, or SIGPIPE
// ignored, as a parent such as Python may leave it.
pid_t start_cli(const std::vector<std::string>& args, Stdout out, const fs::path& out_file, const fs::path& err,
                bool ignore_sigpipe = false) {
  std::vector<std::string> words{kCli};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int out_fd =
      out.kind == Stdout::kFile ? ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644) : out.fd;
  const pid_t pid = ::fork();
  if (pid == 0) {
    for (int signo : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::signal(signo, SIG_DFL);
    if (ignore_sigpipe) ::signal(SIGPIPE, SIG_IGN);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::dup2(err_fd, STDERR_FILENO);
    if (out.kind == Stdout::kClosed) {
      ::close(STDOUT_FILENO);
    } else {
      ::dup2(out_fd, STDOUT_FILENO);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(err_fd);
  if (out.kind == Stdout::kFile) ::close(out_fd);
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

std::vector<fs::path> temporaries(const fs::path& folder) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(entry.path());
  return found;
}

void expect_no_temporaries(const fs::path& folder) {
  for (const fs::path& path : temporaries(folder)) ADD_FAILURE() << "left behind: " << path;
}

// A run that writes until killed: the most steps, every indicator to a CSV.
std::vector<std::string> endless_simulate(const ScratchDir& dir, const std::string& indicators = "ind.csv") {
  return {"simulate",     kLevel,
          "--backend",    "cpu",
          "--threads",    "2",
          "--steps",      "100000000",
          "--stats",      (dir / "stats.json").string(),
          "--indicators", indicators == "-" ? "-" : (dir / indicators).string()};
}

// Waits (bounded by polls, not by time) for the run to create its
// temporary files; false if it never did.
bool wait_for_temporaries(const fs::path& folder, pid_t pid) {
  for (int poll = 0; poll < 20000; ++poll) {
    if (temporaries(folder).size() == 2) return true;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;  // it ended on its own
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

// Killed at random moments, while loading (before any temporary file
// exists) and while writing, by each of the four signals: it dies of that
// signal and no temporary file is left.
TEST(CliSignals, AKilledRunLeavesNoTemporaryFile) {
  std::random_device seed_source;
  const unsigned seed = seed_source();
  SCOPED_TRACE("random seed " + std::to_string(seed));
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> delay_ms(0, 60);
  ScratchDir dir("cli-signals");
  for (int signo : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    for (int round = 0; round < 4; ++round) {
      SCOPED_TRACE(std::string(::strsignal(signo)) + ", round " + std::to_string(round));
      const pid_t pid = start_cli(endless_simulate(dir), {}, dir / "out.txt", dir / "err.txt");
      // Round 0 may land before the outputs are even opened.
      if (round > 0) {
        ASSERT_TRUE(wait_for_temporaries(dir.path(), pid)) << read_text(dir / "err.txt");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(random)));
      ::kill(pid, signo);
      const int status = wait_for(pid);
      ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status << ": " << read_text(dir / "err.txt");
      EXPECT_EQ(WTERMSIG(status), signo);
      expect_no_temporaries(dir.path());
      EXPECT_FALSE(fs::exists(dir / "ind.csv"));
      EXPECT_FALSE(fs::exists(dir / "stats.json"));
      for (const fs::path& path : temporaries(dir.path())) fs::remove(path);
    }
  }
}

// A reader that goes away (`soundpaint ... | head`): the pipe breaks, the
// run dies of SIGPIPE, and the other output's temporary file goes too.
TEST(CliSignals, ABrokenPipeLeavesNoTemporaryFile) {
  ScratchDir dir("cli-broken-pipe");
  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);
  const pid_t pid = start_cli(endless_simulate(dir, "-"), {Stdout::kDescriptor, pipe_fds[1]}, {}, dir / "err.txt");
  ::close(pipe_fds[1]);
  char head[4096];
  EXPECT_GT(::read(pipe_fds[0], head, sizeof head), 0);  // the CSV has begun
  ::close(pipe_fds[0]);
  const int status = wait_for(pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status << ": " << read_text(dir / "err.txt");
  EXPECT_EQ(WTERMSIG(status), SIGPIPE);
  expect_no_temporaries(dir.path());
  EXPECT_FALSE(fs::exists(dir / "stats.json"));
}

// A closed standard output must not become the next file opened: the CSV
// meant for it once landed in front of the stats JSON, with status 0.
TEST(CliSignals, AClosedStandardOutputIsRefusedAndCorruptsNothing) {
  ScratchDir dir("cli-closed-stdout");
  const pid_t pid = start_cli({"simulate", kLevel, "--backend", "cpu", "--steps", "2", "--indicators", "-", "--stats",
                               (dir / "stats.json").string()},
                              {Stdout::kClosed}, {}, dir / "err.txt");
  const int status = wait_for(pid);
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(read_text(dir / "err.txt"), "soundpaint: error: cannot write -: standard output is closed\n");
  if (fs::exists(dir / "stats.json")) {
    const std::string stats = read_text(dir / "stats.json");
    EXPECT_EQ(stats.find("step,kind"), std::string::npos) << stats;
    EXPECT_TRUE(nlohmann::json::accept(stats)) << stats;
  }
  expect_no_temporaries(dir.path());

  // Only the summary line was meant for standard output: stats.json is
  // whole, but the lost line still makes it a failure.
  const pid_t summary =
      start_cli({"simulate", kLevel, "--backend", "cpu", "--steps", "2", "--stats", (dir / "stats.json").string()},
                {Stdout::kClosed}, {}, dir / "err.txt");
  const int summary_status = wait_for(summary);
  ASSERT_TRUE(WIFEXITED(summary_status)) << summary_status;
  EXPECT_EQ(WEXITSTATUS(summary_status), 1);
  EXPECT_EQ(read_text(dir / "err.txt"), "soundpaint: error: cannot write standard output: it is closed\n");
  EXPECT_EQ(nlohmann::json::parse(read_text(dir / "stats.json"))["steps"], 2);
}

// What a command prints is its result: lost to a full disk, or to a reader
// gone while SIGPIPE is ignored, it is exit status 1 with a message.
TEST(CliSignals, AFailingStandardOutputIsExitStatusOne) {
  ScratchDir dir("cli-failing-stdout");
  const int full = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  ASSERT_GE(full, 0);
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"info", kLevel}, {"check", kLevel}, {"simulate", kLevel, "--backend", "cpu", "--steps", "1"}, {"--help"}}) {
    SCOPED_TRACE(args[0]);
    const int status = wait_for(start_cli(args, {Stdout::kDescriptor, full}, {}, dir / "err.txt"));
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 1) << read_text(dir / "err.txt");
    EXPECT_NE(read_text(dir / "err.txt").find("cannot write standard output: No space left on device"),
              std::string::npos)
        << read_text(dir / "err.txt");
  }
  ::close(full);

  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);
  ::close(pipe_fds[0]);  // no reader at all
  const int status =
      wait_for(start_cli({"info", kLevel}, {Stdout::kDescriptor, pipe_fds[1]}, {}, dir / "err.txt", true));
  ::close(pipe_fds[1]);
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_NE(read_text(dir / "err.txt").find("cannot write standard output: Broken pipe"), std::string::npos)
      << read_text(dir / "err.txt");

  // Indicators to `-` with no reader: the write's own error, once; the
  // stream's would only say it again, as "Input/output error".
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);
  ::close(pipe_fds[0]);
  const int csv_status =
      wait_for(start_cli({"simulate", kLevel, "--backend", "cpu", "--steps", "2", "--indicators", "-"},
                         {Stdout::kDescriptor, pipe_fds[1]}, {}, dir / "err.txt", true));
  ::close(pipe_fds[1]);
  ASSERT_TRUE(WIFEXITED(csv_status)) << csv_status;
  EXPECT_EQ(WEXITSTATUS(csv_status), 1);
  const std::string err = read_text(dir / "err.txt");
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("Broken pipe"), std::string::npos) << err;
}

}  // namespace
