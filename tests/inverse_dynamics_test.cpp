// Virtual-power inverse dynamics against independent references:
//  * Orocos KDL ChainIdSolver_RNE on the same URDF and inertials (+ tool mass as an extra KDL
//    segment, + a TCP wrench as KDL f_ext) for seeded random q, q̇, q̈: ≤ 1e-9 relative to the
//    largest torque;
//  * RᵀMR against KDL ChainDynParam::JntToMass;
//  * motor torque three ways: virtual power (adjoint sweep), minus the multipliers μ of driving
//    constraints θ − θ(t) = 0 in the dense Lagrange system, and Φ_{i,θ_i} λ_i of the angle rows.
#include "compensator/robot/inverse_dynamics.hpp"

#include <gtest/gtest.h>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>

#include <random>

#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/counting_new.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nc::Vec6;

struct DynCase {
  std::string label;
  std::string urdf;
  std::string tip;
};

std::vector<DynCase> dynCases() {
  std::vector<DynCase> out;
  for (const std::string& name : bundledRobotNames()) {
    const RobotCard card = loadRobotCard(bundledRobotsDir() + "/" + name + "/robot.xml");
    out.push_back({name, card.urdf_path, card.flange_link});
  }
  if (!test::corpusDir().empty()) {
    out.push_back(
        {"corpus kr120r2500pro", test::corpusDir() + "/urdf/kr120r2500pro.urdf", "flange"});
  }
  return out;
}

nc::ToolAttachment spindle() {
  nc::ToolAttachment t;
  t.T_flange_tcp.translation() = Vec3(0.01, -0.02, 0.31);
  t.T_flange_tcp.linear() = rotationFromRpy(0.0, 0.2, -0.4);
  t.mass = 25.8;
  t.com = Vec3(0.005, 0.0, 0.12);
  t.inertia = Vec3(0.35, 0.33, 0.08).asDiagonal();
  return t;
}

KDL::Chain kdlWithTool(const DynCase& c, const ChainDescription& chain,
                       const nc::ToolAttachment& t) {
  KDL::Chain k = test::kdlChain(c.urdf, chain.base_link, chain.tip_link);
  // Tool segment: frame = TCP; its inertia about the COM, expressed in the TCP frame.
  const Pose T_tcp_flange = t.T_flange_tcp.inverse();
  const Vec3 com_tcp = T_tcp_flange * t.com;
  const Mat3 I_tcp = T_tcp_flange.linear() * t.inertia * T_tcp_flange.linear().transpose();
  const KDL::RotationalInertia Ic(I_tcp(0, 0), I_tcp(1, 1), I_tcp(2, 2), I_tcp(0, 1), I_tcp(0, 2),
                                  I_tcp(1, 2));
  k.addSegment(KDL::Segment(
      "tool", KDL::Joint(KDL::Joint::None), test::toKdl(t.T_flange_tcp),
      KDL::RigidBodyInertia(t.mass, KDL::Vector(com_tcp.x(), com_tcp.y(), com_tcp.z()), Ic)));
  return k;
}

TEST(InverseDynamics, TorquesAndJointSpaceInertiaMatchKdl) {
  const auto cases = dynCases();
  if (cases.empty()) GTEST_SKIP() << "no robots with inertials";
  for (const DynCase& c : cases) {
    SCOPED_TRACE(c.label);
    const ChainDescription chain = loadUrdfChain(c.urdf, {"", c.tip});
    ASSERT_TRUE(chain.has_inertials);
    const nc::ToolAttachment tool = spindle();
    const nc::Model model = nc::buildModel(chain, tool);
    nc::Data data(model);
    const KDL::Chain kchain = kdlWithTool(c, chain, tool);
    const KDL::Vector g(0, 0, -9.80665);
    KDL::ChainIdSolver_RNE rne(kchain, g);
    KDL::ChainDynParam dyn(kchain, g);
    std::mt19937 rng(77);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 0; n < 200; ++n) {
      Vec6 z;
      Vec6 zd;
      Vec6 zdd;
      for (int i = 0; i < 6; ++i) {
        const auto& j = chain.joints[static_cast<size_t>(i)];
        z[i] = 0.5 * (j.lower + j.upper) + 0.5 * (j.upper - j.lower) * u(rng) * 0.9;
        zd[i] = u(rng);
        zdd[i] = 2 * u(rng);
      }
      nc::Loads loads;
      loads.tcp.force = Vec3(u(rng), u(rng), u(rng)) * 1500.0;
      loads.tcp.moment = Vec3(u(rng), u(rng), u(rng)) * 40.0;
      ASSERT_TRUE(nc::solvePosition(model, data, z).converged);
      nc::framePoses(model, data);
      const Vec6 tau = nc::inverseDynamics(model, data, zd, zdd, loads);

      KDL::JntArray q(6);
      KDL::JntArray qd(6);
      KDL::JntArray qdd(6);
      KDL::JntArray t(6);
      for (unsigned i = 0; i < 6; ++i) {
        q(i) = z[i];
        qd(i) = zd[i];
        qdd(i) = zdd[i];
      }
      KDL::Wrenches fext(kchain.getNrOfSegments(), KDL::Wrench::Zero());
      const Mat3 Rt = data.T_W_tcp.linear().transpose();
      const Vec3 f = Rt * loads.tcp.force;
      const Vec3 m = Rt * loads.tcp.moment;
      fext.back() = KDL::Wrench(KDL::Vector(f.x(), f.y(), f.z()), KDL::Vector(m.x(), m.y(), m.z()));
      ASSERT_GE(rne.CartToJnt(q, qd, qdd, fext, t), 0);
      double tmax = 0;
      for (unsigned i = 0; i < 6; ++i) tmax = std::max(tmax, std::abs(t(i)));
      for (unsigned i = 0; i < 6; ++i) EXPECT_NEAR(tau[i], t(i), 1e-9 * tmax) << "joint " << i + 1;

      KDL::JntSpaceInertiaMatrix H(6);
      ASSERT_GE(dyn.JntToMass(q, H), 0);
      const nc::Mat6 Mbar = nc::jointSpaceInertia(model, data);
      double hmax = 0;
      for (unsigned r = 0; r < 6; ++r) {
        for (unsigned k = 0; k < 6; ++k) hmax = std::max(hmax, std::abs(H(r, k)));
      }
      for (unsigned r = 0; r < 6; ++r) {
        for (unsigned k = 0; k < 6; ++k) EXPECT_NEAR(Mbar(r, k), H(r, k), 1e-9 * hmax);
      }
    }
  }
}

TEST(InverseDynamics, MotorTorqueThreeWaysAgree) {
  const auto cases = dynCases();
  if (cases.empty()) GTEST_SKIP();
  const ChainDescription chain = loadUrdfChain(cases.front().urdf, {"", cases.front().tip});
  const nc::Model model = nc::buildModel(chain, spindle());
  nc::Data data(model);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 0; n < 20; ++n) {
    Vec6 z;
    Vec6 zd;
    Vec6 zdd;
    for (int i = 0; i < 6; ++i) {
      z[i] = u(rng);
      zd[i] = u(rng);
      zdd[i] = u(rng);
    }
    nc::Loads loads;
    loads.tcp.force = Vec3(300, -200, 800);
    ASSERT_TRUE(nc::solvePosition(model, data, z).converged);
    const Vec6 tau = nc::inverseDynamics(model, data, zd, zdd, loads);
    const nc::VecC lambda = data.lambda;
    // Dense Lagrange system with driving constraints B q − z(t) = 0:
    //   M q̈ + Φ_qᵀ λ + Bᵀ μ = Q_ext  →  Aᵀ [λ; μ] = Q_ext − M q̈,  τ = −μ.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nc::kNq, nc::kNq);
    nc::assemblePhiq(model, data, A.topRows(nc::kNc));
    for (int i = 0; i < 6; ++i) A(nc::kNc + i, nc::idxTheta(i)) = 1.0;
    nc::VecQ Q;
    nc::generalizedForces(model, data, loads, Q);
    nc::VecQ Mqdd = nc::VecQ::Zero();
    nc::addMassTimes(model, data.qdd, Mqdd);
    const Eigen::VectorXd lm = A.transpose().fullPivLu().solve(Eigen::VectorXd(Q - Mqdd));
    const Vec6 mu = lm.tail<6>();
    const double scale = 1.0 + tau.cwiseAbs().maxCoeff();
    EXPECT_LE((tau + mu).norm(), 1e-9 * scale);
    // Angle-row multipliers: τ_i = ∂Φ_i/∂θ_i λ_i.
    for (int i = 0; i < 6; ++i) {
      const double dphi = A(nc::kAngleRow + i, nc::idxTheta(i));
      EXPECT_NEAR(tau[i], dphi * lambda[nc::kAngleRow + i], 1e-9 * scale);
      EXPECT_NEAR(lm[nc::kAngleRow + i], lambda[nc::kAngleRow + i], 1e-9 * scale);
    }
  }
}

TEST(InverseDynamics, PositionDynamicsAndStaticsAllocateNothing) {
  const auto cases = dynCases();
  if (cases.empty()) GTEST_SKIP();
  const ChainDescription chain = loadUrdfChain(cases.front().urdf, {"", cases.front().tip});
  const nc::Model model = nc::buildModel(chain, spindle());
  nc::Data data(model);
  Vec6 z;
  z << 0.1, -1.0, 1.2, 0.3, 0.4, 0.5;
  nc::Loads loads;
  const long allocations = test::allocationsOf([&] {
    nc::solvePosition(model, data, z);
    nc::inverseDynamics(model, data, Vec6::Ones(), Vec6::Ones(), loads);
    nc::staticTorques(model, data, loads);
  });
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace roprec
