#include "conform/core/output_set.h"

#include <cstdio>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "conform/core/atomic_file.h"
#include "conform/core/error.h"
#include "temp_dir.h"

namespace conform {
namespace {

// The message of the conform::Error that `f` throws, or "" when it throws none.
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(OutputSet, AnOutputThatIsAnInputIsRefusedHoweverItIsSpelled) {
  test::TempDir dir;
  test::write_bytes(dir.file("scan.ply"), "scan");
  ASSERT_EQ(::symlink("scan.ply", dir.file("alias.ply").c_str()), 0);
  ASSERT_EQ(::link(dir.file("scan.ply").c_str(), dir.file("hard.ply").c_str()), 0);
  for (const std::string& output :
       {dir.file("scan.ply"), dir.path() + "/./sub/../scan.ply", dir.file("alias.ply"), dir.file("hard.ply")}) {
    OutputSet set;
    set.add_input(dir.file("scan.ply"));
    const std::string why = error_of([&] { set.add_output(output); });
    EXPECT_TRUE(contains(why, "is the input")) << output << ": " << why;
  }
  {
    OutputSet set;  // the other order: output first
    set.add_output(dir.file("alias.ply"));
    EXPECT_TRUE(contains(error_of([&] { set.add_input(dir.file("scan.ply")); }), "is the input"));
  }
  EXPECT_EQ(test::read_bytes(dir.file("scan.ply")), "scan");
}

TEST(OutputSet, AnOutputGivenTwiceIsRefusedADeviceMayBeSharedEmptyIsIgnored) {
  test::TempDir dir;
  OutputSet set;
  set.add_output(dir.file("path.csv"));
  EXPECT_TRUE(contains(error_of([&] { set.add_output(dir.path() + "//path.csv"); }), "given as two outputs"));
  set.add_output("/dev/null");
  set.add_output("/dev/null");
  set.add_output("");
  set.add_input("");
}

// Two new outputs, one named through a link to its own directory: the same file, refused (one would be lost).
TEST(OutputSet, TwoNewOutputsThroughALinkedDirectoryAreOneFile) {
  test::TempDir dir;
  ASSERT_EQ(::symlink(".", dir.file("selfdir").c_str()), 0);
  OutputSet set;
  set.add_output(dir.file("x.ply"));
  EXPECT_TRUE(contains(error_of([&] { set.add_output(dir.file("selfdir/x.ply")); }), "given as two outputs"));
  EXPECT_TRUE(contains(error_of([&] { set.add_output(dir.file("selfdir/selfdir/./x.ply")); }), "given as two outputs"));
  set.add_output(dir.file("selfdir/y.ply"));  // another file
}

TEST(OutputSet, CommitReplacesEveryTargetAndLeavesNothingElse) {
  test::TempDir dir;
  test::write_bytes(dir.file("a.csv"), "old a");
  {
    OutputSet set;
    write_file_atomically(dir.file("a.csv"), "new a");
    write_file_atomically(dir.file("b.csv"), "new b");
    EXPECT_EQ(test::read_bytes(dir.file("a.csv")), "old a");  // staged, not yet renamed
    EXPECT_EQ(test::read_bytes(dir.file("b.csv")), "");
    set.commit();
  }
  EXPECT_EQ(test::read_bytes(dir.file("a.csv")), "new a");
  EXPECT_EQ(test::read_bytes(dir.file("b.csv")), "new b");
  EXPECT_EQ(dir.listing(), "a.csv\nb.csv\n");
}

// Issue 18: `compare --out-deviation scan.ply --out-histogram nodir/h.png` deleted scan.ply when the histogram failed.
TEST(OutputSet, ALaterFailureLeavesEveryExistingTargetAsItWas) {
  test::TempDir dir;
  test::write_bytes(dir.file("scan.ply"), "the only copy");
  EXPECT_FALSE(error_of([&] {
                 OutputSet set;
                 write_file_atomically(dir.file("scan.ply"), "deviation map");
                 write_file_atomically(dir.file("nodir/h.png"), "png");
                 set.commit();
               }).empty());
  EXPECT_EQ(test::read_bytes(dir.file("scan.ply")), "the only copy");
  EXPECT_EQ(dir.listing(), "scan.ply\n");
}

// A rename that fails during commit(): the targets renamed before it get their previous version back, a target that
// did not exist is removed again, and no temporary or kept copy is left.
TEST(OutputSet, AFailedCommitRestoresThePreviousVersions) {
  test::TempDir dir;
  ASSERT_EQ(::mkdir(dir.file("d").c_str(), 0700), 0);
  test::write_bytes(dir.file("path.csv"), "old path");
  const std::string why = error_of([&] {
    OutputSet set;
    write_file_atomically(dir.file("path.csv"), "new path");
    write_file_atomically(dir.file("new.csv"), "new file");
    write_file_atomically(dir.file("d/cut.csv"), "cut");
    ASSERT_EQ(std::rename(dir.file("d").c_str(), dir.file("e").c_str()), 0);  // the last rename now fails
    set.commit();
  });
  EXPECT_TRUE(contains(why, "d/cut.csv")) << why;
  EXPECT_EQ(test::read_bytes(dir.file("path.csv")), "old path");
  EXPECT_EQ(dir.listing(), "e\npath.csv\n");  // no new.csv, no kept copy of path.csv
}

TEST(OutputSet, AnInnerSetHandsItsFilesToTheOuterOne) {
  test::TempDir dir;
  {
    OutputSet outer;
    {
      OutputSet inner;
      write_file_atomically(dir.file("a.csv"), "a");
      inner.commit();
    }
    EXPECT_EQ(dir.listing().find("a.csv\n"), std::string::npos);
    EXPECT_TRUE(contains(error_of([&] { write_file_atomically(dir.file("a.csv"), "again"); }), "written twice"));
    // destroyed without commit: nothing appears
  }
  EXPECT_EQ(dir.listing(), "");
  {
    OutputSet outer;
    {
      OutputSet inner;
      write_file_atomically(dir.file("a.csv"), "a");
      inner.commit();
    }
    outer.commit();
  }
  EXPECT_EQ(test::read_bytes(dir.file("a.csv")), "a");
}

TEST(OutputSet, AStagedOutputThatIsAnInputIsRefused) {
  test::TempDir dir;
  test::write_bytes(dir.file("in.csv"), "input");
  OutputSet set;
  set.add_input(dir.file("in.csv"));
  EXPECT_TRUE(contains(error_of([&] { write_file_atomically(dir.file("in.csv"), "x"); }), "is the input"));
  EXPECT_EQ(test::read_bytes(dir.file("in.csv")), "input");
}

TEST(OutputSet, AnOutputThatCannotBeWrittenIsRefusedBeforeAnyWork) {
  test::TempDir dir;
  OutputSet set;
  const std::string missing = error_of([&] { set.add_output(dir.file("no/such/dir/report.html")); });
  EXPECT_TRUE(contains(missing, "no/such/dir/report.html: cannot be written: the directory")) << missing;
  EXPECT_TRUE(contains(missing, "does not exist")) << missing;
  const std::string directory = error_of([&] { set.add_output(dir.path()); });
  EXPECT_TRUE(contains(directory, "is a directory")) << directory;
  ASSERT_EQ(::mkdir(dir.file("locked").c_str(), 0500), 0);
  if (::geteuid() != 0) {  // root writes anywhere
    const std::string locked = error_of([&] { set.add_output(dir.file("locked/out.csv")); });
    EXPECT_TRUE(contains(locked, "is not writable")) << locked;
  }
  ::chmod(dir.file("locked").c_str(), 0700);
  EXPECT_EQ(error_of([&] { set.add_output(dir.file("out.csv")); }), "");
  EXPECT_EQ(error_of([&] { set.add_output("/dev/null"); }), "");
  EXPECT_EQ(error_of([&] { set.add_output("-"); }), "");
}

}  // namespace
}  // namespace conform
