// The command-line contract of DESIGN.md: --help, exit codes, --json on stdout only.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"

namespace conform {
namespace {

test::RunResult conform_cli(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

TEST(Cli, HelpListsTheJobsAndExitsZero) {
  const auto r = conform_cli({"--help"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("info"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("generate"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos) << r.out;
}

TEST(Cli, EverySubcommandHasHelp) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"info", "--help"}, std::vector<std::string>{"generate", "tube", "--help"}}) {
    const auto r = conform_cli(args);
    EXPECT_EQ(r.exit_code, 0) << args[0] << ": " << r.err;
    EXPECT_NE(r.out.find("--json"), std::string::npos) << r.out;
  }
}

TEST(Cli, NoJobIsBadUsage) {
  const auto r = conform_cli({});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(r.err.empty());
}

TEST(Cli, UnknownJobOrOptionIsBadUsage) {
  EXPECT_EQ(conform_cli({"no-such-job"}).exit_code, 2);
  EXPECT_EQ(conform_cli({"info", "--no-such-option", "x.ply"}).exit_code, 2);
  EXPECT_EQ(conform_cli({"info"}).exit_code, 2);  // the file is required
}

// Issue 13: `conform --help` took 0.05 s, mostly the loader binding PCL's features library (116k relocations) for
// FPFH, which is now conform's own (registration/src/fpfh_features.h); OpenCASCADE is a plugin opened on the first
// CAD file (core/plugin.h). The loader's own log lists what a start loads.
TEST(Cli, HelpLoadsNoHeavyLibrary) {
  const auto r = test::run("/usr/bin/env", {"LD_DEBUG=libs", CONFORM_EXE, "--help"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_NE(r.err.find("libstdc++"), std::string::npos) << "no loader log: " << r.err.substr(0, 500);
  for (const char* heavy : {"libpcl_features", "libpcl_filters", "libpcl_sample_consensus", "libpcl_search",
                            "libpcl_kdtree", "libconform_cad", "libTKernel", "libvtk", "libopencv_imgcodecs"}) {
    EXPECT_EQ(r.err.find(heavy), std::string::npos) << heavy << " is loaded at start-up";
  }
}

TEST(Cli, VersionExitsZero) {
  const auto r = conform_cli({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("conform"), std::string::npos);
}

}  // namespace
}  // namespace conform
