// ∂p_tcp/∂c of the calibration parameters against central differences of the calibrated chain's
// forward kinematics (calibratedChain + chainForwardKinematics, h = 1e-7 m / rad), at seeded
// joints of a calibrated KUKA and FANUC: agreement to 2e-3 relative (the columns are first order
// in the calibrated errors of ≤ 0.6 mrad) and the σ vector in column order.
#include "compensator/robot/calibration_jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>
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

// The covariance path of calibrationPositionCovariance against sampled calibrations pushed
// through the calibrated chain's FK (no Jacobian): a covariance in which joint 1's origin and the
// base are strongly anti-correlated (as a registration absorbs joint 1) must give the small
// combined spread, not the large single σ. 3-D covariance within 5 % of the sampled one in every
// direction (4000 samples: sampling error ~2 %), and far below the independent-σ result.
TEST(CalibrationJacobian, CorrelatedCovarianceMatchesAMonteCarloOfTheCalibratedChain) {
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  GeometryCalibration cal = test::seededGeometryErrors(6, 0.3, 0.4);
  cal.model_error = 0.0;
  cal.covariance_parameters = {"base_x", "base_y", "base_rz", "j1_x", "j1_y", "j1_rz", "j2_ry"};
  // j1 = −base + small independent part (the base frame and joint 1's frame differ by the
  // joint's origin: the combination is then only approximately zero, which FK must tell)
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(7, 7);
  for (int a = 0; a < 3; ++a) {
    const double big = a < 2 ? 0.3e-3 : 0.5e-3;
    L(a, a) = big;
    L(3 + a, a) = -big;
    L(3 + a, 3 + a) = 2e-6;
  }
  L(6, 6) = 5e-6;
  cal.covariance = L * L.transpose();
  Pose tool = Pose::Identity();
  tool.translation() = Vec3(0, 0, 0.32);
  const ChainDescription real = calibratedChain(robot.chain, cal);
  const Vec6 q = (Vec6() << 0.2, -1.3, 1.6, 0.2, 0.9, -0.4).finished();
  const Mat3 C = calibrationPositionCovariance(real, tool, q, cal);
  GeometryCalibration independent = cal;
  independent.covariance_parameters.clear();
  independent.joints[0].sigma_xyz = Vec3(0.3e-3, 0.3e-3, 0);
  independent.base.sigma_xyz = Vec3(0.3e-3, 0.3e-3, 0);
  const Mat3 C_independent = calibrationPositionCovariance(real, tool, q, independent);
  const Vec3 p0 = (chainForwardKinematics(real, q) * tool).translation();
  std::mt19937 rng(8);
  std::normal_distribution<double> n(0.0, 1.0);
  Mat3 S = Mat3::Zero();
  const int N = 4000;
  for (int s = 0; s < N; ++s) {
    Eigen::VectorXd z(7);
    for (int k = 0; k < 7; ++k) z[k] = n(rng);
    const Eigen::VectorXd d = L * z;
    GeometryCalibration c = cal;
    for (int k = 0; k < 7; ++k) {
      const int comp = calibrationComponent(cal.covariance_parameters[static_cast<size_t>(k)]);
      FrameError& e = comp < 6 ? c.base : c.joints[static_cast<size_t>((comp - 6) / 6)];
      const int a = comp < 6 ? comp : (comp - 6) % 6;
      (a < 3 ? e.dxyz[a] : e.drpy[a - 3]) += d[k];
    }
    const Vec3 dp =
        (chainForwardKinematics(calibratedChain(robot.chain, c), q) * tool).translation() - p0;
    S += dp * dp.transpose();
  }
  S /= N;
  const Eigen::SelfAdjointEigenSolver<Mat3> es(S);
  for (int k = 0; k < 3; ++k) {
    const Vec3 v = es.eigenvectors().col(k);
    const double sampled = std::sqrt(v.dot(S * v));
    EXPECT_NEAR(std::sqrt(v.dot(C * v)), sampled, 0.05 * sampled + 1e-7) << "direction " << k;
  }
  std::printf("correlated: sqrt(trace) %.2f um (sampled %.2f um), independent %.1f um\n",
              std::sqrt(C.trace()) * 1e6, std::sqrt(S.trace()) * 1e6,
              std::sqrt(C_independent.trace()) * 1e6);
  EXPECT_LT(std::sqrt(C.trace()), 0.1 * std::sqrt(C_independent.trace()));
  // the model error adds isotropically
  cal.model_error = 4e-6;
  const Mat3 C_floor = calibrationPositionCovariance(real, tool, q, cal);
  EXPECT_LT((C_floor - C - 16e-12 * Mat3::Identity()).norm(), 1e-20);
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
