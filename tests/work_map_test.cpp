// `roprec map` (plugin/api/work_map.hpp): each map point equals `roprec predict` on a one-hole hole
// list at that point (same printed numbers), the feed reaches the process load, the CSV and HTML
// have one entry per point × feed, and bad requests exit 2 with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/report/json.hpp"
#include "plugin/report/work_map_report.hpp"
#include "support/kdl_support.hpp"
#include "support/test_support.hpp"
#include "tests/support/part_registration.hpp"

namespace roprec {
namespace {

std::string cellPath() { return test::sourceDir() + "/samples/cells/housing-kr120.xml"; }

size_t countOf(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size()))
    ++n;
  return n;
}

/// CSV line → fields (quoted fields without embedded quotes, as the map writes them).
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> f;
  std::string cur;
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      f.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  f.push_back(cur);
  return f;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

/// The value of "key": number after `"key":` inside `text` from `from`.
double jsonNumber(const std::string& text, const std::string& key, size_t from = 0) {
  const size_t at = text.find("\"" + key + "\":", from);
  if (at == std::string::npos) throw std::runtime_error("no " + key);
  return std::stod(text.substr(at + key.size() + 3));
}

TEST(WorkMap, EveryPointEqualsPredictOnAOneHoleList) {
  const std::string dir = test::tempDir("work-map");
  const std::string csv = dir + "/map.csv", html = dir + "/map.html";
  // a 3 × 2 grid on the fixture's top, drilled straight down, at the cell's own feed and another
  const test::RunResult m = test::runRoprec(
      "map --cell " + cellPath() +
      " --region \"-200 -100 250 200 100 250\" --direction \"0 0 -1\" --step 200 --feeds "
      "\"0.2 0.12\" --report " +
      html + " --csv " + csv);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::vector<std::string> rows = lines(test::readFile(csv));
  ASSERT_EQ(rows.size(), 1u + 3u * 2u * 2u);
  const std::vector<std::string> head = fields(rows[0]);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < head.size(); ++i) col[head[i]] = i;
  for (const char* k :
       {"feed_mm_per_rev", "x_mm", "y_mm", "z_mm", "status", "verdict", "config", "config_change",
        "j1_deg", "d_robot_um", "position_error_um", "U_work_um", "U95_um"})
    ASSERT_TRUE(col.count(k)) << k;

  size_t checked = 0;
  for (size_t r = 1; r < rows.size(); ++r) {
    const std::vector<std::string> f = fields(rows[r]);
    ASSERT_EQ(f.size(), head.size()) << rows[r];
    if (f[col["feed_mm_per_rev"]] != "0.2000") continue;  // predict uses the cell's feed (0.2)
    ASSERT_EQ(f[col["status"]], "ok") << rows[r];
    // the same hole as a one-hole hole list (workobject frame) through `roprec predict`
    const std::string list = dir + "/hole" + std::to_string(r) + ".csv";
    test::writeFile(list, "id,x,y,z,i,j,k\nP," + f[col["x_mm"]] + "," + f[col["y_mm"]] + "," +
                              f[col["z_mm"]] + ",0,0,-1\n");
    const test::RunResult p =
        test::runRoprec("predict --cell " + cellPath() + " " + list + " --json " + dir + "/p.json");
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const std::string json = test::readFile(dir + "/p.json");
    const size_t dev = json.find("\"deviation_um\"");
    ASSERT_NE(dev, std::string::npos);
    // δrobot vector → its norm, e⊥, U_work and the anisotropic U: equal to the printed precision
    const size_t robot = json.find("\"robot\":", dev);
    std::istringstream v(json.substr(json.find('[', robot) + 1));
    double x = 0, y = 0, z = 0;
    char comma = 0;
    v >> x >> comma >> y >> comma >> z;
    EXPECT_NEAR(std::stod(f[col["d_robot_um"]]), std::sqrt(x * x + y * y + z * z), 2e-3) << rows[r];
    EXPECT_NEAR(std::stod(f[col["position_error_um"]]), jsonNumber(json, "position_error", dev),
                1e-3 + 1e-12);
    EXPECT_NEAR(std::stod(f[col["U_work_um"]]), jsonNumber(json, "U_work", dev), 1e-3 + 1e-12);
    EXPECT_NEAR(std::stod(f[col["U95_um"]]), jsonNumber(json, "U_work_anisotropic", dev),
                1e-3 + 1e-12);
    EXPECT_NE(json.find("\"config\": \"" + f[col["config"]] + "\""), std::string::npos)
        << f[col["config"]];
    EXPECT_NE(json.find("\"verdict\": \"" + f[col["verdict"]] + "\""), std::string::npos);
    ++checked;
  }
  EXPECT_EQ(checked, 6u);

  // the HTML: one map per feed × quantity (2-D region: no slices), t/2 on e⊥ and U
  const std::string page = test::readFile(html);
  EXPECT_EQ(countOf(page, "<figure class=\"panel\">"), 2u * 3u);
  EXPECT_EQ(countOf(page, "<h2>Feed "), 2u);
  EXPECT_EQ(countOf(page, "<g class=\"tol\">"), 2u * 2u);
  EXPECT_EQ(countOf(page, "<rect class=\"c\""), 2u * 3u * 6u);
  EXPECT_EQ(page.find("http://www.w3.org/2000/svg") != std::string::npos, true);
  EXPECT_EQ(page.find("<script"), std::string::npos);
}

TEST(WorkMap, TheFeedReachesTheProcessLoad) {
  api::WorkMapRequest q;
  q.cell_path = cellPath();
  q.lo_mm = q.hi_mm = Vec3(0, 0, 250);
  q.direction = Vec3(0, 0, -1);
  q.feeds_mm_per_rev = {0.1, 0.2, 0.3};
  const api::WorkMap m = api::computeWorkMap(q);
  ASSERT_EQ(m.layers.size(), 3u);
  std::vector<double> thrust;
  for (const api::WorkMapLayer& l : m.layers) {
    ASSERT_EQ(l.points.size(), 1u);
    ASSERT_EQ(l.points[0].prediction.status, HoleStatus::kOk);
    thrust.push_back(l.points[0].prediction.force_base.norm());
  }
  // the drilling thrust grows with the feed per revolution (Kienzle: F ∝ h^(1−mc), mc < 1)
  EXPECT_LT(thrust[0], thrust[1]);
  EXPECT_LT(thrust[1], thrust[2]);
  // and less than proportionally (1 − mc < 1): doubling the feed less than doubles the thrust
  EXPECT_LT(thrust[1], 2.0 * thrust[0]);
}

TEST(WorkMap, ThreeDimensionalRegionsAreSliced) {
  api::WorkMapRequest q;
  q.cell_path = cellPath();
  q.lo_mm = Vec3(-100, -100, 200);
  q.hi_mm = Vec3(100, 100, 300);
  q.step_mm = 100;
  q.direction = Vec3(0, 0, -1);
  const api::WorkMap m = api::computeWorkMap(q);
  EXPECT_EQ(m.counts, (std::array<int, 3>{3, 3, 2}));
  ASSERT_EQ(m.layers.size(), 1u);  // the cell's feed
  EXPECT_NEAR(m.layers[0].feed_mm_per_rev, 0.2, 1e-12);
  const std::string html = api::workMapReport(m);
  EXPECT_EQ(countOf(html, "<figure class=\"panel\">"), 2u * 3u);  // two z slices
  EXPECT_EQ(countOf(html, " \u00b7 slice Z = "), 2u);
  EXPECT_EQ(lines(api::workMapCsv(m)).size(), 1u + 18u);
}

TEST(WorkMap, BadRequestsExitTwoWithAMessage) {
  const std::string base = "map --cell " + cellPath() + " --csv /dev/null ";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--region \"0 0 0 -1 0 0\" --direction \"0 0 -1\"", "second corner must not be below"},
      {"--region \"0 0 0 1 1 1\" --direction \"0 0 0\"", "non-zero drilling direction"},
      {"--region \"0 0 0 1 1 1\" --direction \"0 0 -1\" --step 0", "--step must be > 0"},
      {"--region \"0 0 0 1 1 1\" --direction \"0 0 -1\" --step -2", "--step must be > 0"},
      {"--region \"0 0 0 1000 1000 1000\" --direction \"0 0 -1\" --step 1", "more than the limit"},
      {"--region \"0 0 0 1 1\" --direction \"0 0 -1\"", "--region"},
      {"--region \"0 0 0 1 1 1\" --direction \"0 0 -1\" --feeds \"0.1 -0.2\"", "--feeds"},
      {"--region \"0 0 nan 1 1 1\" --direction \"0 0 -1\"", "--region"},
      // a tiny step is named as given, not rounded to "0.000"
      {"--region \"0 0 0 1 1 1\" --direction \"0 0 -1\" --step 1e-300", "--step 1e-300 mm"},
  };
  for (const auto& [args, what] : cases) {
    const test::RunResult r = test::runRoprec(base + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << args << "\n" << r.err;
  }
  // the suggested step fits the limit
  const test::RunResult r =
      test::runRoprec(base + "--region \"0 0 0 1000 1000 0\" --direction \"0 0 -1\" --step 1");
  ASSERT_EQ(r.exit_code, 2);
  const size_t at = r.err.find("use --step ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const double step = std::stod(r.err.substr(at + 11));
  const double n = std::pow(std::floor(1000 / step + 1e-9) + 1, 2);
  EXPECT_LE(n, 250000.0) << step;
  // --help names the options
  const test::RunResult h = test::runRoprec("map --help");
  EXPECT_EQ(h.exit_code, 0);
  for (const char* o : {"--region", "--direction", "--feeds", "--step", "--report", "--csv"})
    EXPECT_NE((h.out + h.err).find(o), std::string::npos) << o;
}

TEST(WorkMap, CsvCarriesTheJointsAsTheFanucControllerShowsThem) {
  // R-2000iC card: controller J3 = q3_urdf - q2_urdf (j23_coupling -1), no sign or offset on the
  // other joints (robots/fanuc-r2000ic-165f/robot.xml)
  const std::string dir = test::tempDir("work-map-fanuc");
  const std::string csv = dir + "/map.csv";
  const test::RunResult m = test::runRoprec(
      "map --cell " + test::sourceDir() +
      "/samples/cells/housing-r2000.xml --region \"-200 -100 250 200 100 250\" --direction "
      "\"0 0 -1\" --step 200 --report " +
      dir + "/map.html --csv " + csv);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::vector<std::string> rows = lines(test::readFile(csv));
  const std::vector<std::string> head = fields(rows.at(0));
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < head.size(); ++i) col[head[i]] = i;
  ASSERT_TRUE(col.count("j3_ctrl_deg"));
  size_t checked = 0;
  bool coupled = false;
  for (size_t r = 1; r < rows.size(); ++r) {
    const std::vector<std::string> f = fields(rows[r]);
    if (f[col["status"]] != "ok") continue;
    const auto v = [&](const std::string& k) { return std::stod(f[col[k]]); };
    EXPECT_NEAR(v("j3_ctrl_deg"), v("j3_deg") - v("j2_deg"), 1.5e-3) << rows[r];
    for (const char* j : {"1", "2", "4", "5", "6"})
      EXPECT_NEAR(v(std::string("j") + j + "_ctrl_deg"), v(std::string("j") + j + "_deg"), 1e-9);
    coupled = coupled || std::fabs(v("j2_deg")) > 1.0;
    ++checked;
  }
  EXPECT_GE(checked, 3u);
  EXPECT_TRUE(coupled) << "J2 near 0 everywhere: the test would not see the coupling";
}

// A map of a cell whose robot card is calibrated (the shop-floor sample's): each point is
// commanded by the controller's model — KDL on the card's nominal URDF at the commanded joints
// reaches the map point — and drilled by the calibrated one: the real TCP is KDL on the URDF
// `card export-urdf` writes, at the equilibrium joints, both to 1e-9 m.
TEST(WorkMap, ACalibratedCardDrillsWithTheExportedUrdfsKinematics) {
  api::WorkMapRequest q;
  q.cell_path = test::sourceDir() + "/samples/verification/housing-kr120-calibrated.xml";
  q.lo_mm = Vec3(-100, -100, 150);
  q.hi_mm = Vec3(100, 100, 150);
  q.step_mm = 200;
  const api::WorkMap m = api::computeWorkMap(q);
  const RobotCard& card = m.context.robot.card;
  ASSERT_TRUE(card.calibration.has_value());
  const Pose tool = m.context.tool.T_flange_tcp;
  const KDL::Chain real = test::kdlExportedChain(card.file, test::tempDir("mapcal"), tool);
  const KDL::Chain nominal = test::kdlChain(card.urdf_path, m.context.robot.chain.base_link,
                                            m.context.robot.chain.tip_link, tool);
  ASSERT_EQ(m.layers.size(), 1u);
  ASSERT_EQ(m.layers[0].points.size(), 4u);
  double geometry = 0;
  for (const api::WorkMapPoint& pt : m.layers[0].points) {
    const HolePrediction& h = pt.prediction;
    ASSERT_EQ(h.status, HoleStatus::kOk) << h.reason;
    const Vec3 target = m.context.cell.T_base_wobj * (pt.p_mm * 1e-3);
    EXPECT_LT((test::kdlPose(nominal, h.joints).translation() - target).norm(), 1e-9);
    EXPECT_LT(
        (test::kdlPose(real, h.deflection.theta).translation() - h.deflection.T_real.translation())
            .norm(),
        1e-9);
    geometry = std::max(geometry, (test::kdlPose(real, h.joints).translation() - target).norm());
  }
  EXPECT_GT(geometry, 0.1e-3) << "the calibration moves the real TCP";
}

// A cell with a <part_registration> (verify --write-cell): each map point is a point of the
// nominal part, aimed where the registration found it — the same prediction as predict of a
// one-hole hole list at that point with the same cell (double precision), at the registered
// pose computed by hand, G = T_W_wobj · F⁻¹ · T_W_wobj⁻¹.
TEST(WorkMap, ARegisteredCellMapsThePointsOfTheRegisteredPart) {
  const std::string dir = test::tempDir("map-registered");
  const std::string text = test::withPartRegistration(test::readFile(cellPath()));
  ASSERT_FALSE(text.empty());
  api::WorkMapRequest q;
  q.cell_path = dir + "/registered.xml";
  test::writeFile(q.cell_path, text);
  q.lo_mm = Vec3(-100, -100, 250);
  q.hi_mm = Vec3(100, 100, 250);
  q.step_mm = 200;
  const api::WorkMap m = api::computeWorkMap(q);
  ASSERT_EQ(m.layers.size(), 1u);
  ASSERT_EQ(m.layers[0].points.size(), 4u);
  const Pose F = test::partRegistration();  // the registration by hand
  const Pose T_W_wobj = m.context.cell.T_base_wobj;
  const Pose G = T_W_wobj * F.inverse() * T_W_wobj.inverse();
  for (const api::WorkMapPoint& pt : m.layers[0].points) {
    const HolePrediction& h = pt.prediction;
    ASSERT_EQ(h.status, HoleStatus::kOk) << h.reason;
    const std::string list = dir + "/" + h.id + ".csv";
    test::writeFile(list, "id,x,y,z,i,j,k\nP," + std::to_string(pt.p_mm.x()) + "," +
                              std::to_string(pt.p_mm.y()) + "," + std::to_string(pt.p_mm.z()) +
                              ",0,0,-1\n");
    const api::PredictionResult p = api::predictJob(q.cell_path, list);
    ASSERT_EQ(p.holes.size(), 1u);
    const Vec3 registered = G * (T_W_wobj * (pt.p_mm * 1e-3));
    EXPECT_LT((p.context.job.requests[0].T_W_tcp.translation() - registered).norm(), 1e-9);
    EXPECT_LT((h.d_work - p.holes[0].d_work).norm(), 1e-9);
    EXPECT_LT(
        (h.deflection.T_real.translation() - p.holes[0].deflection.T_real.translation()).norm(),
        1e-9);
    EXPECT_LT((h.joints - p.holes[0].joints).norm(), 1e-9);
    EXPECT_GT((registered - T_W_wobj * (pt.p_mm * 1e-3)).norm(), 0.1e-3);
  }
}

}  // namespace
}  // namespace roprec
