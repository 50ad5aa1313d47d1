// Where an output file goes (README "Command line", "Security"): regular
// files through a temporary file and a rename, symbolic links written
// through, "-" as standard output, and never a device, FIFO, /proc link or
// directory turned into a regular file; another user's link in a sticky
// folder is never followed, and no replacement splits hard links or hands a
// file to a new owner (issue 39).
#include <gtest/gtest.h>
#include <fcntl.h>
#include <grp.h>
#include <sys/stat.h>
#include <sys/wait.h>
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


// The users of the attack in issue 39: "nobody" plants a link, a third user
// owns the file it points at. Only root can make files theirs.
constexpr uid_t kPlanter = 65534;
constexpr uid_t kVictim = 65533;

struct stat status_of(const fs::path& path) {
  struct stat status {};
  EXPECT_EQ(::lstat(path.c_str(), &status), 0) << path;
  return status;
}

class OutputPathAsRoot : public OutputPath {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root, to give files to other users";
    OutputPath::SetUp();
    // A folder like /tmp: sticky and writable by everyone.
    shared_ = dir_ / "shared";
    fs::create_directory(shared_);
    ASSERT_EQ(::chmod(shared_.c_str(), 01777), 0);
    // A third user's private file.
    victim_ = write("victim.txt", "secret");
    ASSERT_EQ(::chown(victim_.c_str(), kVictim, kVictim), 0);
    ASSERT_EQ(::chmod(victim_.c_str(), 0600), 0);
  }
  // The victim's file is as it was: contents, owner, mode, single link.
  void expect_victim_untouched(ino_t inode) {
    EXPECT_EQ(read(victim_), "secret");
    const struct stat status = status_of(victim_);
    EXPECT_EQ(status.st_ino, inode);
    EXPECT_EQ(status.st_uid, kVictim);
    EXPECT_EQ(status.st_mode & 07777, 0600u);
    EXPECT_EQ(status.st_nlink, 1u);
  }
  // A symbolic link at `link` to `target`, owned by `owner`.
  static void plant_link(const fs::path& target, const fs::path& link, uid_t owner) {
    fs::create_symlink(target, link);
    ASSERT_EQ(::lchown(link.c_str(), owner, owner), 0);
  }

  fs::path shared_;
  fs::path victim_;
};

// Issue 39: root's `--stats /tmp/x`, x another user's link to a third
// user's 0600 file, replaced that file with a root-owned 0644 one.
TEST_F(OutputPathAsRoot, InAStickyFolderOnlyOurLinksAndItsOwnersAreFollowed) {
  const ino_t inode = status_of(victim_).st_ino;
  plant_link(victim_, shared_ / "x.json", kPlanter);
  expect_refused(shared_ / "x.json", "the symbolic link " + (shared_ / "x.json").string() +
                                         " belongs to another user (uid 65534) in a sticky world-writable folder");
  EXPECT_FALSE(sp::write_file_atomically(shared_ / "x.json", "{}").ok());
  // Nor when it comes later in a chain, or names the folder on the way.
  plant_link(shared_ / "x.json", dir_ / "mine.json", 0);
  expect_refused(dir_ / "mine.json", "belongs to another user (uid 65534)");
  plant_link(dir_, shared_ / "folder", kPlanter);
  expect_refused(shared_ / "folder" / "victim.txt", "belongs to another user (uid 65534)");
  expect_victim_untouched(inode);
  EXPECT_TRUE(fs::is_symlink(shared_ / "x.json"));
  expect_no_temporaries(shared_);
  expect_no_temporaries(dir_);

  // The rule's exceptions, as the kernel's: links of the follower and of
  // the folder's owner are followed, and any link in a folder that is not
  // sticky.
  plant_link("mine.json", shared_ / "root.json", 0);
  write_atomically(shared_ / "root.json", "by root");
  EXPECT_EQ(read(shared_ / "mine.json"), "by root");
  EXPECT_TRUE(fs::is_symlink(shared_ / "root.json"));
  fs::create_directory(dir_ / "owned");
  ASSERT_EQ(::chown((dir_ / "owned").c_str(), kPlanter, kPlanter), 0);
  ASSERT_EQ(::chmod((dir_ / "owned").c_str(), 01777), 0);
  plant_link("owner.json", dir_ / "owned" / "by-owner.json", kPlanter);
  write_atomically(dir_ / "owned" / "by-owner.json", "owner's link");
  EXPECT_EQ(read(dir_ / "owned" / "owner.json"), "owner's link");
  fs::create_directory(dir_ / "plain");
  plant_link("../plain.json", dir_ / "plain" / "link.json", kPlanter);
  write_atomically(dir_ / "plain" / "link.json", "not sticky");
  EXPECT_EQ(read(dir_ / "plain.json"), "not sticky");
}

// The kernel's fs.protected_regular, by us: another user's file in /tmp
// is theirs to name, never ours to replace.
TEST_F(OutputPathAsRoot, AnotherUsersFileInAStickyFolderIsNotReplaced) {
  const fs::path planted = write("shared/planted.json", "planted");
  ASSERT_EQ(::chown(planted.c_str(), kPlanter, kPlanter), 0);
  expect_refused(planted, "it belongs to another user (uid 65534) in a sticky world-writable folder");
  EXPECT_EQ(read(planted), "planted");
  EXPECT_EQ(status_of(planted).st_uid, kPlanter);
  expect_no_temporaries(shared_);
}

// Replacing another user's file where that is allowed keeps it theirs,
// with its mode: root's run must not turn a 0640 file into root's 0644 one.
TEST_F(OutputPathAsRoot, AReplacedFileKeepsItsOwnerAndMode) {
  const fs::path theirs = write("theirs.json", "old");
  ASSERT_EQ(::chown(theirs.c_str(), kVictim, kPlanter), 0);
  ASSERT_EQ(::chmod(theirs.c_str(), 0640), 0);
  write_atomically(theirs, "new");
  EXPECT_EQ(read(theirs), "new");
  const struct stat status = status_of(theirs);
  EXPECT_EQ(status.st_uid, kVictim);
  EXPECT_EQ(status.st_gid, kPlanter);
  EXPECT_EQ(status.st_mode & 07777, 0640u);
}

// Without root, another user's file cannot be given back to them after a
// rename: it is refused, where it used to become ours.
TEST_F(OutputPathAsRoot, AFileWhoseOwnerCannotBeKeptIsNotReplaced) {
  const fs::path open_folder = dir_ / "open";
  fs::create_directory(open_folder);
  ASSERT_EQ(::chmod(open_folder.c_str(), 0777), 0);  // writable by all, not sticky
  const fs::path theirs = write("open/theirs.json", "old");
  ASSERT_EQ(::chown(theirs.c_str(), kVictim, kVictim), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    // As "nobody": exit 0 only when refused for the owner's sake.
    if (::setgroups(0, nullptr) != 0 || ::setresgid(kPlanter, kPlanter, kPlanter) != 0 ||
        ::setresuid(kPlanter, kPlanter, kPlanter) != 0)
      ::_exit(2);
    try {
      write_atomically(theirs, "new");
    } catch (const sp::Exception& e) {
      ::_exit(std::string(e.what()).find("could not keep that owner") != std::string::npos ? 0 : 3);
    }
    ::_exit(1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: replaced; 2: could not drop root; 3: another error";
  EXPECT_EQ(read(theirs), "old");
  EXPECT_EQ(status_of(theirs).st_uid, kVictim);
  expect_no_temporaries(open_folder);
}

// A rename over a file with other hard links splits them: the other names
// keep the old contents. Refused, before and at commit.
TEST_F(OutputPath, HardLinkedFilesAreNotReplaced) {
  const fs::path original = write("original.json", "old");
  fs::create_hard_link(original, dir_ / "other-name.json");
  expect_refused(original, "it has 2 hard links, and replacing it would split them");
  EXPECT_EQ(read(dir_ / "other-name.json"), "old");
  EXPECT_EQ(fs::hard_link_count(original), 2u);

  // A link made while the output is being written is found at commit.
  {
    sp::AtomicFile file(dir_ / "fresh.json");
    file.write("new");
    fs::create_hard_link(original, dir_ / "fresh.json");
    try {
      file.commit();
      ADD_FAILURE() << "committed";
    } catch (const sp::Exception& e) {
      EXPECT_NE(std::string(e.what()).find("hard links"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(read(dir_ / "fresh.json"), "old");
  EXPECT_EQ(fs::hard_link_count(original), 3u);
  expect_no_temporaries(dir_);
}

// While a run writes, its temporary file is ours alone when it will
// replace a private file: the old 0600 contents are never readable in the
// new file, not even before commit.
TEST_F(OutputPath, ReplacingAPrivateFileKeepsItPrivate) {
  const fs::path private_file = write("private.json", "old");
  ASSERT_EQ(::chmod(private_file.c_str(), 0600), 0);
  sp::AtomicFile file(private_file);
  file.write("new");
  for (const auto& entry : fs::directory_iterator(dir_)) {
    if (entry.path().filename().string().find(".tmp-") == std::string::npos) continue;
    EXPECT_EQ(status_of(entry.path()).st_mode & 0777, 0600u) << entry.path();
  }
  file.commit();
  EXPECT_EQ(status_of(private_file).st_mode & 0777, 0600u);
  EXPECT_EQ(read(private_file), "new");
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
