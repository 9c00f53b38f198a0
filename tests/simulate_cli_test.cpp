// `roprec simulate` end to end: exact CSV header, byte-identical repeated runs, a physically
// consistent history (approach at the static gravity deviation, load during the feed), the JSON
// summary, hole lookup in a hole-list CSV, and bad input → exit 2 with nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
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
  EXPECT_EQ(header,
            "t_s,depth_mm,Fa_N,Ft_N,M_Nm,Fr_N,dx_um,dy_um,dz_um,rx_urad,ry_urad,rz_urad,"
            "dq1_urad,dq2_urad,dq3_urad,dq4_urad,dq5_urad,dq6_urad,tip_mm,cut_depth_mm,"
            "feed_per_rev_mm,axial_um,phase");
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

std::vector<std::vector<std::string>> csvRows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string v;
    std::vector<std::string> f;
    while (std::getline(ls, v, ',')) f.push_back(v);
    rows.push_back(f);
  }
  return rows;
}

/// The whole cycle of the sample through hole, coupled to the penetration: in every row with
/// thrust the tip is at the bottom (tip = cut depth) and never moves back; the cut depth lags the
/// commanded depth by the axial deflection; the summary reports the end of the cut, the maximum
/// thrust (the CSV's) and the settling/damping (an estimate).
TEST(SimulateCli, DrillingCycleFollowsTheRealPenetration) {
  const std::string dir = test::tempDir("simulate_cut");
  const auto r = runRoprec("simulate --cell " + cell() + " --joints \"0 -60 100 0 50 0\" -o '" +
                           dir + "/c.csv' --summary '" + dir + "/c.json'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = csvRows(test::readFile(dir + "/c.csv"));
  const auto j = nlohmann::json::parse(test::readFile(dir + "/c.json"));
  const auto& tr = j["transient"];
  double fa_max = 0.0;
  double prev_tip = -1e9;
  double prev_fa = 0.0;
  double max_lag = 0.0;
  int cutting = 0;
  for (const auto& f : rows) {
    ASSERT_EQ(f.size(), 23u);
    const double fa = std::stod(f[2]);
    const double tip = std::stod(f[18]);
    const double cut = std::stod(f[19]);
    // the tip is never below the material removed (mm): within the cut depth's absolute
    // tolerance of the default integration (1e-8 m = 1e-5 mm, docs/transient.md) plus the CSV's
    // 1 nm digits
    constexpr double kDepthTolMm = 1.1e-5;
    EXPECT_LE(tip, cut + kDepthTolMm);
    if (fa > 0.0) {
      ++cutting;
      EXPECT_NEAR(tip, cut, kDepthTolMm);
      EXPECT_GT(std::stod(f[20]), 0.0);  // real feed per rev
      if (prev_fa > 0.0) {
        EXPECT_GE(tip, prev_tip - kDepthTolMm) << "t = " << f[0];
      }
      max_lag = std::max(max_lag, std::stod(f[1]) - cut);
    }
    fa_max = std::max(fa_max, fa);
    prev_tip = tip;
    prev_fa = fa;
  }
  EXPECT_GT(cutting, 1000);
  EXPECT_GT(max_lag, 0.1);  // mm: the tip lags the spindle by the axial deflection
  EXPECT_NEAR(tr["max_thrust_N"].get<double>(), fa_max, 1e-3);
  EXPECT_NEAR(tr["first_contact_t_s"].get<double>(), 0.1, 1e-4);
  const double t_cut = tr["end_of_cut_t_s"].get<double>();
  EXPECT_GT(t_cut, 1.0);
  for (const auto& f : rows) {
    if (std::stod(f[0]) > t_cut + 1e-6) {
      EXPECT_EQ(std::stod(f[2]), 0.0);
    }
  }
  // without --duration the run ends with the retract, 0.1 s after the end of the cut
  EXPECT_NEAR(std::stod(rows.back()[0]), t_cut + 0.1, 1.5e-3);
  EXPECT_TRUE(j["cvode"]["stopped_at_cycle_end"].get<bool>());
  EXPECT_EQ(j["cvode"]["events"].get<long>(), 2);  // contact, exit of the corner
  EXPECT_NE(tr["damping"]["source"].get<std::string>().find("estimate"), std::string::npos);
  EXPECT_EQ(tr["settling"]["tolerance_um"].get<double>(), 0.1);
}

/// A held constant load (cell <process type="wrench">): the reported settling time is the first
/// row after which every row stays within 0.1 µm of the static deviation (the deflect model).
TEST(SimulateCli, HeldLoadSettlingTimeMatchesTheRows) {
  const std::string dir = test::tempDir("simulate_hold");
  const std::string cell_path = dir + "/wrench.xml";
  {
    std::ofstream c(cell_path);
    c << "<cell name=\"held-load\">\n"
         "  <robot ref=\"kuka-kr120-r2500-pro\"/>\n"
         "  <tool name=\"spindle\" xyz=\"0 0 350\" rpy=\"0 0 0\" mass_kg=\"25\" "
         "com_mm=\"0 0 150\"/>\n"
         "  <workobject xyz=\"1600 0 400\" rpy=\"0 0 0\"/>\n"
         "  <process type=\"wrench\" force_N=\"0 0 -1500\" torque_Nm=\"0 0 -3\"/>\n"
         "</cell>\n";
  }
  const auto r =
      runRoprec("simulate --cell '" + cell_path + "' --joints \"0 -60 100 0 50 0\" -o '" + dir +
                "/h.csv' --summary '" + dir + "/h.json'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::readFile(dir + "/h.json"));
  const auto& st = j["transient"]["settling"];
  ASSERT_TRUE(st["settled"].get<bool>()) << st.dump();
  const double t_s = st["from_t_s"].get<double>() + st["settling_time_s"].get<double>();
  const double hold_end = st["from_t_s"].get<double>() + 1.0;
  std::vector<double> ref;
  for (const auto& v : j["static"]["full_engagement_um"]) ref.push_back(v.get<double>());
  bool before_outside = false;
  int inside = 0;
  for (const auto& f : csvRows(test::readFile(dir + "/h.csv"))) {
    const double t = std::stod(f[0]);
    if (t > hold_end + 1e-9) break;
    double e2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double d = std::stod(f[6 + static_cast<size_t>(i)]) - ref[static_cast<size_t>(i)];
      e2 += d * d;
    }
    const double e = std::sqrt(e2);
    if (t >= t_s - 1e-9) {
      EXPECT_LE(e, 0.1 + 2e-4) << "t = " << t;  // µm, CSV rounding 1e-4 µm
      ++inside;
    } else if (t >= t_s - 1.5e-3) {
      before_outside = e > 0.1 - 2e-4;
    }
  }
  EXPECT_GT(inside, 10);
  EXPECT_TRUE(before_outside);
  EXPECT_GT(st["equivalent_damping_ratio"].get<double>(), 0.0);
  EXPECT_EQ(j["transient"]["damping"]["joint_damping_ratio"].get<double>(), 0.05);
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

TEST(SimulateCli, HoleIsDrilledWithItsOwnDrillDiameterAndDepth) {
  // the sample's T001 is a 6.8 x 16 mm hole: with the single 8.5 mm drill cell the drill is
  // scaled to 6.8 mm and the hole's depth taken; with the tool table, its 6.8 mm drill
  const std::string dir = test::tempDir("simulate_own_drill");
  const std::string holes = test::sourceDir() + "/samples/emotor-housing/holes.csv";
  for (const std::string cell : {"housing-kr120.xml", "housing-kr120-tools.xml"}) {
    SCOPED_TRACE(cell);
    const auto r = runRoprec("simulate --cell '" + test::sourceDir() + "/samples/cells/" + cell +
                             "' --hole T001 '" + holes + "' --duration 0.02 -o '" + dir +
                             "/h.csv' --summary '" + dir + "/h.json'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(test::readFile(dir + "/h.json"));
    const std::string process = j["process"].get<std::string>();
    EXPECT_EQ(process.rfind("drilling Dc 6.80 mm", 0), 0U) << process;
    const std::string source = j["process_source"].get<std::string>();
    EXPECT_EQ(source.rfind("hole list row 3: ", 0), 0U) << source;
  }
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
