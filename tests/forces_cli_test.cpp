// `roprec forces` end to end: the drilling and milling sample cells, the coupled solve with the
// robot, calibration, and bad or absurd process values (exit 2 at their line, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "compensator/process/drilling_forces.hpp"
#include "compensator/support/rotation.hpp"
#include "tests/support/same_bytes.hpp"
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

// A cell with a tool table: `forces` needs --tool N when the table holds several drills (exit 2,
// naming them), and --tool N gives the forces of that drill with its own cut: the same numbers as
// a single-drill cell written by hand with that drill's geometry and the cut merged attribute by
// attribute (feed and speed of the drill's <cut>, depth of the process's).
TEST(ForcesCli, ToolSelectsTheDrillOfTheTable) {
  const std::string tools = sample("housing-kr120-tools.xml");
  const auto none = runRoprec("forces --cell " + tools);
  EXPECT_EQ(none.exit_code, 2) << none.err;
  EXPECT_NE(none.err.find("4 drills (tool 1 'D6.8' (Ø6.8 mm)"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("which drill? Give --tool N"), std::string::npos) << none.err;
  const auto unknown = runRoprec("forces --cell " + tools + " --tool 9");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.err;
  EXPECT_NE(unknown.err.find("--tool 9: the cell has no such drill"), std::string::npos);

  const auto table = runRoprec("forces --cell " + tools + " --tool 4");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const std::string text =
      test::readFile(test::sourceDir() + "/samples/cells/housing-kr120-tools.xml");
  const size_t begin = text.find("    <drill tool=\"1\"");
  const size_t end = text.find("    <material ");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string single =
      text.substr(0, begin) +
      "    <drill name=\"D12\" diameter_mm=\"12\" point_angle_deg=\"140\" helix_angle_deg=\"30\" "
      "web_mm=\"1.7\" tool_material=\"carbide\" stickout_mm=\"45\"/>\n"
      "    <cut feed_mm_per_rev=\"0.25\" spindle_rpm=\"5000\" depth_mm=\"20\"/>\n" +
      text.substr(end);
  const std::string dir = test::tempDir("forces-tool");
  test::writeFile(dir + "/single.xml", single);
  const auto one = runRoprec("forces --cell '" + dir + "/single.xml'");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const nlohmann::json a = nlohmann::json::parse(table.out);
  const nlohmann::json b = nlohmann::json::parse(one.out);
  EXPECT_EQ(a.at("drill").at("diameter_mm"), b.at("drill").at("diameter_mm"));
  EXPECT_EQ(a.at("cut"), b.at("cut"));
  EXPECT_EQ(a.at("steady"), b.at("steady"));
  EXPECT_EQ(a.at("wrench_tool"), b.at("wrench_tool"));
  EXPECT_EQ(a.at("machining_deviation"), b.at("machining_deviation"));
  // and not the first drill's
  const auto first = runRoprec("forces --cell " + tools + " --tool 1");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(nlohmann::json::parse(first.out).at("steady"), a.at("steady"));
}

TEST(ForcesCli, HelpStatesTheCoverageFactorTheOutputUses) {
  const auto r = runRoprec("forces --cell " + sample("alu-drilling-6061.xml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double k = nlohmann::json::parse(r.out)["machining_deviation"]["k"];
  std::ostringstream printed;
  printed.precision(3);
  printed << "k = " << k;  // 2.45
  const auto help = runRoprec("forces --help");
  EXPECT_NE(help.out.find("(U_mach, " + printed.str() + ":"), std::string::npos) << help.out;
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
  EXPECT_EQ(j["coupling"]["solver"], "newton");
  for (const auto& p : j["coupling"]["points"]) {
    EXPECT_TRUE(p["converged"].get<bool>());
    EXPECT_LE(p["iterations"].get<int>(), 10);
    EXPECT_LE(p["residual_um"].get<double>(), 0.1);
  }
  const std::string csv = test::readFile(dir + "/m.csv");
  EXPECT_EQ(
      csv.substr(0, csv.find('\n')),
      "angle_deg,Fx_nom_N,Fy_nom_N,Fz_nom_N,Fxy_nom_N,Fx_N,Fy_N,Fz_N,Fxy_N,dx_um,dy_um,dz_um");
}

/// The CSV rows as numbers (header skipped); every value must parse and be finite.
std::vector<std::vector<double>> csvRows(const std::string& csv) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) {
      const double v = std::stod(cell);
      EXPECT_TRUE(std::isfinite(v)) << line;
      row.push_back(v);
    }
    rows.push_back(row);
  }
  return rows;
}

// The KR 120 at joints (0, -60, 100, 0, 50, 0) deg: every point converges (|r| ≤ 0.1 µm) in a few
// Newton steps; the CSV gives, over one revolution (720 angles), the nominal and the corrected
// force and the TCP movement, whose means agree with the coupled point (±1 %: profile with runout
// vs arc average).
TEST(ForcesCli, MillingWithTheRobotAtJointsConvergesAndWritesTheCorrectedRevolution) {
  const std::string dir = test::tempDir("forces");
  const auto r = runRoprec("forces --cell " + sample("alu-milling-7075.xml") +
                           " --joints '0 -60 100 0 50 0' --csv '" + dir + "/rev.csv'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& pts = j["coupling"]["points"];
  ASSERT_EQ(pts.size(), 10u);
  for (const auto& p : pts) {
    EXPECT_EQ(p["status"], "converged");
    EXPECT_LE(p["iterations"].get<int>(), 6);
    EXPECT_LE(p["residual_um"].get<double>(), 0.1);
  }
  const auto rows = csvRows(test::readFile(dir + "/rev.csv"));
  ASSERT_EQ(rows.size(), 720u);
  Vec3 mean_nom = Vec3::Zero();
  Vec3 mean_cor = Vec3::Zero();
  Vec3 mean_mov = Vec3::Zero();
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 12u);
    mean_nom += Vec3(row[1], row[2], row[3]);
    mean_cor += Vec3(row[5], row[6], row[7]);
    mean_mov += Vec3(row[9], row[10], row[11]);
  }
  mean_nom /= 720.0;
  mean_cor /= 720.0;
  mean_mov /= 720.0;
  const auto& last = pts.back();
  const Vec3 F(last["force_N"][0], last["force_N"][1], last["force_N"][2]);
  const Vec3 d(last["deflection_um"][0], last["deflection_um"][1], last["deflection_um"][2]);
  EXPECT_LE((mean_cor - F).norm(), 0.01 * F.norm());
  // the robot is nearly linear over the revolution: the mean movement is the coupled deflection
  EXPECT_LE((mean_mov - d).norm(), 0.02 * d.norm());
  const auto& cr = j["coupling"]["corrected_revolution"];
  EXPECT_NEAR(cr["mean_nominal_N"][0].get<double>(), mean_nom.x(), 0.01);
}

/// The milling sample cell with `<coupling>` replaced.
std::string millingCellWith(const std::string& dir, const std::string& coupling) {
  std::string text = test::readFile(test::sourceDir() + "/samples/cells/alu-milling-7075.xml");
  const auto a = text.find("<coupling");
  const auto b = text.find("/>", a);
  text = text.substr(0, a) + coupling + text.substr(b + 2);
  const std::string path = dir + "/mill.xml";
  test::writeFile(path, text);
  return path;
}

// A robot 60 µm/N soft along the feed (up-milling, loop gain ≈ 4): the plain iteration fails
// (exit 1, the points listed as not converged), Newton converges every point (exit 0).
TEST(ForcesCli, SoftComplianceFixedPointFailsNewtonConverges) {
  const std::string dir = test::tempDir("forces");
  const std::string C = " compliance_um_per_N=\"60 0 0  0 3 0  0 0 1\"/>";
  const auto plain = runRoprec("forces --cell '" +
                               millingCellWith(dir, "<coupling solver=\"fixed_point\"" + C) + "'");
  EXPECT_EQ(plain.exit_code, 1) << plain.err;
  const auto jp = nlohmann::json::parse(plain.out);
  EXPECT_FALSE(jp["coupling"]["points"][0]["converged"].get<bool>());
  const auto newton =
      runRoprec("forces --cell '" + millingCellWith(dir, "<coupling solver=\"newton\"" + C) + "'");
  ASSERT_EQ(newton.exit_code, 0) << newton.err;
  const auto jn = nlohmann::json::parse(newton.out);
  for (const auto& p : jn["coupling"]["points"]) {
    EXPECT_EQ(p["status"], "converged");
    EXPECT_GT(p["loop_gain"].get<double>(), 1.0);
    EXPECT_LE(p["residual_um"].get<double>(), 0.1);
  }
  // an unphysical cell (pulled 1 mm/N into the wall): reported per point, exit 1, no crash
  const auto bad = runRoprec(
      "forces --cell '" +
      millingCellWith(dir, "<coupling compliance_um_per_N=\"1 0 0  0 1000 0  0 0 1\"/>") + "'");
  EXPECT_EQ(bad.exit_code, 1) << bad.err;
  const auto jb = nlohmann::json::parse(bad.out);
  EXPECT_NE(jb["coupling"]["points"][0]["status"], "converged");
  const auto bad_solver =
      runRoprec("forces --cell '" + millingCellWith(dir, "<coupling solver=\"broyden\"/>") + "'");
  EXPECT_EQ(bad_solver.exit_code, 2);
  EXPECT_NE(bad_solver.err.find("solver must be 'newton' or 'fixed_point'"), std::string::npos);
}

// --program streams its points into the --json file: the same bytes as on standard output, the
// same curve CSV, with 1 and 2 threads; the exit code keeps flagging the chatter points.
TEST(ForcesCli, MillingProgramJsonFileAndThreadsGiveTheSameBytes) {
  const std::string dir = test::tempDir("forces_program_threads");
  const std::string prog = " --program '" + test::sourceDir() + "/samples/milling/wall_pass.src'";
  const auto one = runRoprec("forces --cell " + sample("alu-milling-7075.xml") + prog + " --csv '" +
                             dir + "/one.csv'");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two =
      runRoprec("forces --cell " + sample("alu-milling-7075.xml") + prog + " --threads 2 --csv '" +
                dir + "/two.csv' --json '" + dir + "/two.json'");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(test::readFile(dir + "/two.json"), one.out);
  EXPECT_EQ(test::readFile(dir + "/two.csv"), test::readFile(dir + "/one.csv"));
  const auto bad = runRoprec("forces --cell " + sample("alu-milling-7075.xml") + prog +
                             " --threads x --json '" + dir + "/bad.json'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir + "/bad.json"));
}

// A program read by windows (a KRL pass of 1200 points: a JSON of about 2 MB, copied to standard
// output in more than one piece): the JSON on standard output (held in a temporary file, not in
// memory) is the bytes of the --json file, and with --csv - the curve CSV comes first on standard
// output, as the file --csv writes it.
TEST(ForcesCli, MillingProgramByWindowsStdoutIsTheJsonFilesBytes) {
  const std::string dir = test::tempDir("forces_program_stdout");
  test::writeFile(dir + "/wall.src", test::krlWallPass(1200));
  const std::string cmd =
      "forces --cell " + sample("alu-milling-7075.xml") + " --program '" + dir + "/wall.src'";
  const auto file = runRoprec(cmd + " --json '" + dir + "/f.json' --csv '" + dir + "/f.csv'");
  ASSERT_EQ(file.exit_code, 0) << file.err;
  EXPECT_TRUE(file.out.empty());
  const std::string json = test::readFile(dir + "/f.json");
  ASSERT_NE(json.find("\"point\": 1203"), std::string::npos);  // every point
  const auto out = runRoprec(cmd);
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_TRUE(test::sameBytes(out.out, json));
  const auto both = runRoprec(cmd + " --csv -");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_TRUE(test::sameBytes(both.out, test::readFile(dir + "/f.csv") + json));
}

// A tool the cell's mills do not have at the last pass of a long program (many windows): the
// first reading finds it before any point is computed; exit 2 at its line, nothing written
// (neither standard output nor the --csv and --json files).
TEST(ForcesCli, MillingProgramLateToolErrorExitsTwoWithNothingWritten) {
  const std::string dir = test::tempDir("forces_program_late");
  std::string text = test::krlWallPass(60000);
  const std::string tool = "$TOOL = {FRAME: X 0.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\r\n";
  ASSERT_NE(text.find(tool), std::string::npos);
  text.replace(text.find(tool), tool.size(),
               "TOOL_DATA[1] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n"
               "TOOL_DATA[2] = {X 0.0,Y 0.0,Z 300.0,A 0.0,B 0.0,C 0.0}\n$TOOL = TOOL_DATA[1]\n");
  const size_t at = text.find("LIN {X 70.000");
  text.insert(at, "$TOOL = TOOL_DATA[2]\n");  // the one mill's second tool
  test::writeFile(dir + "/late.src", text);
  const auto line =
      std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n') + 2;
  const std::string cmd = "forces --cell " + sample("alu-milling-7075.xml") + " --program '" + dir +
                          "/late.src' --csv '" + dir + "/c.csv'";
  for (const std::string& json : {std::string(), " --json '" + dir + "/j.json'"}) {
    const auto r = runRoprec(cmd + json);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
    EXPECT_NE(r.err.find("late.src:" + std::to_string(line) + ":"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/c.csv"));
    EXPECT_FALSE(fs::exists(dir + "/j.json"));
  }
}

// wall_pass.src with the KR 120 card: the approach (LIN at 250 mm/s) and the retract are not
// cutting (zero force, reason given); every cutting point converges with |r| ≤ 0.1 µm.
TEST(ForcesCli, MillingProgramPathCuttingDecisionAndConvergence) {
  const auto r = runRoprec("forces --cell " + sample("alu-milling-7075.xml") + " --program '" +
                           test::sourceDir() + "/samples/milling/wall_pass.src'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& pts = j["path"]["points"];
  ASSERT_EQ(pts.size(), 27u);
  for (size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    const bool edge = i == 0 || i + 1 == pts.size();
    EXPECT_EQ(p["cutting"].get<bool>(), !edge) << i;
    if (edge) {
      EXPECT_NE(p["cutting_reason"].get<std::string>().find("rapid"), std::string::npos);
      EXPECT_EQ(p["status"], "not_cutting");
      for (int k = 0; k < 3; ++k) EXPECT_EQ(p["force_N"][k].get<double>(), 0.0);
      continue;
    }
    EXPECT_NE(p["cutting_reason"].get<std::string>().find("depth 5.000 mm"), std::string::npos);
    EXPECT_EQ(p["status"], "converged") << i;
    EXPECT_GE(p["iterations"].get<int>(), 1);
    EXPECT_LE(p["residual_um"].get<double>(), 0.1);
    EXPECT_LT(p["force_N"][0].get<double>(), -100.0);
    EXPECT_TRUE(p["compensated"]["ok"].get<bool>());
  }
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

TEST(ForcesCli, ADepthStepBelowTheProfilesResolutionIsExit2) {
  EXPECT_NE(kMaxDepthSamples, 0.0);
  const auto r = test::runRoprec("forces --cell '" + test::sourceDir() +
                                 "/samples/cells/alu-drilling-6061.xml' --step-mm 1e-12");
  EXPECT_EQ(r.exit_code, 2) << r.out.substr(0, 200);
  EXPECT_NE(r.err.find("--step-mm"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at most"), std::string::npos) << r.err;
  const auto r2 = test::runRoprec("forces --cell '" + test::sourceDir() +
                                  "/samples/cells/alu-drilling-6061.xml' --step-mm 1e-8");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_EQ(r2.err.find("bad_alloc"), std::string::npos) << r2.err;
  EXPECT_NE(r2.err.find("--step-mm"), std::string::npos) << r2.err;
}

TEST(ForcesCli, AnAbsurdCutDepthIsExit2AtItsLineAndWritesNothing) {
  const std::string dir = test::tempDir("range-depth");
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  const std::regex depth("depth_mm=\"[^\"]*\"");
  ASSERT_TRUE(std::regex_search(cell, depth));
  cell = std::regex_replace(cell, depth, "depth_mm=\"1e300\"",
                            std::regex_constants::format_first_only);
  const std::size_t at = cell.find("depth_mm=\"1e300\"");
  const int line = 1 + static_cast<int>(std::count(cell.begin(), cell.begin() + at, '\n'));
  const std::string path = dir + "/cell.xml";
  test::writeFile(path, cell);
  const auto r = test::runRoprec("forces --cell '" + path + "' --csv '" + dir + "/d.csv'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(path + ":" + std::to_string(line)), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/d.csv"));
  EXPECT_LT(r.err.size(), 400u) << r.err;
}

// A milling cell's <coupling compliance_um_per_N> of 1e300 must not overflow the coupling to inf,
// nor a cutter's diameter or runout of 1e300 reach the forces: exit 2 at the number's line.
TEST(ForcesCli, AbsurdCouplingComplianceCutterDiameterAndRunoutAreExit2AtTheirLine) {
  // the milling and drilling samples with one number corrupted, through `forces`: exit 2 at the
  // number's line, no "internal error", nothing written
  const std::string dir = test::tempDir("forces-absurd");
  auto forcesWith = [&](const std::string& cell, const std::string& from, const std::string& to,
                        const std::string& expected) {
    std::string text = test::readFile(test::sourceDir() + "/samples/cells/" + cell);
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    test::writeFile(dir + "/cell.xml", text);
    const auto r =
        test::runRoprec("forces --cell '" + dir + "/cell.xml' --json '" + dir + "/f.json'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/f.json"));
  };
  forcesWith("alu-milling-7075.xml", "compliance_um_per_N=\"1 0 0",
             "compliance_um_per_N=\"1e300 0 0",
             "cell.xml:16: <coupling> compliance_um_per_N entry 1 = 1e+300 is outside the "
             "plausible range");
  // a milling cutter of 1e300 mm (forces must not write its 300-digit diameter), and the
  // drill's diameter below
  forcesWith("alu-milling-7075.xml", "<mill diameter_mm=\"10\"", "<mill diameter_mm=\"1e300\"",
             "cell.xml:13: <mill> diameter_mm = 1e+300 is outside the plausible range 0.1 .. 200 "
             "(cutter diameter, mm)");
  // a runout angle of 1e300 deg (its cosine would be whatever the reduction of 1e300 gives)
  forcesWith("alu-milling-7075.xml", "runout_angle_deg=\"0\"", "runout_angle_deg=\"1e300\"",
             "cell.xml:13: <mill> runout_angle_deg = 1e+300 is outside the plausible range -360 .. "
             "360 (angle of the runout, deg)");
  forcesWith("alu-drilling-7075-dc8.xml", "<drill diameter_mm=\"8\"",
             "<drill diameter_mm=\"1e300\"",
             "cell.xml:9: <drill> diameter_mm = 1e+300 is outside the plausible range 0.1 .. 100 "
             "(twist drill diameter, mm)");
}

}  // namespace
}  // namespace roprec
