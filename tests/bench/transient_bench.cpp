// Transient of a drilling cycle (compensator/robot/transient.hpp) on the KUKA KR 120 R2500 pro with
// the sample cell's spindle and Al 6061 drilling process: simulated-time / real-time ratio of the
// whole cycle (goal ≥ 200×: BM_DrillingCycle2s_Default, the default options chosen by the
// convergence study of docs/transient.md) and the cost of one right-hand-side evaluation. The
// method/rtol variants keep the absolute tolerances used before the study. Counters:
// `sim_per_real` (simulated s per wall s), `steps`, `rhs` (evaluations incl. the
// difference-quotient Jacobian).
#include <benchmark/benchmark.h>

#include <chrono>

#include "compensator/precision/cell.hpp"
#include "compensator/process/process_spec.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/transient.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace roprec;

struct Fixture {
  CellSpec cell;
  Robot robot;
  nc::Model model;
  nc::TransientProblem problem;
  ProcessSpec spec;
  Fixture()
      : cell(loadCell(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml")),
        robot(loadRobot(cell.robot)),
        spec(parseProcess(cell.process)) {
    nc::ToolAttachment tool;
    tool.T_flange_tcp = cell.tool.T_flange_tcp;
    tool.mass = cell.tool.mass;
    tool.com = cell.tool.com;
    tool.inertia = cell.tool.inertia;
    model = nc::buildModel(robot.chain, tool);
    nc::Vec6 q;
    q << 0, -60, 100, 0, 50, 0;
    q *= kDeg;
    nc::Data data(model);
    problem.model = &model;
    problem.drive = nc::driveModelFromCard(robot.card, model, data, q);
    problem.theta_cmd = q;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

/// The absolute tolerances before the convergence study (1e-9 rad, 1e-7 rad/s, 0.1 nm): the
/// method/rtol benchmarks below keep them, so that they compare with earlier runs.
nc::TransientOptions legacyOptions(nc::Method method, double rtol) {
  nc::TransientOptions opt;
  opt.method = method;
  opt.rtol = rtol;
  opt.atol_angle = 1e-9;
  opt.atol_rate = 1e-7;
  opt.atol_depth = 1e-10;
  return opt;
}

/// One 2 s cycle per iteration, the process cycle (and its force table) built inside the timing.
void cycleWith(benchmark::State& st, nc::TransientOptions opt, bool runout, double sample,
               nc::ForceEvaluation forces = nc::ForceEvaluation::kTabulated) {
  Fixture& f = fixture();
  opt.sample = sample;
  nc::TransientResult last;
  double sim = 0.0;
  double wall = 0.0;
  for (auto _ : st) {
    const auto t0 = std::chrono::steady_clock::now();
    nc::DrillingCycle c(f.spec.drilling, {}, runout, forces);
    last = nc::simulateCycle(f.problem, c, opt, 2.0);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    sim += 2.0;
    benchmark::DoNotOptimize(last.samples.data());
  }
  st.counters["sim_per_real"] = sim / wall;
  st.counters["steps"] = static_cast<double>(last.stats.steps);
  st.counters["rhs"] = static_cast<double>(last.stats.rhs_evals + last.stats.rhs_evals_jac);
  if (!last.ok) st.SkipWithError(last.message.c_str());
}

void cycle(benchmark::State& st, nc::Method method, double rtol, bool runout,
           double sample = 1e-3) {
  Fixture& f = fixture();
  nc::TransientOptions opt = legacyOptions(method, rtol);
  opt.sample = sample;
  nc::TransientResult last;
  double sim = 0.0;
  double wall = 0.0;
  for (auto _ : st) {
    auto c = nc::makeProcessCycle(f.spec, {}, runout);
    const auto t0 = std::chrono::steady_clock::now();
    last = nc::simulateCycle(f.problem, *c, opt, 2.0);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    sim += 2.0;
    benchmark::DoNotOptimize(last.samples.data());
  }
  st.counters["sim_per_real"] = sim / wall;
  st.counters["steps"] = static_cast<double>(last.stats.steps);
  st.counters["rhs"] = static_cast<double>(last.stats.rhs_evals + last.stats.rhs_evals_jac);
  if (!last.ok) st.SkipWithError(last.message.c_str());
}

void BM_DrillingCycle2s_Adams(benchmark::State& st) { cycle(st, nc::Method::kAdams, 1e-8, false); }
BENCHMARK(BM_DrillingCycle2s_Adams)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Adams_rtol1e6(benchmark::State& st) {
  cycle(st, nc::Method::kAdams, 1e-6, false);
}
BENCHMARK(BM_DrillingCycle2s_Adams_rtol1e6)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Bdf(benchmark::State& st) { cycle(st, nc::Method::kBdf, 1e-8, false); }
BENCHMARK(BM_DrillingCycle2s_Bdf)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Bdf_rtol1e6(benchmark::State& st) {
  cycle(st, nc::Method::kBdf, 1e-6, false);
}
BENCHMARK(BM_DrillingCycle2s_Bdf_rtol1e6)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Adams_Sample10ms(benchmark::State& st) {
  cycle(st, nc::Method::kAdams, 1e-8, false, 1e-2);
}
BENCHMARK(BM_DrillingCycle2s_Adams_Sample10ms)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Bdf_Sample10ms(benchmark::State& st) {
  cycle(st, nc::Method::kBdf, 1e-8, false, 1e-2);
}
BENCHMARK(BM_DrillingCycle2s_Bdf_Sample10ms)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Adams_Runout(benchmark::State& st) {
  cycle(st, nc::Method::kAdams, 1e-8, true);
}
BENCHMARK(BM_DrillingCycle2s_Adams_Runout)->Unit(benchmark::kMillisecond);

// The default options (BDF, tolerances of the convergence study in docs/transient.md) and the
// tabulated force law: the figure of README's performance table (goal ≥ 200× real time).
void BM_DrillingCycle2s_Default(benchmark::State& st) { cycleWith(st, {}, false, 1e-3); }
BENCHMARK(BM_DrillingCycle2s_Default)->Unit(benchmark::kMillisecond);
// The same with the exact force law (drillingForcesAtDepth at every new tip state).
void BM_DrillingCycle2s_Default_ExactForces(benchmark::State& st) {
  cycleWith(st, {}, false, 1e-3, nc::ForceEvaluation::kExact);
}
BENCHMARK(BM_DrillingCycle2s_Default_ExactForces)->Unit(benchmark::kMillisecond);
void BM_DrillingCycle2s_Default_Runout(benchmark::State& st) { cycleWith(st, {}, true, 1e-3); }
BENCHMARK(BM_DrillingCycle2s_Default_Runout)->Unit(benchmark::kMillisecond);
// Building the process cycle alone (drilling model + force table), included in the cycles above.
void BM_DrillingCycleConstruction(benchmark::State& st) {
  Fixture& f = fixture();
  for (auto _ : st) {
    nc::DrillingCycle c(f.spec.drilling, {}, false);
    benchmark::DoNotOptimize(&c);
  }
}
BENCHMARK(BM_DrillingCycleConstruction)->Unit(benchmark::kMicrosecond);

void rhsCost(benchmark::State& st, nc::Guess guess) {
  Fixture& f = fixture();
  auto c = nc::makeProcessCycle(f.spec, {}, false);
  nc::TransientOptions opt;
  opt.guess = guess;
  nc::TransientSimulator sim(f.problem, *c, opt);
  Eigen::VectorXd y = sim.equilibriumState(0.0);
  Eigen::VectorXd yd(y.size());
  double t = 0.8;  // full engagement
  for (auto _ : st) {
    y[1] += 1e-9;  // a nearby state every call, as CVODE does
    benchmark::DoNotOptimize(sim.rhs(t, y.data(), yd.data()));
  }
}
void BM_Rhs_WarmStart(benchmark::State& st) { rhsCost(st, nc::Guess::kWarmStart); }
BENCHMARK(BM_Rhs_WarmStart);
void BM_Rhs_ClosedForm(benchmark::State& st) { rhsCost(st, nc::Guess::kClosedForm); }
BENCHMARK(BM_Rhs_ClosedForm);

}  // namespace
