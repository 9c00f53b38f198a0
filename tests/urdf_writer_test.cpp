// The calibrated URDF (`roprec card export-urdf`) read by an independent parser: kdl_parser's
// chain of the exported text gives the calibrated FK (calibratedChain, itself checked against a
// KDL truth in geometry_calibration_test.cpp) to 1e-9 m / 1e-9 rad at seeded random joints, on
// the KUKA, ABB and FANUC cards; joints without an error keep their bytes.
#include "compensator/robot/urdf_writer.hpp"

#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <random>

#include "compensator/robot/robot_card.hpp"
#include "compensator/support/error.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

Pose kdlFk(const KDL::Chain& chain, const Vec6& q) {
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::JntArray jq(6);
  for (unsigned i = 0; i < 6; ++i) jq(i) = q[i];
  KDL::Frame F;
  EXPECT_GE(fk.JntToCart(jq, F), 0);
  return test::fromKdl(F);
}

TEST(UrdfWriter, ExportedUrdfGivesTheCalibratedKinematicsInKdl) {
  for (const char* name : {"kuka-kr120-r2500-pro", "abb-irb6640-185-280", "fanuc-r2000ic-165f"}) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const GeometryCalibration cal = test::seededGeometryErrors(12, 0.4, 0.6);
    const std::string path = test::tempDir(std::string("urdfw-") + name) + "/real.urdf";
    test::writeFile(path, calibratedUrdf(robot.card.urdf_path, robot.chain, cal));
    const KDL::Chain chain = test::kdlChain(path, robot.chain.base_link, robot.chain.tip_link);
    const ChainDescription real = calibratedChain(robot.chain, cal);
    std::mt19937 rng(9);
    double moved = 0;
    for (int k = 0; k < 25; ++k) {
      Vec6 q;
      for (int i = 0; i < 6; ++i) {
        const ChainJoint& j = robot.chain.joints[static_cast<size_t>(i)];
        q[i] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
      }
      const Pose a = kdlFk(chain, q);
      const Pose b = chainForwardKinematics(real, q);
      EXPECT_LT((a.translation() - b.translation()).norm(), 1e-9);
      EXPECT_LT((a.linear() - b.linear()).norm(), 1e-9);
      moved = std::max(
          moved, (b.translation() - chainForwardKinematics(robot.chain, q).translation()).norm());
    }
    EXPECT_GT(moved, 5e-4);  // the calibration is in the exported file
  }
}

TEST(UrdfWriter, JointsWithoutErrorKeepTheirBytes) {
  const Robot robot = loadRobot({"abb-irb6700-200-260", "", ""});
  GeometryCalibration cal;
  cal.joints[2].dxyz = Vec3(2e-4, 0, 0);
  const std::string text = test::readFile(robot.card.urdf_path);
  const std::string out = calibratedUrdf(robot.card.urdf_path, robot.chain, cal);
  EXPECT_NE(out, text);
  // only joint 3's <origin> differs: the lines before it are identical
  const std::size_t j3 = text.find("name=\"" + robot.chain.joints[2].name + "\"");
  ASSERT_NE(j3, std::string::npos);
  EXPECT_EQ(out.substr(0, j3), text.substr(0, j3));
  EXPECT_EQ(calibratedUrdf(robot.card.urdf_path, robot.chain, GeometryCalibration{}), text);
}

}  // namespace
}  // namespace roprec
