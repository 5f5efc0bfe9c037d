#include "conform/core/atomic_file.h"

#include <fstream>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "temp_dir.h"

namespace conform {
namespace {

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

}  // namespace
}  // namespace conform
