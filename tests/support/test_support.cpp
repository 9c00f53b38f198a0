#include "tests/support/test_support.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace fs = std::filesystem;

namespace roprec::test {

std::string sourceDir() { return ROPREC_SOURCE_DIR; }

std::string corpusDir() {
  const fs::path p = fs::path(ROPREC_SOURCE_DIR) / ".." / "shared" / "corpus";
  if (fs::exists(p)) return fs::canonical(p).string();
  // In CI the corpus is part of the job: a missing corpus must fail the test that wanted it (a
  // failure recorded before GTEST_SKIP() keeps the test failed), not skip it silently.
  if (const char* ci = std::getenv("CI"); ci != nullptr && std::string(ci) == "true") {
    ADD_FAILURE()
        << "CI=true but the test corpus " << p.lexically_normal().string()
        << " is missing (tests that read ../shared/corpus fail in CI instead of skipping)";
  }
  return std::string();
}

std::string roprecBin() { return ROPREC_BIN; }

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

std::string tempDir(const std::string& tag) {
  static int counter = 0;
  const fs::path p = fs::temp_directory_path() / ("roprec-test-" + std::to_string(::getpid()) +
                                                  "-" + tag + "-" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

RunResult runRoprec(const std::string& args) { return runCommand("'" + roprecBin() + "' " + args); }

RunResult runCommand(const std::string& command) {
  const std::string dir = tempDir("run");
  const std::string out = dir + "/stdout";
  const std::string err = dir + "/stderr";
  const std::string cmd = "{ " + command + "; } >'" + out + "' 2>'" + err + "' </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  r.out = readFile(out);
  r.err = readFile(err);
  fs::remove_all(dir);
  return r;
}

}  // namespace roprec::test
