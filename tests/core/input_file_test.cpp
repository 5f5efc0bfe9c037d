// read_input_file(), which every reader goes through: regular files only, refused before a byte is read.

#include "conform/core/input_file.h"

#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "io_test_data.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::error_of;

TEST(InputFile, RegularFileAndSymlinkToOneAreRead) {
  test::TempDir dir;
  test::write_bytes(dir.file("a.txt"), "1 2 3\n");
  ASSERT_EQ(::symlink(dir.file("a.txt").c_str(), dir.file("link.txt").c_str()), 0);
  EXPECT_EQ(read_input_file(dir.file("a.txt")), "1 2 3\n");
  EXPECT_EQ(read_input_file(dir.file("link.txt")), "1 2 3\n");
}

// A FIFO used to hang a job (nobody writes to it); a link to /dev/zero grew to 1.15 GB.
TEST(InputFile, FifosDevicesAndDirectoriesAreRefusedBeforeReading) {
  test::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("pipe.ply").c_str(), 0600), 0);
  ASSERT_EQ(::symlink("/dev/zero", dir.file("zero.csv").c_str()), 0);
  ::mkdir(dir.file("sub.ply").c_str(), 0700);
  const struct {
    std::string path, expected;
  } cases[] = {
      {dir.file("pipe.ply"), "pipe.ply: is a FIFO (named pipe), not a regular file"},
      {dir.file("zero.csv"), "zero.csv: is a device, not a regular file"},
      {"/dev/null", "/dev/null: is a device, not a regular file"},
      {dir.file("sub.ply"), "sub.ply: is a directory, not a regular file"},
      {dir.file("missing.ply"), "missing.ply: cannot open (No such file or directory)"},
  };
  for (const auto& c : cases) {
    EXPECT_CONTAINS(error_of([&] { read_input_file(c.path); }), c.expected);
    if (c.path != "/dev/null") {
      EXPECT_CONTAINS(error_of([&] { read_geometry(c.path); }), c.expected);
    }
  }
  test::write_bytes(dir.file("empty.xyz"), "");
  EXPECT_CONTAINS(error_of([&] { read_geometry(dir.file("empty.xyz")); }), "empty.xyz: is empty");
}

}  // namespace
}  // namespace conform
