// Transient of a drilling cycle (compensator/process/transient.hpp) on the KUKA KR 120 R2500 pro
// with the sample cell's spindle and Al 6061 drilling process: simulated-time / real-time ratio of
// the whole cycle (goal ≥ 200×: BM_DrillingCycle2s_Default, the default options chosen by the
// convergence study of docs/transient.md) and the cost of one right-hand-side evaluation. The
// method/rtol variants keep the absolute tolerances used before the study. Counters:
// `sim_per_real` (simulated s per wall s), `steps`, `rhs` (evaluations incl. the
// difference-quotient Jacobian).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "compensator/precision/cell.hpp"
#include "compensator/process/process_spec.hpp"
#include "compensator/process/transient.hpp"
#include "compensator/robot/robot_card.hpp"
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

// Convergence study of the integrator tolerances (docs/transient.md "Integrator tolerances"):
// each setting against a tight reference (Adams, rtol 1e-11, atol 1e-14 rad / 1e-12 rad/s /
// 1e-14 m, exact force law), 2 s cycle of the through hole (blind = 0) or of a 6 mm blind hole
// ending in the dwell (blind = 1). Counters: bottom_um = |dp − dp_ref| at the reference's last
// sample of the cut, cut_um = the largest over the cut, depth_um = final cut depth difference,
// steps. Args: method (0 BDF, 1 Adams), −log10 atol_angle (atol_rate = 100×, atol_depth =
// 0.1× in m), −log10 rtol, blind, BDF maximum order (3: the default cap, 5: CVODE's).
struct Study {
  nc::TransientResult ref;
  double cut_end{0.0};
};
const Study& studyReference(bool blind) {
  static Study s[2];
  Study& r = s[blind ? 1 : 0];
  if (r.ref.samples.empty()) {
    Fixture& f = fixture();
    DrillingSpec spec = f.spec.drilling;
    if (blind) {
      spec.through = false;
      spec.hole_depth = 6e-3;
    }
    nc::DrillingCycle c(spec, {}, false, nc::ForceEvaluation::kExact);
    nc::TransientOptions o = legacyOptions(nc::Method::kAdams, 1e-11);
    o.atol_angle = 1e-14;
    o.atol_rate = 1e-12;
    o.atol_depth = 1e-14;
    r.ref = nc::simulateCycle(f.problem, c, o, 2.0);
    r.cut_end = c.cutEnd();
  }
  return r;
}

void BM_TransientToleranceStudy(benchmark::State& st) {
  const bool blind = st.range(3) != 0;
  const Study& ref = studyReference(blind);
  Fixture& f = fixture();
  DrillingSpec spec = f.spec.drilling;
  if (blind) {
    spec.through = false;
    spec.hole_depth = 6e-3;
  }
  nc::TransientOptions o;
  o.method = st.range(0) == 0 ? nc::Method::kBdf : nc::Method::kAdams;
  o.atol_angle = std::pow(10.0, -static_cast<double>(st.range(1)));
  o.atol_rate = 100.0 * o.atol_angle;
  o.atol_depth = 0.1 * o.atol_angle;
  o.rtol = std::pow(10.0, -static_cast<double>(st.range(2)));
  o.bdf_max_order = static_cast<int>(st.range(4));
  nc::TransientResult r;
  for (auto _ : st) {
    nc::DrillingCycle c(spec, {}, false);
    r = nc::simulateCycle(f.problem, c, o, 2.0);
  }
  const size_t n = std::min(r.samples.size(), ref.ref.samples.size());
  if (!r.ok || n == 0) {
    st.SkipWithError("the run failed");
    return;
  }
  const size_t bottom = std::min(n - 1, static_cast<size_t>(ref.cut_end / 1e-3));
  double cut = 0.0;
  for (size_t i = 0; i <= bottom; ++i) {
    cut = std::max(cut, (r.samples[i].dp - ref.ref.samples[i].dp).norm());
  }
  st.counters["bottom_um"] = (r.samples[bottom].dp - ref.ref.samples[bottom].dp).norm() * 1e6;
  st.counters["cut_um"] = cut * 1e6;
  st.counters["depth_um"] =
      std::abs(r.samples[n - 1].process.depth - ref.ref.samples[n - 1].process.depth) * 1e6;
  st.counters["steps"] = static_cast<double>(r.stats.steps);
  st.counters["steps_ref"] = static_cast<double>(ref.ref.stats.steps);
}
BENCHMARK(BM_TransientToleranceStudy)
    ->ArgsProduct({{0}, {6, 7, 8}, {4, 5, 6}, {0, 1}, {3, 5}})
    ->ArgsProduct({{1}, {6, 7, 8}, {4, 5, 6}, {0, 1}, {0}})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

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
