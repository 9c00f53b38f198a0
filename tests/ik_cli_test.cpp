// `roprec ik` end to end: JSON solutions re-enter the chain's FK, flags as the library computes
// them, exit codes 1 (unreachable) and 2 (bad input), --cell tool handling, determinism.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "compensator/robot/chain.hpp"
#include "compensator/robot/configuration.hpp"
#include "compensator/robot/ik.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using test::runRoprec;

Vec6 jointsOf(const nlohmann::json& a) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) q[i] = a.at(static_cast<size_t>(i)).get<double>() * kDeg;
  return q;
}

TEST(IkCli, BundledRobotsListSolutionsWithFlags) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  for (const std::string& name : bundledRobotNames()) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(robot);
    Vec6 q;
    q << 0.2, -0.3, 0.4, 0.5, 0.6, 0.7;
    q = q.cwiseMax(m.lower).cwiseMin(m.upper);
    const Pose T = chainForwardKinematics(robot.chain, q);
    const Eigen::Quaterniond qu(T.linear());
    std::ostringstream pose;
    pose.precision(17);
    pose << T.translation().x() * 1e3 << " " << T.translation().y() * 1e3 << " "
         << T.translation().z() * 1e3 << " " << qu.w() << " " << qu.x() << " " << qu.y() << " "
         << qu.z();
    const auto r = runRoprec("ik --robot " + name + " --pose '" + pose.str() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_GE(j.at("solutions").size(), 4u);
    int prev = -1;
    double best = 1e9;
    for (const auto& s : j.at("solutions")) {
      const Vec6 qs = jointsOf(s.at("joints_deg"));
      const Pose Ts = chainForwardKinematics(robot.chain, qs);
      // joints printed with 6 decimals (1e-6° ≈ 1.7e-8 rad): ≤ 0.2 µm at 3 m reach.
      EXPECT_LE((Ts.translation() - T.translation()).norm(), 2e-7);
      EXPECT_TRUE(s.at("converged").get<bool>());
      EXPECT_EQ(s.at("config").get<std::string>(),
                formatConfig(configurationOf(m, robot.card, qs)));
      const int b = s.at("branch_index").get<int>();
      EXPECT_GT(b, prev);  // one per branch, ordered
      prev = b;
      best = std::min(best, (qs - q).cwiseAbs().maxCoeff());
      const Vec6 qc = jointsOf(s.at("controller_joints_deg"));
      EXPECT_LE((qc - toControllerJoints(robot.card, qs)).cwiseAbs().maxCoeff(), 1e-7);
    }
    EXPECT_LE(best, 1e-7);
  }
}

TEST(IkCli, DeterministicAndAllTurns) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  const std::string args =
      "ik --robot kuka-kr120-r2500-pro --xyzabc '1600 200 1200 10 80 -20' --all-turns";
  const auto a = runRoprec(args);
  const auto b = runRoprec(args);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  const auto primary = nlohmann::json::parse(runRoprec("ik --robot kuka-kr120-r2500-pro --xyzabc "
                                                       "'1600 200 1200 10 80 -20'")
                                                 .out);
  EXPECT_GT(nlohmann::json::parse(a.out).at("solutions").size(), primary.at("solutions").size());
}

TEST(IkCli, CellPoseIsTheTcp) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  const std::string dir = test::tempDir("ikcell");
  test::writeFile(
      dir + "/cell.xml",
      "<cell name=\"c\">\n  <robot ref=\"abb-irb6640-185-280\"/>\n"
      "  <tool name=\"spindle\" xyz=\"0 0 250\" rpy=\"0 0 0\" mass_kg=\"20\" com_mm=\"0 0 100\"/>\n"
      "</cell>\n");
  const auto withCell = runRoprec("ik --robot abb-irb6640-185-280 --cell " + dir +
                                  "/cell.xml --pose '1800 0 1000 0 0 1 0'");
  // Same flange pose without the cell: the TCP is 250 mm along the flange z, which points down
  // here.
  const auto bare = runRoprec("ik --robot abb-irb6640-185-280 --pose '1800 0 1250 0 0 1 0'");
  ASSERT_EQ(withCell.exit_code, 0) << withCell.err;
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  const auto jc = nlohmann::json::parse(withCell.out);
  const auto jb = nlohmann::json::parse(bare.out);
  EXPECT_EQ(jc.at("solutions"), jb.at("solutions"));
  EXPECT_TRUE(jc.contains("tcp"));
}

TEST(IkCli, UnreachableExitsOneWithReason) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  const auto r = runRoprec("ik --robot fanuc-r2000ic-165f --xyzabc '8000 0 0 0 0 0'");
  EXPECT_EQ(r.exit_code, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("solutions").size(), 0u);
  EXPECT_NE(j.at("unreachable").get<std::string>().find("beyond the arm's reach"),
            std::string::npos);
  EXPECT_NE(r.err.find("unreachable"), std::string::npos);
}

// A pose 1e300 mm away: "far beyond the arm's reach", never "infinite mm"; joints of 1e300° are
// refused, not echoed with 300 digits.
TEST(IkCli, AbsurdlyFarPosesAndHugeJointsGetReadableMessages) {
  const auto r = runRoprec("ik --robot kuka-kr120-r2500-pro --xyzabc '1e300 0 0 0 0 0'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("far beyond the arm's reach"), std::string::npos) << r.err;
  EXPECT_EQ((r.out + r.err).find("infinite"), std::string::npos) << r.out << r.err;
  const auto fk = runRoprec("fk --robot kuka-kr120-r2500-pro --joints '1e300 0 0 0 0 0'");
  EXPECT_EQ(fk.exit_code, 2) << fk.out.substr(0, 200);
  EXPECT_NE(fk.err.find("joint 1 = 1e+300° is beyond ten turns"), std::string::npos) << fk.err;
  EXPECT_LT(fk.out.size() + fk.err.size(), 300u);
}

TEST(IkCli, BareUrdfWithSeed) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "no corpus";
  const auto r = runRoprec("ik --robot " + corpus +
                           "/urdf/irb2400.urdf --tip tool0 --pose '900 0 1200 0 0 1 0'"
                           " --seed '0 0 0 30 0 0'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("vendor").get<std::string>(), "generic");
  EXPECT_EQ(j.at("solutions").at(0).at("config").get<std::string>().rfind("branch ", 0), 0u);
}

TEST(IkCli, BadInputExitsTwo) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  struct Bad {
    std::string args;
    std::string needle;
  };
  for (const Bad& b : std::vector<Bad>{
           {"ik --robot kuka-kr120-r2500-pro --pose '1 2 3'", "needs 7 numbers"},
           {"ik --robot kuka-kr120-r2500-pro --pose '1000 0 1000 2 0 0 0'", "unit quaternion"},
           {"ik --robot kuka-kr120-r2500-pro", "--pose"},
           {"ik --robot kuka-kr120-r2500-pro --pose '1000 0 1000 1 0 0 0' --xyzabc '1 2 3 0 0 0'",
            "exactly one"},
           {"ik --robot kuka-kr120-r2500-pro --xyzabc '1000 0 nan 0 0 0'", "not a finite number"},
           {"ik --robot kuka-kr120-r2500-pro --xyzabc '1000 0 1000 0 0 0' --seed '1 2'",
            "needs 6 numbers"},
           {"ik --robot fanuc-r2000ic-165f --xyzabc '1000 0 1000 0 0 0' --turn-axes '1 4 7'",
            "1..6"},
           {"ik --robot no-such-robot --xyzabc '1000 0 1000 0 0 0'", "unknown robot"},
           {"ik --robot kuka-kr120-r2500-pro --xyzabc '1000 0 1000 0 0 0' --bogus", "--bogus"},
       }) {
    SCOPED_TRACE(b.args);
    const auto r = runRoprec(b.args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("roprec: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(b.needle), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace roprec
