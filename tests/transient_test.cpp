// CVODE transient of the flexible-joint robot under its servo (compensator/robot/transient.hpp)
// against independent references:
//  * the steady state equals the static deviation of predictDeflection (fixed point/Newton on the
//    static equations, no integration) to ≤ 0.01 µm, with integral action (ideal-servo statics)
//    and without it (k_servo = Kv·Kω in series with k), and with a follower wrench against the
//    static solution iterated on the TCP orientation;
//  * free motion (no gravity, no damping, free motors) conserves the total energy
//    ½θ̇ᵀRᵀMRθ̇ + ½θ̇_mᵀB_mθ̇_m + ½(θ_m−θ)ᵀK(θ_m−θ) to ≤ 1e-6 relative over 2 s;
//  * a single massive link on a flexible joint with a free motor: θ(t) against the closed form of
//    the two-inertia oscillator, ω² = k(1/J + 1/B_m) (undamped and damped);
//  * the C firewall: an exception thrown inside the right-hand side comes back as itself, a
//    non-finite load is a failed result (a value), and the right-hand side does not allocate.
#include "compensator/robot/transient.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "compensator/precision/cell.hpp"
#include "compensator/process/process_load.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nc::Vec6;

struct Kuka {
  Robot robot;
  nc::Model model;
  Vec6 q;
  Kuka() : robot(loadRobot({"kuka-kr120-r2500-pro", "", ""})) {
    nc::ToolAttachment tool;  // the sample cell's drilling spindle
    tool.T_flange_tcp.translation() = Vec3(0, 0, 0.35);
    tool.mass = 25.0;
    tool.com = Vec3(0, 0, 0.15);
    tool.inertia = Mat3::Identity() * 0.3;
    model = nc::buildModel(robot.chain, tool);
    q << 0, -60, 100, 0, 50, 0;
    q *= kDeg;
  }
};

const Kuka& kuka() {
  static const Kuka k;
  return k;
}

nc::DriveModel kukaDrive(bool integral, double damping_ratio) {
  const Kuka& k = kuka();
  nc::Data data(k.model);
  nc::DriveEstimateOptions o;
  o.integral = integral;
  o.damping_ratio = damping_ratio;
  return nc::driveModelFromCard(k.robot.card, k.model, data, k.q, o);
}

/// Steady state from the undeflected command state under gravity + a constant wrench applied
/// from t = 0 (no ramp), compared with the static model.
void checkSteadyState(bool integral) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(integral, 0.5);
  ASSERT_EQ(p.drive.servo, nc::ServoMode::kCascade);
  p.theta_cmd = k.q;
  p.follower_wrench = false;
  nc::CycleTiming tm;
  tm.approach = 0.0;
  tm.ramp = 0.0;
  tm.hold = 100.0;
  ToolWrench w;
  w.force = Vec3(60.0, -40.0, -800.0);
  w.torque = Vec3(0.0, 0.0, -12.0);
  nc::StepWrenchCycle cycle(w, tm);
  nc::TransientOptions opt;
  opt.rtol = 1e-9;
  opt.sample = 0.05;
  nc::TransientSimulator sim(p, cycle, opt);
  EXPECT_EQ(sim.stateSize(), integral ? 30 : 24);
  const nc::TransientResult r = sim.run(0.0, sim.commandState(), 4.0);
  ASSERT_TRUE(r.ok) << r.message;

  nc::Data data(k.model);
  nc::forwardKinematics(k.model, data, k.q);
  nc::Loads loads;
  loads.tcp = toBaseFrame(w, data.T_W_tcp.linear());
  const nc::Deflection d =
      nc::predictDeflection(k.model, data, p.drive.staticCompliance(), k.q, loads);
  ASSERT_TRUE(d.converged);
  const nc::TransientSample& s = r.samples.back();
  EXPECT_GT(d.dp.norm(), 100e-6);  // a real deflection (gravity + 800 N)
  EXPECT_LE((s.dp - d.dp).norm(), 0.01e-6) << "transient " << s.dp.transpose() * 1e6
                                           << " um, static " << d.dp.transpose() * 1e6 << " um";
  EXPECT_LE((s.drot - d.drot).norm(), 0.01e-6 / 2.5);
  EXPECT_LE((s.theta - d.theta).lpNorm<Eigen::Infinity>(), 1e-9);
  std::printf("steady state (%s): |dp - static| = %.3e um of %.1f um, steps %ld, rhs %ld\n",
              integral ? "integral" : "proportional", (s.dp - d.dp).norm() * 1e6, d.dp.norm() * 1e6,
              r.stats.steps, r.stats.rhs_evals + r.stats.rhs_evals_jac);
  // the transient really happened: the first sample is the rigid command
  EXPECT_LE(r.samples.front().dp.norm(), 1e-12);
}

TEST(Transient, SteadyStateEqualsStaticDeviationWithIntegralServo) { checkSteadyState(true); }

TEST(Transient, SteadyStateEqualsStaticDeviationWithProportionalServo) { checkSteadyState(false); }

TEST(Transient, FollowerWrenchSteadyStateEqualsStaticWithLoadAtRealOrientation) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(true, 0.5);
  p.theta_cmd = k.q;
  p.follower_wrench = true;
  nc::CycleTiming tm;
  tm.approach = 0.0;
  tm.ramp = 0.0;
  tm.hold = 100.0;
  ToolWrench w;
  w.force = Vec3(0.0, 0.0, -1500.0);
  w.torque = Vec3(0.0, 0.0, -20.0);
  nc::StepWrenchCycle cycle(w, tm);
  nc::TransientOptions opt;
  opt.rtol = 1e-9;
  opt.sample = 0.05;
  nc::TransientSimulator sim(p, cycle, opt);
  const nc::TransientResult r = sim.run(0.0, sim.equilibriumState(0.0), 0.5);
  ASSERT_TRUE(r.ok) << r.message;
  // static solution with the load turned by the real TCP orientation (outer fixed point)
  nc::Data data(k.model);
  nc::forwardKinematics(k.model, data, k.q);
  Mat3 R = data.T_W_tcp.linear();
  nc::Deflection d;
  for (int it = 0; it < 10; ++it) {
    nc::Loads loads;
    loads.tcp = toBaseFrame(w, R);
    d = nc::predictDeflection(k.model, data, p.drive.staticCompliance(), k.q, loads);
    ASSERT_TRUE(d.converged);
    R = d.T_real.linear();
  }
  // the library's follower load (Loads::tcp_tool, as `roprec deflect` uses it)
  nc::Loads follower;
  follower.tcp_tool.force = w.force;
  follower.tcp_tool.moment = w.torque;
  const nc::Deflection df =
      nc::predictDeflection(k.model, data, p.drive.staticCompliance(), k.q, follower);
  ASSERT_TRUE(df.converged);
  EXPECT_LE((df.dp - d.dp).norm(), 1e-12);
  nc::Loads fixed;
  fixed.tcp = toBaseFrame(w, d.T_nominal.linear());
  const nc::Deflection d0 =
      nc::predictDeflection(k.model, data, p.drive.staticCompliance(), k.q, fixed);
  EXPECT_LE((r.samples.back().dp - d.dp).norm(), 0.01e-6);
  // the follower effect is visible against the fixed-direction load
  EXPECT_GT((d0.dp - d.dp).norm(), 0.05e-6);
  // started at the follower equilibrium: nothing moves
  EXPECT_LE((r.samples.front().dp - r.samples.back().dp).norm(), 0.01e-6);
}

TEST(Transient, FreeMotionConservesEnergy) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(false, 0.0);
  p.drive.servo = nc::ServoMode::kFree;
  p.drive.damping.setZero();
  p.gravity = false;
  p.theta_cmd = k.q;
  nc::NoProcess none(2.0);
  nc::TransientOptions opt;
  opt.rtol = 1e-11;
  opt.atol_angle = 1e-13;
  opt.atol_rate = 1e-12;
  opt.sample = 0.01;
  nc::TransientSimulator sim(p, none, opt);
  Eigen::VectorXd y0 = sim.commandState();
  Vec6 rate;
  rate << 0.2, -0.1, 0.15, 0.3, -0.2, 0.25;
  Vec6 twist;
  twist << 1e-4, -2e-4, 1.5e-4, -3e-4, 2e-4, 1e-4;
  y0.segment<6>(6) = rate;
  y0.segment<6>(12) += twist;
  y0.segment<6>(18) = -0.5 * rate;
  const nc::TransientResult r = sim.run(0.0, y0, 2.0);
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(r.samples.size(), 201u);
  nc::Data data(k.model);
  auto energy = [&](const Vec6& th, const Vec6& thd, const Vec6& thm, const Vec6& thmd) {
    nc::solvePosition(k.model, data, th);
    const nc::Mat6 M = nc::jointSpaceInertia(k.model, data);
    const Vec6 e = thm - th;
    return 0.5 * thd.dot(M * thd) + 0.5 * thmd.dot(p.drive.motor_inertia.cwiseProduct(thmd)) +
           0.5 * e.dot(p.drive.k.cwiseProduct(e));
  };
  const double E0 =
      energy(y0.segment<6>(0), y0.segment<6>(6), y0.segment<6>(12), y0.segment<6>(18));
  // state at the samples: re-run to each sample time is unnecessary; use y_final and the
  // sampled angles with rates from a second run segment by segment
  double worst = 0.0;
  Eigen::VectorXd y = y0;
  for (int seg = 1; seg <= 4; ++seg) {
    const nc::TransientResult rs = sim.run(0.5 * (seg - 1), y, 0.5 * seg);
    ASSERT_TRUE(rs.ok) << rs.message;
    y = rs.y_final;
    const double E = energy(y.segment<6>(0), y.segment<6>(6), y.segment<6>(12), y.segment<6>(18));
    worst = std::max(worst, std::abs(E - E0) / E0);
  }
  EXPECT_LE(worst, 1e-6);
  // the arm really moved (large motion, nonlinear Sc terms exercised)
  EXPECT_GT((y.segment<6>(0) - y0.segment<6>(0)).norm(), 0.2);
  EXPECT_LE((r.y_final - y).norm(), 1e-6 * y.norm());
  std::printf("energy drift over 2 s: %.3e relative (steps %ld)\n", worst, r.stats.steps);
}

/// Single massive link on joint 2 (tests/data/single_link_6r.urdf: 50 kg at 1 m), other joints
/// locked, free motor, no gravity: the two-inertia oscillator. With e = θ_m − θ,
///   e'' + c e' + ω² e = 0,  ω² = k(1/J + 1/B),  c = d(1/J + 1/B),   J θ + B θ_m = const.
void checkSingleLink(double damping) {
  const ChainDescription chain =
      loadUrdfChain(test::sourceDir() + "/tests/data/single_link_6r.urdf");
  const nc::Model model = nc::buildModel(chain);
  const double J = 50.0 * 1.0 * 1.0;
  const double B = 20.0;
  const double kk = 1.0e4;
  nc::TransientProblem p;
  p.model = &model;
  p.drive.servo = nc::ServoMode::kFree;
  p.drive.k = Vec6::Constant(1e6);
  p.drive.k[1] = kk;
  p.drive.damping.setZero();
  p.drive.damping[1] = damping;
  p.drive.motor_inertia = Vec6::Ones();
  p.drive.motor_inertia[1] = B;
  p.drive.locked = {true, false, true, true, true, true};
  p.gravity = false;
  p.theta_cmd << 0.2, 0.3, -0.4, 0.1, 0.5, -0.2;
  nc::NoProcess none(1.0);
  nc::TransientOptions opt;
  opt.rtol = 1e-11;
  opt.atol_angle = 1e-14;
  opt.atol_rate = 1e-12;
  opt.sample = 1e-3;
  nc::TransientSimulator sim(p, none, opt);
  Eigen::VectorXd y0 = sim.commandState();
  const double e0 = 2e-3;
  const double rate0 = 0.05;  // common rigid rotation
  y0[13] += e0;
  y0[7] = rate0;
  y0[19] = rate0;
  const nc::TransientResult r = sim.run(0.0, y0, 1.0);
  ASSERT_TRUE(r.ok) << r.message;
  const double w2 = kk * (1 / J + 1 / B);
  const double c = damping * (1 / J + 1 / B);
  const double wd = std::sqrt(w2 - 0.25 * c * c);
  double worst = 0.0;
  for (const nc::TransientSample& s : r.samples) {
    const double t = s.t;
    // e(t) = e0 exp(−ct/2)(cos ωd t + c/(2ωd) sin ωd t), e'(0) = 0
    const double e =
        e0 * std::exp(-0.5 * c * t) * (std::cos(wd * t) + 0.5 * c / wd * std::sin(wd * t));
    const double centre = (J * p.theta_cmd[1] + B * (p.theta_cmd[1] + e0)) / (J + B) + rate0 * t;
    const double th = centre - B / (J + B) * e;
    worst = std::max(worst, std::abs(s.theta[1] - th));
    EXPECT_NEAR(s.theta_m[1] - s.theta[1], e, 1e-9);
    EXPECT_EQ(s.theta[0], p.theta_cmd[0]);  // locked
  }
  EXPECT_LE(worst, 1e-9);
}

TEST(Transient, SingleLinkFlexibleJointMatchesClosedForm) { checkSingleLink(0.0); }

TEST(Transient, SingleLinkDampedFlexibleJointMatchesClosedForm) { checkSingleLink(150.0); }

struct InjectedFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A load law that fails after t_fail: throws, or returns a non-finite wrench.
class FailingProcess final : public nc::ProcessCycle {
 public:
  FailingProcess(double t_fail, bool throw_it) : t_fail_(t_fail), throw_(throw_it) {}
  void sample(double t, nc::ProcessSample& out) override {
    out = nc::ProcessSample{};
    if (t < t_fail_) return;
    if (throw_) throw InjectedFailure("injected failure at t = " + std::to_string(t));
    out.wrench.force.z() = std::numeric_limits<double>::quiet_NaN();
  }
  [[nodiscard]] double duration() const override { return 1.0; }
  [[nodiscard]] std::vector<double> breakpoints() const override { return {}; }

 private:
  double t_fail_;
  bool throw_;
};

TEST(Transient, RhsExceptionComesBackAsTheOriginalException) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(true, 0.05);
  p.theta_cmd = k.q;
  FailingProcess fail(0.05, true);
  nc::TransientSimulator sim(p, fail, {});
  const Eigen::VectorXd y0 = sim.equilibriumState(0.0);
  try {
    (void)sim.run(0.0, y0, 0.2);
    FAIL() << "no exception";
  } catch (const InjectedFailure& e) {
    EXPECT_NE(std::string(e.what()).find("injected failure"), std::string::npos);
  }
  // the simulator is still usable afterwards
  FailingProcess later(10.0, true);
  nc::TransientSimulator sim2(p, later, {});
  const nc::TransientResult r = sim2.run(0.0, sim2.equilibriumState(0.0), 0.05);
  EXPECT_TRUE(r.ok) << r.message;
}

TEST(Transient, NonFiniteLoadIsAFailedResultNotACrash) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(true, 0.05);
  p.theta_cmd = k.q;
  FailingProcess nan(0.05, false);
  nc::TransientSimulator sim(p, nan, {});
  const nc::TransientResult r = sim.run(0.0, sim.equilibriumState(0.0), 0.2);
  EXPECT_FALSE(r.ok);
  EXPECT_LT(r.cvode_flag, 0);
  EXPECT_NE(r.message.find("non-finite process load"), std::string::npos) << r.message;
  EXPECT_GT(r.t_reached, 0.04);  // failed on the first step that reached the bad load
  EXPECT_LE(r.t_reached, 0.05);
  EXPECT_LE(r.samples.back().t, 0.05 + 1e-12);
}

TEST(Transient, PositionProblemFailureIsAValue) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(true, 0.05);
  p.theta_cmd = k.q;
  nc::NoProcess none(1.0);
  nc::TransientSimulator sim(p, none, {});
  Eigen::VectorXd y0 = sim.equilibriumState(0.0);
  y0[2] = std::numeric_limits<double>::quiet_NaN();
  const nc::TransientResult r = sim.run(0.0, y0, 0.1);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("position problem did not converge"), std::string::npos) << r.message;
  // the same simulator runs again from a good state
  const nc::TransientResult r2 = sim.run(0.0, sim.equilibriumState(0.0), 0.01);
  EXPECT_TRUE(r2.ok) << r2.message;
}

TEST(Transient, RightHandSideDoesNotAllocate) {
  const Kuka& k = kuka();
  nc::TransientProblem p;
  p.model = &k.model;
  p.drive = kukaDrive(true, 0.05);
  p.theta_cmd = k.q;
  const CellSpec cell = loadCell(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  const ProcessSpec ps = parseProcess(cell.process);
  auto cycle = nc::makeProcessCycle(ps, {}, true);
  nc::TransientSimulator sim(p, *cycle, {});
  const Eigen::VectorXd y0 = sim.equilibriumState(0.0);
  Eigen::VectorXd yd(y0.size());
  ASSERT_EQ(sim.rhs(0.3, y0.data(), yd.data()), 0);  // warm up (entry)
  Eigen::internal::set_is_malloc_allowed(false);
  const int a = sim.rhs(0.35, y0.data(), yd.data());
  const int b = sim.rhs(0.9, y0.data(), yd.data());  // full engagement
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 0);
  EXPECT_TRUE(yd.allFinite());
}

TEST(Transient, DrillingCyclePhasesAndLoads) {
  const CellSpec cell = loadCell(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  const ProcessSpec ps = parseProcess(cell.process);
  nc::CycleTiming tm;
  nc::DrillingCycle c(ps.drilling, tm, false);
  const SteadyProcessLoad steady = steadyProcessLoad(ps);
  nc::ProcessSample s;
  c.sample(0.05, s);
  EXPECT_EQ(s.phase, nc::CyclePhase::kApproach);
  EXPECT_EQ(s.wrench.force.norm(), 0.0);
  // full engagement: the steady load of `roprec deflect`
  const double v = c.feedRate();
  const double depth_full = 6e-3;  // beyond (R − a)/tan p for the 10 mm, 118° drill
  c.sample(tm.approach + depth_full / v, s);
  EXPECT_EQ(s.phase, nc::CyclePhase::kFull);
  EXPECT_NEAR(s.wrench.force.z(), steady.wrench.force.z(),
              1e-9 * std::abs(steady.wrench.force.z()));
  EXPECT_NEAR(s.wrench.torque.z(), steady.wrench.torque.z(),
              1e-9 * std::abs(steady.wrench.torque.z()));
  EXPECT_NEAR(s.depth, depth_full, 1e-12);
  // entry: partial load, growing
  nc::ProcessSample s1, s2;
  c.sample(tm.approach + 1e-3 / v, s1);
  c.sample(tm.approach + 2e-3 / v, s2);
  EXPECT_EQ(s1.phase, nc::CyclePhase::kEntry);
  EXPECT_GT(s1.Fa, 0.0);
  EXPECT_LT(s1.Fa, s2.Fa);
  EXPECT_LT(s2.Fa, s.Fa);
  // through hole: the load has vanished before the end of the feed, retract is unloaded
  c.sample(c.duration() - 1e-3, s);
  EXPECT_EQ(s.phase, nc::CyclePhase::kRetract);
  EXPECT_EQ(s.wrench.force.norm(), 0.0);
  const auto bp = c.breakpoints();
  EXPECT_TRUE(std::is_sorted(bp.begin(), bp.end()));
  EXPECT_GE(bp.size(), 4u);
}

}  // namespace
}  // namespace roprec
