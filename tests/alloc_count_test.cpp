// Heap allocations per hole, counted by the replacement of the global operator new in the test
// binary (tests/support/counting_new.hpp; per thread, Release too, every allocation, not only
// Eigen's). Checked, after one warm-up call that sizes the caller-owned scratch:
//  * the static deviation kernels (fast_equilibrium, predictDeflection, compensateCommand, the
//    model-of-record staticTorques): 0 per call;
//  * predictHole into a reused HolePrediction over the 204 holes of the housing sample: 0;
//  * an NLopt evaluation (the trampoline hands x and the gradient over in owned buffers): 0;
//  * the drilling transient's right-hand side (entry on the force table, full engagement,
//    breakthrough, each at a new θ and again at the same θ): 0 per call;
//  * compensateHoles, keep and flip-free, on N and 2N holes: the same count (a fixed number per
//    call: result vector, per-thread scratch, DP tables; none per hole);
//  * the counter itself: a deliberate std::vector allocation is counted (the test can fail).
#include <gtest/gtest.h>

#include <algorithm>

#include "compensator/compensation/compensation.hpp"
#include "compensator/compensation/nlopt_problem.hpp"
#include "compensator/precision/cell.hpp"
#include "compensator/process/transient.hpp"
#include "compensator/robot/deflection.hpp"
#include "compensator/robot/fast_equilibrium.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/support/counting_new.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using test::allocationsOf;

api::PredictionContext& housing() {
  static api::PredictionContext c = api::loadPredictionContext(
      test::sourceDir() + "/samples/cells/housing-kr120.xml",
      test::sourceDir() + "/samples/emotor-housing/holes.csv", std::nullopt, "");
  return c;
}

TEST(AllocCount, CounterSeesAnAllocation) {
  const long n = allocationsOf([] {
    std::vector<double> v(100);
    static volatile double sink = 0;
    sink = sink + v[7];
  });
  EXPECT_EQ(n, 1);
}

TEST(AllocCount, StaticDeviationKernelsAllocateNothing) {
  const PredictionModel& m = housing().model;
  nc::Data data(m.model);
  nc::Loads loads;
  loads.tcp.force = Vec3(0, 0, 800);
  loads.tcp_tool.force = Vec3(10, 0, 700);
  Vec6 th;
  th << 0.1, -1.2, 1.9, 0.2, 0.9, 0.1;
  nc::Deflection d;
  Vec6 tau;
  nc::StaticLoadSums sums;
  nc::Mat6 D;
  const long n = allocationsOf([&] {
    for (int k = 0; k < 20; ++k) {
      th[0] += 0.01;
      d = nc::predictDeflection(m.model, data, m.compliance, th, loads);
      tau = nc::compensateCommand(m.model, data, m.compliance, th, loads);
      nc::chainFrames(m.model, data, th);
      nc::staticTorquesFromFrames(m.model, data, loads, tau, sums);
      nc::staticSensitivity(m.model, data, sums, D);
      nc::solvePosition(m.model, data, th);
      tau = nc::staticTorques(m.model, data, loads);
      nc::tcpJacobian(m.model, data);
    }
  });
  EXPECT_TRUE(d.converged);
  EXPECT_EQ(n, 0);
}

TEST(AllocCount, PredictHoleAllocatesNothingPerHole) {
  const api::PredictionContext& c = housing();
  const auto& req = c.job.requests;
  ASSERT_GE(req.size(), 100u);
  PredictionData d(c.model);
  HolePrediction p;
  predictHole(c.model, d, req[0], nullptr, p);  // sizes p's strings and budget
  std::optional<Vec6> prev;
  int ok = 0;
  const long n = allocationsOf([&] {
    for (const HoleRequest& h : req) {
      predictHole(c.model, d, h, prev ? &*prev : nullptr, p);
      if (p.status == HoleStatus::kOk) {
        prev = p.joints;
        ++ok;
      }
    }
  });
  EXPECT_GT(ok, 100);
  EXPECT_EQ(n, 0) << n << " allocations over " << req.size() << " holes";
  // and the reused prediction is the fresh one
  const HolePrediction fresh = predictHole(c.model, d, req.back(), nullptr);
  predictHole(c.model, d, req.back(), nullptr, p);
  EXPECT_EQ(fresh.U_work_exact, p.U_work_exact);
  EXPECT_EQ(fresh.config, p.config);
  EXPECT_EQ(fresh.budget.size(), p.budget.size());
}

/// The housing's holes `copies` times, copy k shifted by 2 mm · k along y (ids "<id>_k"); every
/// other top-face hole turned by 180° about its axis, so that flip-free turns holes back (jump
/// reasons, NLopt refinement) as in compensation_test's flag test.
std::vector<HoleRequest> housingCopies(int copies) {
  std::vector<HoleRequest> out;
  for (int k = 0; k < copies; ++k) {
    const std::vector<HoleRequest>& req = housing().job.requests;
    for (size_t i = 0; i < req.size(); ++i) {
      HoleRequest r = req[i];
      r.id = r.id + "_" + std::to_string(k);
      r.T_W_tcp.translation().y() += 2e-3 * k;
      if (i % 2 && r.T_W_tcp.linear().col(2).z() < -0.99)
        r.T_W_tcp.rotate(Eigen::AngleAxisd(kPi, Vec3::UnitZ()));
      out.push_back(r);
    }
  }
  return out;
}

/// Allocations of compensateHoles (one thread: all on this one) on 1 and 2 copies of the housing.
void expectNoAllocationPerHole(OrientationMode mode) {
  CompensationOptions o;
  o.mode = mode;
  const std::vector<HoleRequest> one = housingCopies(1), two = housingCopies(2);
  const PredictionModel& m = housing().model;
  compensateHoles(m, one, o);  // warm-up: lazily built tables, if any
  std::vector<HoleCompensation> r1, r2;
  CompensationStats s1, s2;
  const long n1 = allocationsOf([&] { r1 = compensateHoles(m, one, o, &s1); });
  const long n2 = allocationsOf([&] { r2 = compensateHoles(m, two, o, &s2); });
  const auto ok = [](const std::vector<HoleCompensation>& r) {
    return std::count_if(r.begin(), r.end(), [](const HoleCompensation& c) { return c.ok; });
  };
  EXPECT_GT(ok(r1), 150);
  EXPECT_EQ(ok(r2), 2 * ok(r1));
  if (mode == OrientationMode::kFlipFree) {  // holes turned, with reasons, after a refinement
    EXPECT_GT(s1.psi_changed, 10);
    EXPECT_EQ(s2.psi_changed, 2 * s1.psi_changed);
    EXPECT_GT(s1.nlopt_evaluations, 0);
  }
  EXPECT_EQ(n2, n1) << orientationModeName(mode) << ": " << n1 << " allocations for " << one.size()
                    << " holes, " << n2 << " for " << two.size();
}

TEST(AllocCount, CompensateKeepAllocatesNothingPerHole) {
  expectNoAllocationPerHole(OrientationMode::kKeep);
}

TEST(AllocCount, CompensateFlipFreeAllocatesNothingPerHole) {
  expectNoAllocationPerHole(OrientationMode::kFlipFree);
}

TEST(AllocCount, NloptEvaluationAllocatesNothing) {
  NloptProblem prob(NLOPT_LN_COBYLA, 1);
  long in_callback = -1;
  int calls = 0;
  prob.setObjective([&](const std::vector<double>& x, std::vector<double>&) {
    ++calls;
    return (x[0] - 0.3) * (x[0] - 0.3);
  });
  prob.setBounds({-1.0}, {1.0});
  prob.setXtolAbs(1e-10);
  prob.setMaxEvaluations(200);
  std::vector<double> x{0.0};
  prob.optimize(x);  // first run: NLopt's own workspace
  x = {0.0};
  // count only inside the trampoline: NLopt's C code uses malloc, which is not counted anyway
  in_callback = allocationsOf([&] { prob.optimize(x); });
  EXPECT_NEAR(x[0], 0.3, 1e-6);
  EXPECT_GT(calls, 10);
  EXPECT_EQ(in_callback, 0);
}

TEST(AllocCount, TransientRightHandSideAllocatesNothing) {
  const CellSpec cell = loadCell(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  const Robot robot = loadRobot(cell.robot);
  nc::ToolAttachment tool;
  tool.T_flange_tcp = cell.tool.T_flange_tcp;
  tool.mass = cell.tool.mass;
  tool.com = cell.tool.com;
  const nc::Model model = nc::buildModel(robot.chain, tool);
  Vec6 q;
  q << 0, -60, 100, 0, 50, 0;
  q *= kDeg;
  nc::Data data(model);
  nc::TransientProblem p;
  p.model = &model;
  p.drive = nc::driveModelFromCard(robot.card, model, data, q);
  p.theta_cmd = q;
  nc::DrillingCycle cycle(parseProcess(cell.process).drilling, {}, true);
  nc::TransientSimulator sim(p, cycle);
  Eigen::VectorXd y = sim.equilibriumState(0.0);
  const int contact[3] = {1, 0, 0};
  cycle.onEvents(0.1, nc::TipState{}, contact);  // cutting (the run latches it at contact)
  Eigen::VectorXd yd(y.size());
  const long depth = y.size() - 1;
  ASSERT_EQ(sim.rhs(0.3, y.data(), yd.data()), 0);  // warm-up
  int failures = 0;
  const long n = allocationsOf([&] {
    for (const double D : {1e-3, 8e-3, 13e-3}) {  // entry, full engagement, breakthrough
      y[depth] = D;
      y[1] += 1e-7;  // a new θ: position problem and RᵀMR
      failures += sim.rhs(0.5, y.data(), yd.data()) != 0;
      y[7] += 1e-5;  // same θ: the cached position
      failures += sim.rhs(0.5, y.data(), yd.data()) != 0;
    }
  });
  EXPECT_EQ(failures, 0);
  EXPECT_TRUE(yd.allFinite());
  EXPECT_EQ(n, 0);
}

}  // namespace
}  // namespace roprec
