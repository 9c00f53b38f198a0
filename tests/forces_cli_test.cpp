#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using test::runRoprec;

std::string sample(const std::string& name) {
  return "'" + test::sourceDir() + "/samples/cells/" + name + "'";
}

TEST(ForcesCli, DrillingSampleCellPrintsThrustTorqueAndFr) {
  const std::string dir = test::tempDir("forces");
  const auto r =
      runRoprec("forces --cell " + sample("alu-drilling-6061.xml") + " --csv '" + dir + "/d.csv'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["process"], "drilling");
  const double thrust = j["steady"]["thrust_N"];
  const double torque = j["steady"]["torque_Nm"];
  EXPECT_NEAR(thrust, 1542, 1542 * 0.01);  // docs/process.md §7.5 mechanistic Dc 10 / f 0.2
  EXPECT_NEAR(torque, 2.96, 2.96 * 0.01);
  EXPECT_GT(j["steady"]["Fr_N"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["wrench_tool"]["force_N"][2].get<double>(), -thrust);
  EXPECT_DOUBLE_EQ(j["wrench_tool"]["torque_Nm"][2].get<double>(), -torque);
  EXPECT_EQ(j["steady"]["lips"].size(), 2u);
  EXPECT_GT(j["machining_deviation"]["U_mach_um"].get<double>(), 0.0);
  const std::string csv = test::readFile(dir + "/d.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "depth_mm,engaged_radius_mm,Fa_N,Ft_N,M_Nm,Fr_N");
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 200);
  // deterministic
  const auto r2 = runRoprec("forces --cell " + sample("alu-drilling-6061.xml"));
  EXPECT_EQ(r.out, r2.out);
}

TEST(ForcesCli, MillingSampleCellWithCoupling) {
  const std::string dir = test::tempDir("forces");
  const auto r =
      runRoprec("forces --cell " + sample("alu-milling-7075.xml") + " --csv '" + dir + "/m.csv'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["process"], "milling");
  EXPECT_NEAR(j["immersion"]["exit_deg"].get<double>(), 53.1301, 1e-3);
  ASSERT_TRUE(j.contains("coupling"));
  for (const auto& p : j["coupling"]["points"]) {
    EXPECT_TRUE(p["converged"].get<bool>());
    EXPECT_LE(p["iterations"].get<int>(), 10);
  }
  const std::string csv = test::readFile(dir + "/m.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "angle_deg,Fx_N,Fy_N,Fz_N,Fxy_N");
}

TEST(ForcesCli, CalibrateWritesACalibratedCellThatReproducesTheTest) {
  const std::string dir = test::tempDir("forces");
  const std::string out = dir + "/cal.xml";
  const auto r = runRoprec("forces --cell " + sample("alu-drilling-6061.xml") +
                           " --calibrate 'Fa_N=1466 M_Nm=4.04' --o '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["steady"]["thrust_N"].get<double>(), 1466, 0.01);
  EXPECT_NEAR(j["steady"]["torque_Nm"].get<double>(), 4.04, 1e-4);
  ASSERT_TRUE(fs::exists(out));
  // The calibrated copy sits in another folder: it refers to the bundled robot by name, so it
  // loads.
  const auto r2 = runRoprec("forces --cell '" + out + "'");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto j2 = nlohmann::json::parse(r2.out);
  EXPECT_NEAR(j2["steady"]["thrust_N"].get<double>(), 1466, 0.05);
  EXPECT_NEAR(j2["steady"]["torque_Nm"].get<double>(), 4.04, 1e-3);
}

/// Writes a cell with the given <process> body; returns its path.
std::string cellWith(const std::string& dir, const std::string& process) {
  const std::string path = dir + "/cell.xml";
  test::writeFile(path,
                  "<cell name=\"t\">\n"
                  "  <robot ref=\"kuka-kr120-r2500-pro\"/>\n"
                  "  <process type=\"drilling\">\n" +
                      process +
                      "  </process>\n"
                      "</cell>\n");
  return path;
}

void expectExit2AtLine(const std::string& process, int line, const std::string& what) {
  const std::string dir = test::tempDir("forces-bad");
  const std::string cell = cellWith(dir, process);
  const auto r = runRoprec("forces --cell '" + cell + "' --csv '" + dir + "/out.csv' --json '" +
                           dir + "/out.json'");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("roprec: error: " + cell + ":" + std::to_string(line) + ":"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.csv"));
  EXPECT_FALSE(fs::exists(dir + "/out.json"));
  EXPECT_TRUE(r.out.empty());
}

const char* const kDrill = "    <drill diameter_mm=\"10\"/>\n";
const char* const kCut = "    <cut feed_mm_per_rev=\"0.2\"/>\n";
const char* const kMat = "    <material name=\"Al 6061-T6\"/>\n";

TEST(ForcesCli, NegativeFeedIsExit2WithFileAndLine) {
  expectExit2AtLine(std::string(kDrill) + "    <cut feed_mm_per_rev=\"-0.1\"/>\n" + kMat, 5,
                    "feed_mm_per_rev must be > 0");
}

TEST(ForcesCli, PointAngleBelowRangeIsExit2WithFileAndLine) {
  expectExit2AtLine(
      std::string("    <drill diameter_mm=\"10\" point_angle_deg=\"60\"/>\n") + kCut + kMat, 4,
      "point angle must lie in (60, 180)");
}

TEST(ForcesCli, PointAngleAboveRangeIsExit2WithFileAndLine) {
  expectExit2AtLine(
      std::string("    <drill diameter_mm=\"10\" point_angle_deg=\"181\"/>\n") + kCut + kMat, 4,
      "point angle must lie in (60, 180)");
}

TEST(ForcesCli, WebWiderThanTheDrillIsExit2WithFileAndLine) {
  expectExit2AtLine(std::string("    <drill diameter_mm=\"10\" web_mm=\"10.5\"/>\n") + kCut + kMat,
                    4, "web is wider than the drill");
}

TEST(ForcesCli, UnknownMaterialIsExit2WithFileAndLine) {
  expectExit2AtLine(std::string(kDrill) + kCut + "    <material name=\"Al 9999\"/>\n", 6,
                    "unknown material 'Al 9999'");
}

TEST(ForcesCli, BadCalibrationArgumentWritesNothing) {
  const std::string dir = test::tempDir("forces-bad");
  const auto r = runRoprec("forces --cell " + sample("alu-drilling-6061.xml") +
                           " --calibrate 'Fa_N=-3 M_Nm=4' --o '" + dir + "/cal.xml'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir + "/cal.xml"));
  const auto r2 =
      runRoprec("forces --cell " + sample("alu-milling-7075.xml") + " --calibrate 'Fa_N=3 M_Nm=4'");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_NE(r2.err.find("needs a <process type=\"drilling\">"), std::string::npos);
}

}  // namespace
}  // namespace roprec
