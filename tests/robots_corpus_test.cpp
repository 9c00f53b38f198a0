/// The bundled robots against the RoboDK corpus: the public RoboDK post processors wrote
/// controller joint values together with the targets computed from them (corpus README: FK of
/// the joints equals the target to < 1e-6 mm in RoboDK's own models). Converting those
/// controller joints with the robot card's joint convention, running our URDF's forward
/// kinematics and applying the cell's tool (flange + 250 mm along flange z) must reproduce the
/// targets: workpiece frame at X = 1400, Y = 0, Z = 400 mm in the robot base frame (FANUC: in
/// World at J2 height, which is our FANUC card's base link), drilling straight down
/// (tool z = -base z) with tool x = +base x. This checks dimensions, axis signs, the FANUC J2/J3
/// coupling and each vendor's flange orientation at once, against an independent reference.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "compensator/robot/chain.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

struct TargetRow {
  int line{0};
  Vec3 target_mm{Vec3::Zero()};
  Eigen::Matrix<double, 6, 1> joints_deg{Eigen::Matrix<double, 6, 1>::Zero()};
};

std::vector<TargetRow> readTargets(const std::string& path) {
  std::ifstream in(path);
  std::vector<TargetRow> rows;
  std::string line;
  int n = 0;
  std::getline(in, line);  // header: move,x_frame_mm,y_frame_mm,z_frame_mm,j1_deg..j6_deg
  ++n;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    std::getline(ss, cell, ',');  // move type
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    EXPECT_EQ(v.size(), 9u) << path << ":" << n;
    if (v.size() != 9) continue;
    TargetRow r;
    r.line = n;
    r.target_mm = Vec3(1400.0 + v[0], v[1], 400.0 + v[2]);  // workpiece frame in the base frame
    for (int i = 0; i < 6; ++i) r.joints_deg[i] = v[3 + static_cast<size_t>(i)];
    rows.push_back(r);
  }
  return rows;
}

void checkAgainstCorpus(const std::string& robot_name, const std::string& targets_file) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  const std::string path = corpus + "/robodk/" + targets_file;
  // The corpus is there but incomplete: a failure, never a skip.
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing from the corpus";
  const Robot robot =
      loadRobot({test::sourceDir() + "/robots/" + robot_name + "/robot.xml", "", ""});
  const std::vector<TargetRow> rows = readTargets(path);
  ASSERT_EQ(rows.size(), 18u);  // 3 holes x 6 targets
  Pose tool = Pose::Identity();
  tool.translation() = Vec3(0, 0, 0.250);
  double worst_mm = 0;
  for (const TargetRow& r : rows) {
    const Eigen::Matrix<double, 6, 1> q = fromControllerJoints(robot.card, r.joints_deg * kDeg);
    // Round trip of the joint convention.
    EXPECT_LT((toControllerJoints(robot.card, q) - r.joints_deg * kDeg).cwiseAbs().maxCoeff(),
              1e-12);
    const Pose tcp = chainForwardKinematics(robot.chain, q) * tool;
    const double err_mm = (tcp.translation() * 1e3 - r.target_mm).norm();
    worst_mm = std::max(worst_mm, err_mm);
    // The joints are printed with 5 decimals (<= 5e-6 deg each): <= ~1e-3 mm at 2.8 m.
    EXPECT_LE(err_mm, 1e-3) << path << ":" << r.line;
    // Straight down; tool x along base +x (FANUC W 180 P 0 R 0, ABB q [0 1 0 0], KUKA A 0 B 0 C
    // 180).
    EXPECT_LT((tcp.linear().col(2) - Vec3(0, 0, -1)).norm(), 1e-6) << path << ":" << r.line;
    EXPECT_LT((tcp.linear().col(0) - Vec3(1, 0, 0)).norm(), 1e-6) << path << ":" << r.line;
  }
  ::testing::Test::RecordProperty("worst_mm", std::to_string(worst_mm));
}

TEST(RobotsCorpus, KukaKr120ReproducesRoboDkKrc4Targets) {
  checkAgainstCorpus("kuka-kr120-r2500-pro", "DrillKRC4_targets.csv");
}
TEST(RobotsCorpus, KukaKr120ReproducesRoboDkKrc2Targets) {
  checkAgainstCorpus("kuka-kr120-r2500-pro", "DrillKRC2DAT_targets.csv");
}
TEST(RobotsCorpus, AbbIrb6640ReproducesRoboDkIrc5Targets) {
  checkAgainstCorpus("abb-irb6640-185-280", "DrillIRC5_targets.csv");
}
TEST(RobotsCorpus, FanucR2000icReproducesRoboDkR30iaTargetsInWorld) {
  checkAgainstCorpus("fanuc-r2000ic-165f", "DRILLR30IA_targets.csv");
}

// The FANUC coupling on its own: a pure controller-J2 motion leaves the J3 arm's absolute
// orientation unchanged (the controller measures J3 from the horizontal), so the wrist centre
// moves on a circle about J2 while the forearm stays horizontal.
TEST(RobotsCorpus, FanucControllerJ2KeepsTheJ3ArmHorizontal) {
  const Robot robot =
      loadRobot({test::sourceDir() + "/robots/fanuc-r2000ic-165f/robot.xml", "", ""});
  for (const double j2_deg : {-40.0, -10.0, 0.0, 25.0, 60.0}) {
    Eigen::Matrix<double, 6, 1> ctrl;
    ctrl << 0, j2_deg, 0, 0, 0, 0;
    const Eigen::Matrix<double, 6, 1> q = fromControllerJoints(robot.card, ctrl * kDeg);
    EXPECT_NEAR(q[2], j2_deg * kDeg, 1e-15);  // q3_urdf = J3 + J2
    const Pose flange = chainForwardKinematics(robot.chain, q);
    // Faceplate z (out) stays along base +x, as at all-zero: W 180, P -90, R 0.
    EXPECT_LT((flange.linear().col(2) - Vec3::UnitX()).norm(), 1e-12) << j2_deg;
    EXPECT_LT((flange.linear().col(0) - Vec3::UnitZ()).norm(), 1e-12) << j2_deg;
  }
}

// Our URDFs were written from the published dimensions, independently of the ROS-Industrial
// macros; both must describe the same kinematics: our `flange` == their `tool0` (z out of the
// flange in both), same base frame (FANUC: World `base` in both), at seeded random joints.
TEST(RobotsCorpus, BundledUrdfsAgreeWithTheRosIndustrialUrdfs) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "corpus absent";
  const std::array<std::pair<const char*, const char*>, 3> pairs{{
      {"kuka-kr120-r2500-pro", "kr120r2500pro.urdf"},
      {"abb-irb6640-185-280", "irb6640_185_280.urdf"},
      {"fanuc-r2000ic-165f", "r2000ic165f.urdf"},
  }};
  std::mt19937 rng(23);
  for (const auto& [name, file] : pairs) {
    SCOPED_TRACE(name);
    const Robot ours = loadRobot({test::sourceDir() + "/robots/" + name + "/robot.xml", "", ""});
    const ChainDescription rosi =
        loadUrdfChain(corpus + "/urdf/" + file, {ours.card.base_link, "tool0"});
    for (size_t i = 0; i < 6; ++i) {
      EXPECT_EQ(ours.chain.joints[i].name, rosi.joints[i].name);
      EXPECT_LT((ours.chain.joints[i].axis - rosi.joints[i].axis).norm(), 1e-15);
    }
    for (int k = 0; k < 200; ++k) {
      Eigen::Matrix<double, 6, 1> q;
      for (int i = 0; i < 6; ++i) q[i] = std::uniform_real_distribution<double>(-kPi, kPi)(rng);
      const Pose a = chainForwardKinematics(ours.chain, q);
      const Pose b = chainForwardKinematics(rosi, q);
      ASSERT_LT((a.translation() - b.translation()).norm(), 1e-12) << q.transpose();
      // The ABB macro writes pi/2 as 1.57079632679 (3.4e-12 rad short).
      ASSERT_LT((a.linear() - b.linear()).norm(), 1e-11) << q.transpose();
    }
  }
}

}  // namespace
}  // namespace roprec
