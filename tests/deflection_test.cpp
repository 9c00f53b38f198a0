// Static deviation with flexible joints against independent computations:
//  * a single massive link under gravity: φ = −m g l cos(θ)/k solved as a scalar equation;
//  * the linear joint-compliance estimate δ ≈ J K⁻¹ (Jᵀw − g(q)) with KDL's Jacobian and RNE
//    gravity torques: agreement within the second-order (complementary-stiffness) difference,
//    ≤ 0.5 % at realistic loads;
//  * a nonlinear equilibrium θ = θ_m − K⁻¹ τ_KDL(θ) iterated in the test with KDL FK + RNE
//    (wrench fixed in the base frame, applied at the TCP): ≤ 0.01 µm;
//  * compensation ∘ prediction is the identity to ≤ 1e-12 rad.
#include "compensator/robot/deflection.hpp"

#include <gtest/gtest.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <random>

#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/counting_new.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nc::Vec6;

TEST(Deflection, SingleLinkUnderGravityMatchesScalarEquation) {
  const ChainDescription chain =
      loadUrdfChain(test::sourceDir() + "/tests/data/single_link_6r.urdf");
  const nc::Model model = nc::buildModel(chain);
  nc::Data data(model);
  nc::JointCompliance c;
  c.k = Vec6::Constant(1e6);
  const double k2 = 2.0e5;
  c.k[1] = k2;
  const double m = 50.0;
  const double g = 9.80665;
  const double l = 1.0;
  for (const double th_deg : {-60.0, -20.0, 0.0, 35.0, 80.0}) {
    Vec6 th_m = Vec6::Zero();
    th_m[1] = th_deg * kDeg;
    const nc::Deflection d = nc::predictDeflection(model, data, c, th_m, nc::Loads{});
    ASSERT_TRUE(d.converged);
    // Axis −y: positive q2 lifts the mass; the drive holds m g l cos(q2). Link side:
    // θ = θ_m − m g l cos θ / k  (bisection, independent of the library).
    double lo = th_m[1] - 0.1;
    double hi = th_m[1] + 0.1;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      const double f = mid - th_m[1] + m * g * l * std::cos(mid) / k2;
      (f > 0 ? hi : lo) = mid;
    }
    EXPECT_NEAR(d.theta[1], 0.5 * (lo + hi), 1e-13);
    EXPECT_NEAR(d.tau[1], m * g * l * std::cos(d.theta[1]), 1e-9);
    EXPECT_NEAR(d.phi[1], -m * g * l * std::cos(d.theta[1]) / k2, 1e-15);
    for (int i : {0, 2, 3, 4, 5}) EXPECT_NEAR(d.theta[i], th_m[i], 1e-15);
  }
}

struct RobotUnderTest {
  std::string label;
  std::string urdf;
  ChainDescription chain;
  RobotCard card;
};

std::vector<RobotUnderTest> bundled() {
  std::vector<RobotUnderTest> out;
  for (const std::string& name : bundledRobotNames()) {
    const Robot r = loadRobot({name, "", ""});
    out.push_back({name, r.card.urdf_path, r.chain, r.card});
  }
  return out;
}

nc::JointCompliance compliance(const RobotCard& card) {
  nc::JointCompliance c;
  for (int i = 0; i < 6; ++i) c.k[i] = card.joints[static_cast<size_t>(i)].stiffness;
  return c;
}

TEST(Deflection, AgreesWithLinearAndNonlinearKdlCompliance) {
  const auto robots = bundled();
  if (robots.empty()) GTEST_SKIP();
  nc::ToolAttachment tool;
  tool.T_flange_tcp.translation() = Vec3(0, 0, 0.3);
  tool.mass = 25.8;
  tool.com = Vec3(0, 0, 0.12);
  for (const RobotUnderTest& s : robots) {
    SCOPED_TRACE(s.label);
    const nc::Model model = nc::buildModel(s.chain, tool);
    nc::Data data(model);
    const nc::JointCompliance c = compliance(s.card);
    KDL::Chain kc = test::kdlChain(s.urdf, s.chain.base_link, s.chain.tip_link);
    kc.addSegment(KDL::Segment("tool", KDL::Joint(KDL::Joint::None), test::toKdl(tool.T_flange_tcp),
                               KDL::RigidBodyInertia(tool.mass, KDL::Vector(0, 0, 0.12 - 0.3))));
    KDL::ChainFkSolverPos_recursive fk(kc);
    KDL::ChainJntToJacSolver jac(kc);
    KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 0; n < 20; ++n) {
      Vec6 th_m;
      for (int i = 0; i < 6; ++i) {
        const auto& j = s.chain.joints[static_cast<size_t>(i)];
        th_m[i] = 0.5 * (j.lower + j.upper) + 0.35 * (j.upper - j.lower) * u(rng);
      }
      nc::Loads loads;
      loads.tcp.force = Vec3(u(rng), u(rng), u(rng)).normalized() * 800.0;  // drilling thrust level
      loads.tcp.moment = Vec3(u(rng), u(rng), u(rng)).normalized() * 3.0;
      const nc::Deflection d = nc::predictDeflection(model, data, c, th_m, loads);
      ASSERT_TRUE(d.converged);
      EXPECT_LE(d.iterations, 12);

      auto kdlTau = [&](const Vec6& th, KDL::Frame& F) {
        KDL::JntArray q(6);
        KDL::JntArray zero(6);
        KDL::JntArray t(6);
        for (unsigned i = 0; i < 6; ++i) q(i) = th[i];
        fk.JntToCart(q, F);
        const Mat3 Rt = test::fromKdl(F).linear().transpose();
        const Vec3 f = Rt * loads.tcp.force;
        const Vec3 mm = Rt * loads.tcp.moment;
        KDL::Wrenches fext(kc.getNrOfSegments(), KDL::Wrench::Zero());
        fext.back() =
            KDL::Wrench(KDL::Vector(f.x(), f.y(), f.z()), KDL::Vector(mm.x(), mm.y(), mm.z()));
        rne.CartToJnt(q, zero, zero, fext, t);
        Vec6 out;
        for (unsigned i = 0; i < 6; ++i) out[i] = t(i);
        // the card's axis-2 balancer carries part of the weight (its law: gravity_test.cpp)
        const Counterbalance& cb = s.chain.counterbalance;
        if (cb.present()) out[cb.joint] -= balancerTorque(cb, th[cb.joint]);
        return out;
      };
      // nonlinear equilibrium with KDL (fixed point in the test)
      Vec6 th = th_m;
      KDL::Frame F;
      for (int it = 0; it < 100; ++it) th = th_m - kdlTau(th, F).cwiseQuotient(c.k);
      kdlTau(th, F);
      const Pose T_real = test::fromKdl(F);
      KDL::Frame F0;
      kdlTau(th_m, F0);
      const Pose T_nom = test::fromKdl(F0);
      const Vec3 dp_kdl = T_real.translation() - T_nom.translation();
      EXPECT_LE((d.dp - dp_kdl).norm(), 1e-8) << "0.01 µm";
      EXPECT_LE((d.drot - smallRotationDifference(T_real.linear(), T_nom.linear())).norm(), 1e-9);

      // linear estimate δ ≈ J K⁻¹ (Jᵀ w − g(q)) at θ_m, all from KDL
      KDL::JntArray q(6);
      for (unsigned i = 0; i < 6; ++i) q(i) = th_m[i];
      KDL::Jacobian J(6);
      jac.JntToJac(q, J);
      const Vec6 tau0 = kdlTau(th_m, F0);  // = g(q) − Jᵀ w
      const Vec6 phi0 = -tau0.cwiseQuotient(c.k);
      const Vec6 dx = J.data * phi0;
      // The difference is the complementary-stiffness term: θ − θ_m = −(I + K⁻¹D)⁻¹ K⁻¹ τ₀ + O(φ²),
      // D = ∂τ/∂θ (KDL central differences). Documented bound: ‖K⁻¹D‖∞ (+ O(φ)).
      nc::Mat6 D;
      for (int j = 0; j < 6; ++j) {
        Vec6 tp = th_m;
        Vec6 tm = th_m;
        tp[j] += 1e-6;
        tm[j] -= 1e-6;
        D.col(j) = (kdlTau(tp, F) - kdlTau(tm, F)) / 2e-6;
      }
      nc::Mat6 KinvD;
      for (int i = 0; i < 6; ++i) KinvD.row(i) = D.row(i) / c.k[i];
      const Vec6 dx2 = J.data * (nc::Mat6::Identity() + KinvD).partialPivLu().solve(phi0);
      const double rel = (d.dp - dx.head<3>()).norm() / d.dp.norm();
      // ‖J((I + K⁻¹D)⁻¹ − I)φ₀‖ ≤ ‖K⁻¹D‖∞/(1 − ‖K⁻¹D‖∞) Σⱼ‖J_j‖ ‖φ₀‖∞: relative to ‖δ‖ the bound
      // grows where the joint contributions cancel (a thrust against the weight), factor c ≥ 1.
      double column_sum = 0;
      for (int j = 0; j < 6; ++j) column_sum += J.data.block<3, 1>(0, j).norm();
      const double c_cancel =
          std::max(1.0, column_sum * phi0.lpNorm<Eigen::Infinity>() / d.dp.norm());
      const double bound = (KinvD.lpNorm<Eigen::Infinity>() * 1.5 + 1e-3) * c_cancel;
      EXPECT_LE(rel, bound) << "linear vs nonlinear";
      // what remains is the geometric second-order term ½ Δθᵀ H Δθ, relative size ~ |φ| ≈ 1e-3
      EXPECT_LE((d.dp - dx2.head<3>()).norm(), 5e-3 * d.dp.norm()) << "second-order remainder";
    }
  }
}

TEST(Deflection, LinearEstimateWithinHalfPercentAtAKr120WorkingPose) {
  // roprec deflect --robot kuka-kr120-r2500-pro --joints "0 -60 100 0 50 0" --wrench "0 0 800 0 0
  // 0"
  const auto robots = bundled();
  const auto it = std::find_if(robots.begin(), robots.end(), [](const RobotUnderTest& r) {
    return r.label == "kuka-kr120-r2500-pro";
  });
  if (it == robots.end()) GTEST_SKIP();
  const nc::Model model = nc::buildModel(it->chain);
  nc::Data data(model);
  const nc::JointCompliance c = compliance(it->card);
  Vec6 th_m;
  th_m << 0, -60, 100, 0, 50, 0;
  th_m *= kDeg;
  nc::Loads loads;
  loads.tcp.force = Vec3(0, 0, 800);
  const nc::Deflection d = nc::predictDeflection(model, data, c, th_m, loads);
  ASSERT_TRUE(d.converged);
  KDL::Chain kc = test::kdlChain(it->urdf, it->chain.base_link, it->chain.tip_link);
  KDL::ChainJntToJacSolver jac(kc);
  KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
  KDL::ChainFkSolverPos_recursive fk(kc);
  KDL::JntArray q(6);
  KDL::JntArray zero(6);
  KDL::JntArray t(6);
  for (unsigned i = 0; i < 6; ++i) q(i) = th_m[i];
  KDL::Frame F;
  fk.JntToCart(q, F);
  const Vec3 f = test::fromKdl(F).linear().transpose() * loads.tcp.force;
  KDL::Wrenches fext(kc.getNrOfSegments(), KDL::Wrench::Zero());
  fext.back() = KDL::Wrench(KDL::Vector(f.x(), f.y(), f.z()), KDL::Vector::Zero());
  rne.CartToJnt(q, zero, zero, fext, t);
  KDL::Jacobian J(6);
  jac.JntToJac(q, J);
  Vec6 tau;
  for (unsigned i = 0; i < 6; ++i) tau[i] = t(i);
  const Counterbalance& cb = it->chain.counterbalance;  // the card's A2 balancer
  if (cb.present()) tau[cb.joint] -= balancerTorque(cb, th_m[cb.joint]);
  const Vec6 phi = -tau.cwiseQuotient(c.k);
  const Vec6 dx = J.data * phi;
  EXPECT_LE((d.dp - dx.head<3>()).norm() / d.dp.norm(), 0.005);
}

TEST(Deflection, CompensationThenPredictionIsIdentity) {
  const auto robots = bundled();
  if (robots.empty()) GTEST_SKIP();
  for (const RobotUnderTest& s : robots) {
    SCOPED_TRACE(s.label);
    nc::ToolAttachment tool;
    tool.T_flange_tcp.translation() = Vec3(0, 0, 0.25);
    tool.mass = 30;
    tool.com = Vec3(0, 0, 0.1);
    const nc::Model model = nc::buildModel(s.chain, tool);
    nc::Data data(model);
    nc::JointCompliance c = compliance(s.card);
    c.k_servo = Vec6::Constant(5e6);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 0; n < 20; ++n) {
      Vec6 th_d;
      for (int i = 0; i < 6; ++i) th_d[i] = 0.6 * u(rng);
      th_d[1] -= 0.5;
      nc::Loads loads;
      loads.tcp.force = Vec3(100, -50, 1200);
      const Vec6 th_m = nc::compensateCommand(model, data, c, th_d, loads);
      const nc::Deflection d = nc::predictDeflection(model, data, c, th_m, loads);
      ASSERT_TRUE(d.converged);
      EXPECT_LE((d.theta - th_d).lpNorm<Eigen::Infinity>(), 1e-12);
    }
  }
}

TEST(Deflection, NonConvergenceIsAValueAndNoAllocation) {
  const auto robots = bundled();
  if (robots.empty()) GTEST_SKIP();
  const nc::Model model = nc::buildModel(robots.front().chain);
  nc::Data data(model);
  nc::JointCompliance c = compliance(robots.front().card);
  Vec6 th;
  th << 0.1, -1.2, 1.4, 0.2, 0.7, 0.1;
  nc::Loads loads;
  loads.tcp.force = Vec3(0, 0, 800);
  nc::Deflection d;
  const long allocations =
      test::allocationsOf([&] { d = nc::predictDeflection(model, data, c, th, loads); });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(d.converged);
  nc::DeflectionOptions opt;
  opt.max_iterations = 1;
  opt.tol = 1e-30;
  const nc::Deflection d2 = nc::predictDeflection(model, data, c, th, loads, opt);
  EXPECT_FALSE(d2.converged);
  EXPECT_EQ(d2.iterations, 1);
  EXPECT_GT(d2.residual, 0.0);
}

}  // namespace
}  // namespace roprec
