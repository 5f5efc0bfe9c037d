#include "conform/core/atomic_file.h"

#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "temp_dir.h"

namespace conform {
namespace {

mode_t mode_of(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
  return st.st_mode & 0777;
}

TEST(AtomicFile, CommitReplacesTheTargetWhole) {
  test::TempDir dir;
  test::write_bytes(dir.file("out.txt"), "old");
  write_file_atomically(dir.file("out.txt"), "new contents");
  EXPECT_EQ(test::read_bytes(dir.file("out.txt")), "new contents");
  EXPECT_EQ(dir.listing(), "out.txt\n");
}

TEST(AtomicFile, WithoutCommitNothingIsLeftAndTheTargetIsUntouched) {
  test::TempDir dir;
  test::write_bytes(dir.file("out.txt"), "old");
  {
    AtomicFile file(dir.file("out.txt"));
    std::ofstream(file.temp_path()) << "half-writ";
    // an exception on the way out would land here: no commit
  }
  EXPECT_EQ(test::read_bytes(dir.file("out.txt")), "old");
  EXPECT_EQ(dir.listing(), "out.txt\n");
}

TEST(AtomicFile, UnwritableTargetIsAnErrorNamingIt) {
  try {
    write_file_atomically("/nonexistent-dir/out.txt", "x");
    FAIL() << "writing into a missing directory succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/out.txt"), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, TheTemporaryHasARandomNameBesideTheTarget) {
  test::TempDir dir;
  const AtomicFile a(dir.file("out.txt")), b(dir.file("out.txt"));
  const std::regex pattern(".*/out\\.txt\\.conform-tmp-[0-9a-f]{16}");
  EXPECT_TRUE(std::regex_match(a.temp_path(), pattern)) << a.temp_path();
  EXPECT_TRUE(std::regex_match(b.temp_path(), pattern)) << b.temp_path();
  EXPECT_NE(a.temp_path(), b.temp_path());
}

// Issue 18: the temporary's name was NAME.tmp-PID-N and it was opened without O_EXCL|O_NOFOLLOW, so a symlink planted
// there redirected the write into any file the user could write. Links planted at every such name now change nothing.
TEST(AtomicFile, APlantedSymlinkCannotRedirectTheWrite) {
  test::TempDir dir;
  test::write_bytes(dir.file("victim"), "precious");
  ::chmod(dir.file("victim").c_str(), 0600);
  for (int n = 0; n < 64; ++n) {
    const std::string planted = dir.file("out.txt.tmp-" + std::to_string(::getpid()) + "-" + std::to_string(n));
    ASSERT_EQ(::symlink(dir.file("victim").c_str(), planted.c_str()), 0);
  }
  write_file_atomically(dir.file("out.txt"), "output");
  EXPECT_EQ(test::read_bytes(dir.file("out.txt")), "output");
  EXPECT_EQ(test::read_bytes(dir.file("victim")), "precious");
  EXPECT_EQ(mode_of(dir.file("victim")), 0600u);
}

TEST(AtomicFile, AReplacedTargetKeepsItsPermissionsANewOneFollowsTheUmask) {
  test::TempDir dir;
  test::write_bytes(dir.file("private.txt"), "old");
  ASSERT_EQ(::chmod(dir.file("private.txt").c_str(), 0600), 0);
  write_file_atomically(dir.file("private.txt"), "new");
  EXPECT_EQ(mode_of(dir.file("private.txt")), 0600u);
  const mode_t previous = ::umask(027);
  write_file_atomically(dir.file("fresh.txt"), "new");
  ::umask(previous);
  EXPECT_EQ(mode_of(dir.file("fresh.txt")), 0640u);
}

TEST(AtomicFile, ASymlinkOutputIsWrittenThroughAndStaysALink) {
  test::TempDir dir;
  test::write_bytes(dir.file("real.txt"), "old");
  ASSERT_EQ(::symlink("real.txt", dir.file("link.txt").c_str()), 0);
  ASSERT_EQ(::symlink(dir.file("missing.txt").c_str(), dir.file("dangling.txt").c_str()), 0);
  write_file_atomically(dir.file("link.txt"), "through the link");
  write_file_atomically(dir.file("dangling.txt"), "created");
  struct stat st {};
  ASSERT_EQ(::lstat(dir.file("link.txt").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(test::read_bytes(dir.file("real.txt")), "through the link");
  EXPECT_EQ(test::read_bytes(dir.file("missing.txt")), "created");
  EXPECT_EQ(dir.listing(), "dangling.txt\nlink.txt\nmissing.txt\nreal.txt\n");
}

// A hard-linked target gets a new file under its name; the other names keep the old contents (docs/foundation.md).
TEST(AtomicFile, AHardLinkedTargetIsReplacedTheOtherNameKeepsTheOldFile) {
  test::TempDir dir;
  test::write_bytes(dir.file("a.txt"), "old");
  ASSERT_EQ(::link(dir.file("a.txt").c_str(), dir.file("b.txt").c_str()), 0);
  write_file_atomically(dir.file("a.txt"), "new");
  EXPECT_EQ(test::read_bytes(dir.file("a.txt")), "new");
  EXPECT_EQ(test::read_bytes(dir.file("b.txt")), "old");
}

TEST(AtomicFile, AFifoIsStreamedIntoAndStaysAFifo) {
  test::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = test::read_bytes(fifo); });
  write_file_atomically(fifo, "streamed");
  reader.join();
  EXPECT_EQ(received, "streamed");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(dir.listing(), "pipe\n");
  write_file_atomically("/dev/null", "discarded");  // a device: written in place, never replaced
}

TEST(AtomicFile, DashIsStandardOutput) {
  test::TempDir dir;
  const int saved = ::dup(STDOUT_FILENO);
  const int file = ::open(dir.file("stdout.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(file, 0);
  ::dup2(file, STDOUT_FILENO);
  write_file_atomically("-", "to stdout");
  ::dup2(saved, STDOUT_FILENO);
  ::close(file);
  ::close(saved);
  EXPECT_EQ(test::read_bytes(dir.file("stdout.txt")), "to stdout");
  EXPECT_EQ(dir.listing(), "stdout.txt\n");
}

TEST(AtomicFile, ADirectoryIsAnErrorNamingIt) {
  test::TempDir dir;
  try {
    write_file_atomically(dir.path(), "x");
    FAIL() << "writing over a directory succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace conform
