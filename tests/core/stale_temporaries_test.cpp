// Issue 18: a writer killed with kill -9 left its temporary (`NAME.conform-tmp-<hex>`, up to 112 MB) for good. Every
// temporary is now locked by its writer while it exists; the next write into the same directory removes the ones
// whose lock is free. Real processes are killed here (fork + SIGKILL), so the lock is released by the kernel exactly
// as after a crash.

#include <csignal>
#include <regex>
#include <string>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "conform/core/atomic_file.h"
#include "temp_dir.h"

namespace conform {
namespace {

const std::regex kTemporary(".*\\.conform-tmp-[0-9a-f]{16}");

int count_temporaries(const test::TempDir& dir) {
  int n = 0;
  std::string listing = dir.listing();
  std::size_t start = 0;
  while (start < listing.size()) {
    std::size_t end = listing.find('\n', start);
    if (end == std::string::npos) end = listing.size();
    if (std::regex_match(listing.substr(start, end - start), kTemporary)) ++n;
    start = end + 1;
  }
  return n;
}

// A child process that opens an output in `dir`, writes to it and is killed before it commits.
void killed_writer(const test::TempDir& dir) {
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    AtomicFile file(dir.file("scan.ply"));
    file.write("half a scan", 11);
    ::kill(::getpid(), SIGKILL);
    ::_exit(3);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
}

TEST(StaleTemporaries, AKilledWritersTemporaryIsRemovedByTheNextWriteThere) {
  test::TempDir dir;
  killed_writer(dir);
  ASSERT_EQ(count_temporaries(dir), 1) << dir.listing();
  killed_writer(dir);  // removed the first one's leftover before it died itself
  ASSERT_EQ(count_temporaries(dir), 1) << dir.listing();
  write_file_atomically(dir.file("path.csv"), "x,y,z\n");
  EXPECT_EQ(count_temporaries(dir), 0) << dir.listing();
  EXPECT_EQ(test::read_bytes(dir.file("path.csv")), "x,y,z\n");
}

TEST(StaleTemporaries, ALiveWritersTemporaryIsLeftAloneAndItsCommitSucceeds) {
  test::TempDir dir;
  int ready[2], go[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(go), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(ready[0]);
    ::close(go[1]);
    AtomicFile file(dir.file("scan.ply"));
    file.write("whole scan", 10);
    char c = 'r';
    if (::write(ready[1], &c, 1) != 1) ::_exit(4);
    if (::read(go[0], &c, 1) < 0) ::_exit(5);  // returns 0 when the parent closes its end
    try {
      file.commit();
    } catch (...) {
      ::_exit(6);
    }
    ::_exit(0);
  }
  ::close(ready[1]);
  ::close(go[0]);
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  write_file_atomically(dir.file("other.txt"), "other");  // sweeps the directory while the child holds its lock
  EXPECT_EQ(count_temporaries(dir), 1) << dir.listing();
  ::close(go[1]);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(test::read_bytes(dir.file("scan.ply")), "whole scan");
  EXPECT_EQ(count_temporaries(dir), 0) << dir.listing();
  ::close(ready[0]);
}

TEST(StaleTemporaries, OnlyRegularFilesNamedExactlyLikeATemporaryAreRemoved) {
  test::TempDir dir;
  test::write_bytes(dir.file("kept.txt"), "data");
  const std::string lookalikes[] = {"a.conform-tmp-0123456789ABCDEF", "a.conform-tmp-0123456789abcde",
                                    "a.conform-tmp-0123456789abcdef.ply", "a.conform-old-0123456789abcdef"};
  for (const std::string& name : lookalikes) test::write_bytes(dir.file(name), "keep me");
  ASSERT_EQ(::symlink(dir.file("kept.txt").c_str(), dir.file("b.conform-tmp-0123456789abcdef").c_str()), 0);
  ASSERT_EQ(::mkdir(dir.file("c.conform-tmp-0123456789abcdef").c_str(), 0700), 0);
  test::write_bytes(dir.file("d.conform-tmp-0123456789abcdef"), "left by a crash");

  write_file_atomically(dir.file("out.txt"), "out");
  for (const std::string& name : lookalikes) EXPECT_EQ(test::read_bytes(dir.file(name)), "keep me") << name;
  struct stat st {};
  EXPECT_EQ(::lstat(dir.file("b.conform-tmp-0123456789abcdef").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(::stat(dir.file("c.conform-tmp-0123456789abcdef").c_str(), &st), 0);
  EXPECT_EQ(::lstat(dir.file("d.conform-tmp-0123456789abcdef").c_str(), &st), -1);
  EXPECT_EQ(test::read_bytes(dir.file("kept.txt")), "data");
}

}  // namespace
}  // namespace conform
