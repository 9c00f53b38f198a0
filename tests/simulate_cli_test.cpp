// `roprec simulate` end to end: exact CSV header, byte-identical repeated runs, a physically
// consistent history (approach at the static gravity deviation, load during the feed), the JSON
// summary, hole lookup in a hole-list CSV, and bad input → exit 2 with nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using test::runRoprec;

std::string cell() { return "'" + test::sourceDir() + "/samples/cells/alu-drilling-6061.xml'"; }

TEST(SimulateCli, CsvHeaderDeterminismAndSummary) {
  const std::string dir = test::tempDir("simulate");
  const std::string args =
      "simulate --cell " + cell() + " --joints \"0 -60 100 0 50 0\" --duration 0.5 --sample-ms 5";
  const auto a = runRoprec(args + " -o '" + dir + "/a.csv' --summary '" + dir + "/a.json'");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto b = runRoprec(args + " -o '" + dir + "/b.csv' --summary '" + dir + "/b.json'");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string csv = test::readFile(dir + "/a.csv");
  EXPECT_EQ(csv, test::readFile(dir + "/b.csv"));
  EXPECT_EQ(test::readFile(dir + "/a.json"), test::readFile(dir + "/b.json"));
  std::istringstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("t_s,depth_mm,Fa_N,Ft_N,M_Nm,Fr_N,dx_um,dy_um,dz_um", 0), 0u) << header;
  int rows = 0;
  std::string line;
  double fa_max = 0.0;
  while (std::getline(in, line)) {
    ++rows;
    std::istringstream ls(line);
    std::string cellv;
    std::vector<std::string> f;
    while (std::getline(ls, cellv, ',')) f.push_back(cellv);
    fa_max = std::max(fa_max, std::stod(f[2]));
  }
  EXPECT_EQ(rows, 101);       // 0 .. 0.5 s every 5 ms
  EXPECT_GT(fa_max, 1000.0);  // the drill is in full engagement by 0.5 s (thrust ≈ 1.5 kN)
  const auto j = nlohmann::json::parse(test::readFile(dir + "/a.json"));
  EXPECT_TRUE(j["cvode"]["ok"].get<bool>());
  EXPECT_GT(j["cvode"]["steps"].get<long>(), 0);
  EXPECT_GT(j["cvode"]["rhs_evaluations"].get<long>(), 0);
  // the first row (approach, at rest) is the static gravity deviation of the deflect model
  std::istringstream again(csv);
  std::getline(again, line);
  std::getline(again, line);
  std::istringstream ls(line);
  std::vector<double> v;
  std::string x;
  while (std::getline(ls, x, ',') && v.size() < 9) v.push_back(std::stod(x));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(v[6 + static_cast<size_t>(i)],
                j["static"]["gravity_only_um"][static_cast<size_t>(i)].get<double>(), 2e-4);
  }
  // stdout mode prints the same CSV; the summary goes to stderr
  const auto c = runRoprec(args);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.out, csv);
  EXPECT_NE(c.err.find("\"cvode\""), std::string::npos);
}

TEST(SimulateCli, HoleFromHoleList) {
  const std::string dir = test::tempDir("simulate_hole");
  const auto r = runRoprec("simulate --cell " + cell() + " --hole H2 '" + test::sourceDir() +
                           "/tests/data/programs/holes.csv' --duration 0.05 -o '" + dir +
                           "/h.csv' --summary '" + dir + "/h.json'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::readFile(dir + "/h.json"));
  EXPECT_NE(j["joints_source"].get<std::string>().find("hole list row"), std::string::npos);
}

TEST(SimulateCli, BadInputExitsTwoAndWritesNothing) {
  const std::string dir = test::tempDir("simulate_bad");
  const std::string out = " -o '" + dir + "/x.csv'";
  const auto five = runRoprec("simulate --cell " + cell() + " --joints \"0 -60 100 0 50\"" + out);
  EXPECT_EQ(five.exit_code, 2);
  const auto limits =
      runRoprec("simulate --cell " + cell() + " --joints \"0 -170 100 0 50 0\"" + out);
  EXPECT_EQ(limits.exit_code, 2);
  EXPECT_NE(limits.err.find("limits"), std::string::npos) << limits.err;
  const auto dur =
      runRoprec("simulate --cell " + cell() + " --joints \"0 -60 100 0 50 0\" --duration -1" + out);
  EXPECT_EQ(dur.exit_code, 2);
  const auto nohole = runRoprec("simulate --cell " + cell() + " --hole H99 '" + test::sourceDir() +
                                "/tests/data/programs/holes.csv'" + out);
  EXPECT_EQ(nohole.exit_code, 2);
  EXPECT_NE(nohole.err.find("H99"), std::string::npos);
  const auto nocell =
      runRoprec("simulate --robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\"" + out);
  EXPECT_EQ(nocell.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir + "/x.csv"));
}

}  // namespace
}  // namespace roprec
