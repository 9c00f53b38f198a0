// `--threads N` through the CLI: predict and compensate write byte-identical files for
// 1, 2 and 0 (every core) threads, on the KUKA sample and on a generated 600-hole program (more
// than one block of the streamed predict per worker); a count that is not a whole number in
// [0, 1024] is a usage error (exit 2, nothing written).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

std::string cellPath() { return test::sourceDir() + "/samples/cells/housing-kr120.xml"; }

/// A KRL drilling program of `n` holes on the housing's top face (1.2 mm grid).
std::string generatedProgram(const std::string& dir, int n) {
  std::ostringstream s;
  s << "DEF threads_job ( )\n"
       "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
       "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n";
  s.setf(std::ios::fixed);
  s.precision(3);
  for (int k = 0; k < n; ++k) {
    const double x = -30.0 + 1.2 * (k % 40);
    const int row = k / 40;
    const double y = -20.0 + 1.2 * row;
    auto at = [&](double z) {
      std::ostringstream p;
      p.setf(std::ios::fixed);
      p.precision(3);
      p << "{X " << x << ",Y " << y << ",Z " << z << ",A 0.000,B 0.000,C 180.000}";
      return p.str();
    };
    s << "$VEL.CP = 0.25000\nPTP " << at(300) << " C_PTP\nLIN " << at(252)
      << " C_DIS\n$VEL.CP = 0.02000\nLIN " << at(234) << "\nWAIT SEC 0.3\n$VEL.CP = 0.25000\nLIN "
      << at(300) << " C_DIS\n";
  }
  s << "END\n";
  const std::string path = dir + "/threads_job.src";
  test::writeFile(path, s.str());
  return path;
}

TEST(ThreadsCli, PredictAndCompensateAreByteIdenticalForAnyThreadCount) {
  const std::string dir = test::tempDir("threads_cli");
  const std::string sample = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  const std::string holes = test::sourceDir() + "/samples/emotor-housing/holes.csv";
  struct Job {
    std::string program;
    std::string extra;
  };
  const std::vector<Job> jobs = {{sample, "--holes '" + holes + "'"},
                                 {generatedProgram(dir, 600), ""}};
  int k = 0;
  for (const Job& job : jobs) {
    SCOPED_TRACE(job.program);
    std::string first_json;
    std::string first_program;
    std::string first_targets;
    for (const char* t : {"1", "2", "0"}) {
      SCOPED_TRACE(std::string("--threads ") + t);
      const std::string tag = dir + "/" + std::to_string(k) + "_" + t;
      const auto p =
          test::runRoprec("predict --cell '" + cellPath() + "' '" + job.program + "' " + job.extra +
                          " --quiet --json '" + tag + ".json' --threads " + t);
      ASSERT_EQ(p.exit_code, 0) << p.err;
      const auto c =
          test::runRoprec("compensate --cell '" + cellPath() + "' '" + job.program + "' " +
                          job.extra + " --quiet --orientation flip-free --grid 12 -o '" + tag +
                          ".src' --targets '" + tag + ".csv' --threads " + t);
      ASSERT_EQ(c.exit_code, 0) << c.err;
      const std::string json = test::readFile(tag + ".json");
      const std::string program = test::readFile(tag + ".src");
      const std::string targets = test::readFile(tag + ".csv");
      ASSERT_GT(json.size(), 1000U);
      if (first_json.empty()) {
        first_json = json;
        first_program = program;
        first_targets = targets;
        continue;
      }
      EXPECT_TRUE(json == first_json) << "predict JSON differs from --threads 1";
      EXPECT_TRUE(program == first_program) << "compensated program differs from --threads 1";
      EXPECT_TRUE(targets == first_targets) << "targets export differs from --threads 1";
    }
    ++k;
  }
}

TEST(ThreadsCli, ACountThatIsNotAWholeNumberInRangeIsAUsageError) {
  const std::string dir = test::tempDir("threads_bad");
  const std::string holes = test::sourceDir() + "/samples/emotor-housing/holes.csv";
  for (const char* bad : {"-1", "1.5", "two", "1025"}) {
    SCOPED_TRACE(bad);
    const auto r = test::runRoprec("predict --cell '" + cellPath() + "' '" + holes + "' --json '" +
                                   dir + "/p.json' --threads " + bad);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.json"));
  }
  const auto c = test::runRoprec("compensate --cell '" + cellPath() + "' '" + test::sourceDir() +
                                 "/samples/emotor-housing/housing_kr120.src' -o '" + dir +
                                 "/c.src' --threads -2");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/c.src"));
}

}  // namespace
}  // namespace roprec
