// The roprec executable's own entry points (plugin/cli/main.cpp): --version, --help and an
// unknown command.
#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace roprec
