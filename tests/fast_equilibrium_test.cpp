// The static-equilibrium kernel (fast_equilibrium.hpp) against the natural-coordinate model of
// record (model.hpp, inverse_dynamics.hpp) on every bundled robot, each also with a seeded
// geometric calibration (calibratedChain), and every corpus URDF:
//  * TCP pose, static torques τ and TCP Jacobian agree to 1e-9 relative (loads: link weights —
//    random seeded inertials on URDFs without them —, tool mass, the balancer of the card, a
//    base-fixed and a tool-fixed TCP wrench);
//  * the analytic ∂τ/∂θ agrees with central differences of the model-of-record torques
//    (h = 1e-6 rad: truncation + round-off ≤ 1e-6 relative);
//  * predictDeflection (Newton on the fast kernel) reaches the equilibrium of the model of record:
//    a fixed-point iteration θ = θ_cmd − K⁻¹ τ_NC(θ) written here with solvePosition +
//    staticTorques, θ to 1e-11 rad and δp to 1e-9 relative;
//  * the balancer's analytic slope agrees with central differences of counterbalance.hpp's
//    balancerTorque (spring and gas, push and pull, isothermal and adiabatic), its torque with
//    balancerTorque to 1e-14 relative;
//  * DeflectionOptions::natural_state = false gives the same deflection bit for bit;
//  * soft joints (K⁻¹ ∂τ/∂θ of order 1: the Newton matrix's pivots leave the unpivoted range):
//    a converged equilibrium satisfies the model of record's G(θ) = 0 to 1e-10 rad.
#include "compensator/robot/fast_equilibrium.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "compensator/robot/deflection.hpp"
#include "compensator/robot/geometry_calibration.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nc::Vec6;

struct Case {
  std::string label;
  ChainDescription chain;
};

/// Every bundled robot once more, calibrated (geometry_calibration.hpp): every joint origin, the
/// base and the tool moved by seeded errors of a real uncalibrated arm (±0.5 mm, ±0.8 mrad per
/// component). Appended last, so the other cases keep their seeded draws.
void addCalibratedCases(std::vector<Case>& out) {
  std::mt19937 cal_rng(31);
  std::uniform_real_distribution<double> mm(-0.5e-3, 0.5e-3);
  std::uniform_real_distribution<double> mrad(-0.8e-3, 0.8e-3);
  const auto error = [&] {
    FrameError e;
    e.dxyz = Vec3(mm(cal_rng), mm(cal_rng), mm(cal_rng));
    e.drpy = Vec3(mrad(cal_rng), mrad(cal_rng), mrad(cal_rng));
    return e;
  };
  for (const std::string& name : bundledRobotNames()) {
    GeometryCalibration cal;
    for (FrameError& j : cal.joints) j = error();
    cal.base = error();
    cal.tool = error();
    out.push_back({name + " calibrated", calibratedChain(loadRobot({name, "", ""}).chain, cal)});
  }
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& name : bundledRobotNames()) {
    out.push_back({name, loadRobot({name, "", ""}).chain});
  }
  const std::string corpus = test::corpusDir();
  EXPECT_FALSE(corpus.empty()) << "corpus absent";
  if (corpus.empty()) {
    addCalibratedCases(out);
    return out;
  }
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(corpus + "/urdf")) {
    if (e.path().extension() == ".urdf") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  EXPECT_GE(files.size(), 6u);
  for (const std::string& f : files) {
    Case c{f, loadUrdfChain(f)};
    // URDFs without inertials: seeded masses and centres of mass so the weights are exercised
    for (Inertial& in : c.chain.inertials) {
      if (in.mass > 0) continue;
      in.mass = 30.0 + 20.0 * u(rng);
      in.com = Vec3(0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng));
      in.inertia = Mat3::Identity() * 0.5;
      in.present = true;
    }
    out.push_back(c);
  }
  addCalibratedCases(out);
  return out;
}

nc::ToolAttachment tool() {
  nc::ToolAttachment t;
  t.T_flange_tcp.translation() = Vec3(0.02, -0.01, 0.28);
  t.T_flange_tcp.linear() = Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  t.mass = 28.0;
  t.com = Vec3(0.01, 0.0, 0.12);
  return t;
}

nc::Loads loads() {
  nc::Loads l;
  l.tcp.force = Vec3(120, -80, 650);
  l.tcp.moment = Vec3(4, -3, 9);
  l.tcp_tool.force = Vec3(30, 15, 900);
  l.tcp_tool.moment = Vec3(0.5, -0.2, 6);
  return l;
}

double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

TEST(FastEquilibrium, FramesTorquesJacobianMatchNaturalCoordinates) {
  const auto all = cases();
  ASSERT_FALSE(all.empty());
  const nc::Loads l = loads();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (const Case& c : all) {
    SCOPED_TRACE(c.label);
    const nc::Model model = nc::buildModel(c.chain, tool());
    nc::Data fast(model);
    nc::Data ref(model);
    for (int n = 0; n < 40; ++n) {
      Vec6 th;
      for (int i = 0; i < 6; ++i) th[i] = u(rng);
      ASSERT_TRUE(nc::solvePosition(model, ref, th).converged);
      nc::framePoses(model, ref);
      const Vec6 tau_ref = nc::staticTorques(model, ref, l);
      const nc::Mat6 J_ref = nc::tcpJacobian(model, ref);
      nc::chainFrames(model, fast, th);
      Vec6 tau;
      nc::StaticLoadSums sums;
      nc::staticTorquesFromFrames(model, fast, l, tau, sums);
      EXPECT_LE(relErr(fast.frames.p_tcp, ref.T_W_tcp.translation()), 1e-9);
      EXPECT_LE(relErr(fast.frames.R_tcp, ref.T_W_tcp.linear()), 1e-9);
      EXPECT_LE(relErr(tau, tau_ref), 1e-9) << tau.transpose() << "\n" << tau_ref.transpose();
      EXPECT_LE(relErr(nc::tcpJacobianFromFrames(model, fast), J_ref), 1e-9);
      // the synchronised natural coordinates are a solution of Φ(q) = 0
      nc::syncNaturalCoordinates(model, fast);
      nc::evaluatePhi(model, fast, fast.q);
      EXPECT_LE(fast.Phi.lpNorm<Eigen::Infinity>(), 1e-12);
      EXPECT_LE(relErr(fast.T_W_flange.matrix(), ref.T_W_flange.matrix()), 1e-9);
    }
  }
}

TEST(FastEquilibrium, AnalyticSensitivityMatchesCentralDifferences) {
  const auto all = cases();
  ASSERT_FALSE(all.empty());
  const nc::Loads l = loads();
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (const Case& c : all) {
    SCOPED_TRACE(c.label);
    const nc::Model model = nc::buildModel(c.chain, tool());
    nc::Data fast(model);
    nc::Data ref(model);
    for (int n = 0; n < 10; ++n) {
      Vec6 th;
      for (int i = 0; i < 6; ++i) th[i] = u(rng);
      nc::chainFrames(model, fast, th);
      Vec6 tau;
      nc::StaticLoadSums sums;
      nc::staticTorquesFromFrames(model, fast, l, tau, sums);
      nc::Mat6 D;
      nc::staticSensitivity(model, fast, sums, D);
      nc::Mat6 Dfd;
      const double h = 1e-6;
      for (int j = 0; j < 6; ++j) {
        Vec6 t = th;
        t[j] += h;
        nc::solvePosition(model, ref, t);
        const Vec6 tp = nc::staticTorques(model, ref, l);
        t[j] -= 2 * h;
        nc::solvePosition(model, ref, t);
        const Vec6 tm = nc::staticTorques(model, ref, l);
        Dfd.col(j) = (tp - tm) / (2 * h);
      }
      EXPECT_LE((D - Dfd).lpNorm<Eigen::Infinity>() / Dfd.lpNorm<Eigen::Infinity>(), 1e-6)
          << D << "\n\n"
          << Dfd;
    }
  }
}

TEST(FastEquilibrium, DeflectionReachesTheModelOfRecordEquilibrium) {
  const auto all = cases();
  ASSERT_FALSE(all.empty());
  const nc::Loads l = loads();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (const Case& c : all) {
    SCOPED_TRACE(c.label);
    const nc::Model model = nc::buildModel(c.chain, tool());
    nc::Data data(model);
    nc::Data ref(model);
    nc::JointCompliance comp;
    comp.k << 8e6, 9e6, 5e6, 1.2e6, 1.1e6, 0.9e6;
    comp.k_servo = Vec6::Constant(2e7);
    const Vec6 keff = comp.effective();
    for (int n = 0; n < 10; ++n) {
      Vec6 th_m;
      for (int i = 0; i < 6; ++i) th_m[i] = u(rng);
      const nc::Deflection d = nc::predictDeflection(model, data, comp, th_m, l);
      ASSERT_TRUE(d.converged);
      EXPECT_LE(d.iterations, 6);
      // reference: fixed point with the model of record (contraction ≪ 1 at these stiffnesses)
      Vec6 th = th_m;
      for (int it = 0; it < 200; ++it) {
        nc::solvePosition(model, ref, th);
        const Vec6 next = th_m - nc::staticTorques(model, ref, l).cwiseQuotient(keff);
        const double step = (next - th).lpNorm<Eigen::Infinity>();
        th = next;
        if (step < 1e-15) break;
      }
      nc::solvePosition(model, ref, th);
      nc::framePoses(model, ref);
      const Pose T_real = ref.T_W_tcp;
      nc::solvePosition(model, ref, th_m);
      nc::framePoses(model, ref);
      const Vec3 dp_ref = T_real.translation() - ref.T_W_tcp.translation();
      EXPECT_LE((d.theta - th).lpNorm<Eigen::Infinity>(), 1e-11);
      // floor: the equilibrium stops at ‖G‖∞ ≤ 1e-12 rad, which moves a TCP up to ~3 m from the
      // joints by 3e-12 m
      EXPECT_LE((d.dp - dp_ref).norm(), 1e-9 * dp_ref.norm() + 3e-12);
      // data is left the natural-coordinate state at θ: the model-of-record Jacobian there
      const nc::Mat6 J = nc::tcpJacobian(model, data);
      nc::solvePosition(model, ref, d.theta);
      EXPECT_LE(relErr(J, nc::tcpJacobian(model, ref)), 1e-9);
    }
  }
}

TEST(FastEquilibrium, BalancerSlopeMatchesCentralDifferences) {
  for (const bool gas : {false, true}) {
    for (const bool push : {false, true}) {
      for (const double n : {1.0, 1.4}) {
        Counterbalance cb;
        cb.joint = 1;
        cb.law = gas ? Counterbalance::Law::kGas : Counterbalance::Law::kSpring;
        cb.action = push ? Counterbalance::Action::kPush : Counterbalance::Action::kPull;
        cb.r = 0.25;
        cb.d = 0.45;
        cb.psi0 = 0.5 * kPi;
        cb.sign = push ? -1.0 : 1.0;
        cb.length_ref = std::sqrt(cb.r * cb.r + cb.d * cb.d);
        cb.force_ref = 9000.0;
        cb.stiffness = 4e4;
        cb.pressure_ref = 15e6;
        cb.area = 1.26e-3;
        cb.volume_ref = 0.36e-3;
        cb.polytropic = n;
        SCOPED_TRACE(std::string(gas ? "gas" : "spring") + (push ? " push" : " pull") +
                     " n=" + std::to_string(n));
        for (double q = -1.2; q <= 0.6; q += 0.15) {
          const nc::BalancerTorque b = nc::balancerTorqueAndSlope(cb, q);
          const double t = balancerTorque(cb, q);
          EXPECT_NEAR(b.torque, t, 1e-14 * std::abs(t));
          const double h = 1e-6;
          const double fd = (balancerTorque(cb, q + h) - balancerTorque(cb, q - h)) / (2 * h);
          EXPECT_NEAR(b.slope, fd, 1e-6 * std::max(1.0, std::abs(fd))) << "q " << q;
          EXPECT_NE(b.slope, 0.0);
        }
      }
    }
  }
  const nc::BalancerTorque none = nc::balancerTorqueAndSlope(Counterbalance{}, 0.3);
  EXPECT_EQ(none.torque, 0.0);
  EXPECT_EQ(none.slope, 0.0);
}

TEST(FastEquilibrium, FramesOnlyDeflectionIsTheSame) {
  const auto all = cases();
  ASSERT_FALSE(all.empty());
  const nc::Loads l = loads();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (const Case& c : all) {
    SCOPED_TRACE(c.label);
    const nc::Model model = nc::buildModel(c.chain, tool());
    nc::Data full(model);
    nc::Data frames(model);
    nc::JointCompliance comp;
    comp.k << 8e6, 9e6, 5e6, 1.2e6, 1.1e6, 0.9e6;
    nc::DeflectionOptions fo;
    fo.natural_state = false;
    for (int n = 0; n < 5; ++n) {
      Vec6 th_m;
      for (int i = 0; i < 6; ++i) th_m[i] = u(rng);
      const Vec6 offset = Vec6::Constant(1e-4 * n);
      const nc::Deflection a = nc::predictDeflection(model, full, comp, th_m, l, {}, offset);
      const nc::Deflection b = nc::predictDeflection(model, frames, comp, th_m, l, fo, offset);
      ASSERT_TRUE(a.converged);
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_TRUE(a.theta == b.theta && a.tau == b.tau && a.dp == b.dp && a.drot == b.drot);
      EXPECT_TRUE(a.T_real.matrix() == b.T_real.matrix());
      EXPECT_TRUE(full.frames.p_tcp == frames.frames.p_tcp &&
                  full.frames.R_tcp == frames.frames.R_tcp);
      // the full state's pose is the frames' pose
      EXPECT_LE(relErr(full.T_W_tcp.matrix(), a.T_real.matrix()), 1e-15);
    }
  }
}

TEST(FastEquilibrium, SoftJointsStillSolveTheModelOfRecordEquilibrium) {
  const auto all = cases();
  ASSERT_FALSE(all.empty());
  const nc::Loads l = loads();
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  int converged = 0;
  for (const Case& c : all) {
    SCOPED_TRACE(c.label);
    const nc::Model model = nc::buildModel(c.chain, tool());
    nc::Data data(model);
    nc::Data ref(model);
    for (const double scale : {1e-1, 1e-2, 3e-3}) {
      nc::JointCompliance comp;
      comp.k << 8e6, 9e6, 5e6, 1.2e6, 1.1e6, 0.9e6;
      comp.k *= scale;
      const Vec6 keff = comp.effective();
      for (int n = 0; n < 4; ++n) {
        Vec6 th_m;
        for (int i = 0; i < 6; ++i) th_m[i] = u(rng);
        const nc::Deflection d = nc::predictDeflection(model, data, comp, th_m, l);
        if (!d.converged) continue;  // a value, not a wrong answer
        ++converged;
        nc::solvePosition(model, ref, d.theta);
        const Vec6 G = d.theta - th_m + nc::staticTorques(model, ref, l).cwiseQuotient(keff);
        EXPECT_LE(G.lpNorm<Eigen::Infinity>(), 1e-10) << "scale " << scale;
      }
    }
  }
  EXPECT_GT(converged, 20);
}

}  // namespace
}  // namespace roprec
