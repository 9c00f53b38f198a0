// Structural dynamics at the milling tool:
//  - the periodic forced response of a one-mode system equals its closed-form receptance
//    X_k = F_k / (k − m ω² + i c ω) harmonic by harmonic (1e-9 relative);
//  - the robot's natural frequencies at a pose equal an independent computation: KDL's
//    ChainDynParam mass matrix of the same URDF with the tool as a KDL segment, the card's joint
//    stiffness in series with the servo, and Eigen's generalized eigensolver (1e-6 relative);
//  - the modal sum at ω = 0 is the linear static compliance J K⁻¹ Jᵀ (1e-9 relative);
//  - far above the robot's modes, the response to the tooth-frequency force is orders of magnitude
//    below the quasi-static C·F (more than 100 times).
#include "compensator/process/milling_dynamics.hpp"

#include <gtest/gtest.h>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <complex>

#include "compensator/robot/robot_card.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

TEST(MillingDynamics, OneModeForcedResponseIsTheClosedFormReceptance) {
  const double mass = 4.0;  // kg
  const double k = 2.5e7;   // N/m
  const double zeta = 0.04;
  const double wn = std::sqrt(k / mass);
  const double c = 2 * zeta * std::sqrt(k * mass);
  VibrationMode m;
  m.omega = wn;
  m.zeta = zeta;
  m.tcp = Vec3(0, 1, 0) / std::sqrt(mass);  // the mode moves Y only
  ModalModel dyn;
  dyn.modes.push_back(m);
  const double rpm = 9000;
  const double Omega = 2 * kPi * rpm / 60;
  const int N = 360;
  // force with a mean, harmonics 1..3 in Y and an X part the mode does not see
  std::vector<Vec3> F(N);
  const double amp[4] = {35.0, 20.0, 8.0, 3.0};
  const double phase[4] = {0.0, 0.3, -1.1, 2.0};
  for (int n = 0; n < N; ++n) {
    const double phi = 2 * kPi * n / N;
    double fy = amp[0];
    for (int h = 1; h <= 3; ++h) fy += amp[h] * std::cos(h * phi + phase[h]);
    F[static_cast<size_t>(n)] = Vec3(50 * std::sin(phi), fy, -10);
  }
  const std::vector<Vec3> x = periodicResponse(dyn, F, rpm);
  double scale = 0;
  for (int n = 0; n < N; ++n) {
    const double phi = 2 * kPi * n / N;
    double y = 0;
    for (int h = 1; h <= 3; ++h) {
      const double w = h * Omega;
      const std::complex<double> G = 1.0 / std::complex<double>(k - mass * w * w, c * w);
      y += (amp[h] * G * std::polar(1.0, h * phi + phase[h])).real();
    }
    scale = std::max(scale, std::abs(y));
    EXPECT_NEAR(x[static_cast<size_t>(n)].y(), y, 1e-9 * 1e-5) << n;
    EXPECT_EQ(x[static_cast<size_t>(n)].x(), 0.0);
  }
  EXPECT_GT(scale, 1e-6);  // a response of micrometres: the comparison is not vacuous
}

struct RobotAtPose {
  Robot robot;
  nc::ToolAttachment tool;
  nc::Model model;
  nc::JointCompliance c;
  nc::Vec6 q;
};

RobotAtPose kr120AtPose() {
  RobotAtPose r{loadRobot({"kuka-kr120-r2500-pro", "", ""}), {}, {}, {}, {}};
  r.tool.T_flange_tcp.translation() = Vec3(0, 0, 0.3);
  r.tool.mass = 30;
  r.tool.com = Vec3(0.01, 0, 0.14);
  r.tool.inertia = Vec3(0.4, 0.5, 0.2).asDiagonal();
  r.model = nc::buildModel(r.robot.chain, r.tool);
  r.c = nc::complianceFromCard(r.robot.card);
  r.q << 0.2, -1.0, 1.6, 0.3, 0.8, -0.4;
  return r;
}

TEST(MillingDynamics, RobotNaturalFrequenciesMatchKdlMassMatrix) {
  const RobotAtPose r = kr120AtPose();
  const ModalModel dyn = robotModes(r.model, r.c, r.q, 0.05);
  ASSERT_EQ(dyn.modes.size(), 6u);
  // KDL: the URDF chain, then the spindle as a fixed segment carrying its mass; the TCP as a
  // massless fixed segment
  KDL::Chain kc =
      test::kdlChain(r.robot.card.urdf_path, r.robot.chain.base_link, r.robot.chain.tip_link);
  const KDL::RigidBodyInertia I(r.tool.mass,
                                KDL::Vector(r.tool.com.x(), r.tool.com.y(), r.tool.com.z()),
                                KDL::RotationalInertia(0.4, 0.5, 0.2, 0, 0, 0));
  kc.addSegment(KDL::Segment("spindle", KDL::Joint(KDL::Joint::None), KDL::Frame::Identity(), I));
  KDL::ChainDynParam dp(kc, KDL::Vector(0, 0, -9.80665));
  KDL::JntArray jq(6);
  for (unsigned i = 0; i < 6; ++i) jq(i) = r.q[i];
  KDL::JntSpaceInertiaMatrix H(6);
  ASSERT_GE(dp.JntToMass(jq, H), 0);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6, 6);
  for (int j = 0; j < 6; ++j) {
    const double kj = r.robot.card.joints[static_cast<size_t>(j)].stiffness;
    const double ks = r.c.k_servo[j];
    K(j, j) = 1.0 / (1.0 / kj + 1.0 / ks);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, H.data);
  for (int m = 0; m < 6; ++m) {
    const double f_ref = std::sqrt(es.eigenvalues()[m]) / (2 * kPi);
    const double f = dyn.modes[static_cast<size_t>(m)].omega / (2 * kPi);
    EXPECT_NEAR(f, f_ref, 1e-6 * f_ref) << "mode " << m;
  }
  // the first mode of a 120 kg-class arm lies in the 5-40 Hz band of the literature
  EXPECT_GT(dyn.modes[0].omega / (2 * kPi), 5.0);
  EXPECT_LT(dyn.modes[0].omega / (2 * kPi), 40.0);
}

TEST(MillingDynamics, ModalSumAtZeroFrequencyIsTheLinearStaticCompliance) {
  const RobotAtPose r = kr120AtPose();
  const ModalModel dyn = robotModes(r.model, r.c, r.q, 0.05);
  KDL::Chain kc = test::kdlChain(r.robot.card.urdf_path, r.robot.chain.base_link,
                                 r.robot.chain.tip_link, r.tool.T_flange_tcp);
  KDL::ChainJntToJacSolver jac(kc);
  KDL::JntArray jq(6);
  for (unsigned i = 0; i < 6; ++i) jq(i) = r.q[i];
  KDL::Jacobian J(6);
  jac.JntToJac(jq, J);
  nc::Data d(r.model);
  nc::forwardKinematics(r.model, d, r.q);
  const Mat3 S = Vec3(1, -1, -1).asDiagonal();
  const Mat3 T = S * d.T_W_tcp.linear().transpose();
  const Eigen::Matrix<double, 3, 6> Jv = J.data.topRows<3>();
  const Mat3 C_ref =
      T * Jv * r.c.effective().cwiseInverse().asDiagonal() * Jv.transpose() * T.transpose();
  const Mat3 C = receptance(dyn, 0.0).real();
  EXPECT_LE((C - C_ref).norm(), 1e-9 * C_ref.norm());
  EXPECT_LE(receptance(dyn, 0.0).imag().norm(), 1e-20);
}

TEST(MillingDynamics, ToothFrequencyResponseIsFarBelowTheQuasiStaticOne) {
  const RobotAtPose r = kr120AtPose();
  const ModalModel dyn = robotModes(r.model, r.c, r.q, 0.05);
  const Mat3 C = receptance(dyn, 0.0).real();
  // a pure tooth-frequency force of 100 N in Y, 3 teeth at 12000 rpm: 600 Hz
  const int N = 360;
  std::vector<Vec3> F(N);
  for (int n = 0; n < N; ++n)
    F[static_cast<size_t>(n)] = Vec3(0, 100 * std::cos(3 * 2 * kPi * n / N), 0);
  const std::vector<Vec3> x = periodicResponse(dyn, F, 12000);
  double peak = 0;
  double quasi = 0;
  for (int n = 0; n < N; ++n) {
    peak = std::max(peak, x[static_cast<size_t>(n)].norm());
    quasi = std::max(quasi, (C * F[static_cast<size_t>(n)]).norm());
  }
  EXPECT_LT(peak, quasi / 100);  // (f_r/600 Hz)² for the robot modes f_r ≲ 60 Hz
  EXPECT_GT(peak, 0.0);
}

TEST(MillingDynamics, ToolModeReceptanceIsItsClosedForm) {
  ModalModel dyn;
  ToolModeSpec t;
  t.frequency_hz = 1800;
  t.stiffness = 15e6;
  t.damping_ratio = 0.03;
  addToolMode(dyn, t);
  const double wn = 2 * kPi * t.frequency_hz;
  for (double f : {0.0, 600.0, 1800.0, 2500.0}) {
    const double w = 2 * kPi * f;
    const std::complex<double> G =
        1.0 /
        (t.stiffness * std::complex<double>(1 - w * w / (wn * wn), 2 * t.damping_ratio * w / wn));
    const Mat3c H = receptance(dyn, w);
    EXPECT_NEAR(std::abs(H(0, 0) - G), 0.0, 1e-12 * std::abs(G));
    EXPECT_NEAR(std::abs(H(1, 1) - G), 0.0, 1e-12 * std::abs(G));
    EXPECT_EQ(std::abs(H(0, 1)), 0.0);
    EXPECT_EQ(std::abs(H(2, 2)), 0.0);
  }
}

}  // namespace
}  // namespace roprec
