// The roprec executable's own entry points (plugin/cli/main.cpp): --version, --help, an unknown
// command, a failed write to stdout and running out of memory ("input too large").
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "plugin/api/job.hpp"
#include "plugin/c/roprec.h"
#include "support/test_support.hpp"

namespace roprec {
namespace {

TEST(CliMain, VersionIsTheLibrarysVersion) {
  const test::RunResult r = test::runCommand("'" + test::roprecBin() + "' --version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // the CLI, the job API and the C ABI report one version (CMake's PROJECT_VERSION)
  EXPECT_EQ(r.out, "roprec " + std::string(api::version()) + "\n");
  EXPECT_EQ(std::string(api::version()), std::string(roprec_version()));
}

TEST(CliMain, HelpListsTheCommandsAndAnUnknownCommandExitsTwo) {
  const test::RunResult help = test::runCommand("'" + test::roprecBin() + "' --help");
  ASSERT_EQ(help.exit_code, 0) << help.err;
  EXPECT_NE(help.out.find("predict"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("compensate"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("roprec --version"), std::string::npos) << help.out;
  const test::RunResult bad = test::runCommand("'" + test::roprecBin() + "' drill-faster");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown command 'drill-faster'"), std::string::npos) << bad.err;
}

// A failed write to standard output (/dev/full: "No space left on device") is exit 2 with the errno
// text, for every command that prints (JSON on stdout, `--json -`, lists, help), and what the run
// had staged is removed: the report of a predict whose JSON could not be printed is not written.
TEST(CliMain, AFailedWriteToStandardOutputIsExitTwoAndWritesNothing) {
  const std::string src = test::sourceDir();
  const std::string dir = test::tempDir("stdout-full");
  const std::string cell = src + "/samples/cells/housing-kr120.xml";
  const std::string program = src + "/samples/emotor-housing/housing_kr120.src";
  const std::vector<std::string> commands{
      "predict --cell '" + cell + "' '" + program + "' --quiet --json -",
      "predict --cell '" + cell + "' '" + program + "' --json - --quiet --report '" + dir +
          "/r.html'",
      "inspect '" + program + "'",
      "robots",
      "fk --robot kuka-kr120-r2500-pro --joints \"0 -90 90 0 0 0\"",
      "--help",
      "--version",
  };
  for (const std::string& c : commands) {
    const test::RunResult r = test::runCommand("'" + test::roprecBin() + "' " + c + " > /dev/full");
    EXPECT_EQ(r.exit_code, 2) << c << "\n" << r.err;
    EXPECT_NE(r.err.find("cannot write to standard output: No space left on device"),
              std::string::npos)
        << c << "\n"
        << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/r.html"));
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// predict --help tells what its memory grows with: not with the holes of a KRL program (read by
// windows; scripts/check-memory.sh measures it), with those of the other inputs (~1.5 kB each).
TEST(CliMain, PredictHelpSaysWhatMemoryGrowsWith) {
  const test::RunResult r = test::runCommand("'" + test::roprecBin() + "' predict --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("constant memory"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("KUKA KRL program is read twice by windows"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("memory does not grow with the number of\nholes"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("about 1.5 kB a hole"), std::string::npos) << r.out;
}

namespace fs = std::filesystem;

TEST(CliMain, OutOfMemoryIsReportedAsInputTooLargeNamingTheInput) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ulimit -v and the address sanitizer's shadow memory do not mix";
#else
  // 650,000 depth rows are within range but do not fit in 100 MB of address space: the
  // std::bad_alloc is reported as "input too large" with the input named, exit 2, nothing written.
  const std::string dir = test::tempDir("range-oom");
  const std::string cell = test::sourceDir() + "/samples/cells/alu-drilling-6061.xml";
  const test::RunResult r =
      test::runCommand("ulimit -v 100000; '" + test::roprecBin() + "' forces --cell '" + cell +
                       "' --step-mm 2e-5 --csv '" + dir + "/d.csv'");
  EXPECT_EQ(r.exit_code, 2);
  const std::string& err = r.err;
  EXPECT_NE(err.find("input too large"), std::string::npos) << err;
  EXPECT_NE(err.find(cell), std::string::npos) << err;
  EXPECT_EQ(err.find("bad_alloc"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir + "/d.csv"));
#endif
}

}  // namespace
}  // namespace roprec
