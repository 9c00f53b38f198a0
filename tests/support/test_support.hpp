#pragma once
/// Helpers shared by the tests: paths, running the CLI, KDL chains from the same URDF.
#include <optional>
#include <string>
#include <vector>

namespace roprec::test {

std::string sourceDir();
/// ../shared/corpus next to the source tree, or "" when absent (tests then GTEST_SKIP()). With
/// CI=true a missing corpus also records a test failure, so the test fails instead of skipping.
std::string corpusDir();
std::string roprecBin();

struct RunResult {
  int exit_code{0};
  std::string out;
  std::string err;
};
/// Runs `roprec ARGS` (ARGS is passed to /bin/sh, quote as needed) and captures stdout/stderr.
RunResult runRoprec(const std::string& args);
/// Runs a /bin/sh command line (stdin /dev/null) and captures stdout/stderr.
RunResult runCommand(const std::string& command);
/// A fresh temporary directory under the build tree.
std::string tempDir(const std::string& tag);
std::string readFile(const std::string& path);
void writeFile(const std::string& path, const std::string& text);

}  // namespace roprec::test
