// ∂p_tcp/∂c of the calibration parameters against central differences of the calibrated chain's
// forward kinematics (calibratedChain + chainForwardKinematics, h = 1e-7 m / rad), at seeded
// joints of a calibrated KUKA and FANUC: agreement to 2e-3 relative (the columns are first order
// in the calibrated errors of ≤ 0.6 mrad) and the σ vector in column order.
#include "compensator/robot/calibration_jacobian.hpp"

#include <gtest/gtest.h>

#include <random>

#include "compensator/robot/robot_card.hpp"
#include "tests/support/kdl_support.hpp"

namespace roprec {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// The calibration with parameter c moved by h.
GeometryCalibration moved(GeometryCalibration cal, int c, double h) {
  FrameError& e = c < 6    ? cal.base
                  : c < 42 ? cal.joints[static_cast<size_t>((c - 6) / 6)]
                           : cal.tool;
  const int k = (c < 6 ? c : c < 42 ? (c - 6) % 6 : c - 42);
  (k < 3 ? e.dxyz[k] : e.drpy[k - 3]) += h;
  return cal;
}

TEST(CalibrationJacobian, ColumnsMatchCentralDifferencesOfTheCalibratedChain) {
  Pose tool = Pose::Identity();
  tool.translation() = Vec3(0.03, -0.02, 0.31);
  tool.linear() = Eigen::AngleAxisd(0.4, Vec3(1, 0, 1).normalized()).toRotationMatrix();
  for (const char* name : {"kuka-kr120-r2500-pro", "fanuc-r2000ic-165f"}) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const GeometryCalibration cal = test::seededGeometryErrors(4, 0.4, 0.6);
    const ChainDescription real = calibratedChain(robot.chain, cal);
    std::mt19937 rng(2);
    for (int s = 0; s < 5; ++s) {
      Vec6 q;
      for (int i = 0; i < 6; ++i) q[i] = std::uniform_real_distribution<double>(-1.5, 1.5)(rng);
      CalibrationJacobian J;
      tcpCalibrationJacobian(real, tool, q, J);
      const double h = 1e-7;
      for (int c = 0; c < kCalibrationParameters; ++c) {
        const Vec3 plus =
            (chainForwardKinematics(calibratedChain(robot.chain, moved(cal, c, h)), q) * tool)
                .translation();
        const Vec3 minus =
            (chainForwardKinematics(calibratedChain(robot.chain, moved(cal, c, -h)), q) * tool)
                .translation();
        const Vec3 fd = (plus - minus) / (2 * h);
        EXPECT_LT((J.col(c) - fd).norm(), 2e-3 * std::max(1.0, fd.norm())) << "column " << c;
      }
    }
  }
}

TEST(CalibrationJacobian, SigmasFollowTheColumnOrder) {
  GeometryCalibration cal;
  cal.base.sigma_xyz = Vec3(1, 2, 3);
  cal.joints[3].sigma_rpy = Vec3(4, 5, 6);
  cal.tool.sigma_xyz = Vec3(7, 8, 9);
  const CalibrationSigmas s = calibrationSigmas(cal);
  EXPECT_EQ(s[1], 2);
  EXPECT_EQ(s[6 + 18 + 3], 4);
  EXPECT_EQ(s[6 + 18 + 5], 6);
  EXPECT_EQ(s[42], 7);
  EXPECT_EQ(s.sum(), 45);
}

}  // namespace
}  // namespace roprec
