// Static deviation per pose (position problem + inverse dynamics + compliance iteration)
// vs a KDL kernel (Jacobian + RNE gravity + J K⁻¹ Jᵀ w). Full prediction per hole
// (IK + deviation + forces + linearised budget). Compensation of a 1,000-hole program
// through the library, keep vs flip-free. Same binary, same robot (KR 120 sample cell).
#include <benchmark/benchmark.h>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <random>

#include "compensator/compensation/compensation.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/support/counting_new.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace roprec;

struct Fixture {
  api::PredictionContext c;
  std::vector<nc::Vec6> poses;
  std::vector<HoleRequest> thousand;
  Fixture()
      : c(api::loadPredictionContext(test::sourceDir() + "/samples/cells/housing-kr120.xml",
                                     test::sourceDir() + "/samples/emotor-housing/holes.csv",
                                     std::nullopt, "")) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    for (int i = 0; i < 64; ++i) {
      nc::Vec6 q;
      q << u(rng), -1.2 + u(rng), 1.9 + u(rng), u(rng), 0.9 + u(rng), u(rng);
      poses.push_back(q);
    }
    thousand = copies(1000);
  }
  /// n holes: the 204 housing holes, repeated with small shifts
  [[nodiscard]] std::vector<HoleRequest> copies(size_t n) const {
    std::vector<HoleRequest> out;
    for (int k = 0; out.size() < n; ++k) {
      for (const HoleRequest& h : c.job.requests) {
        if (out.size() == n) break;
        HoleRequest r = h;
        r.id = h.id + "_" + std::to_string(k);
        r.T_W_tcp.translation().y() += 2e-3 * k;
        out.push_back(r);
      }
    }
    return out;
  }
};
Fixture& fx() {
  static Fixture f;
  return f;
}

void BM_Roprec_StaticDeviation(benchmark::State& st) {
  Fixture& f = fx();
  nc::Data d(f.c.model.model);
  nc::Loads loads;
  loads.tcp.force = Vec3(0, 0, 800);
  // as the per-hole prediction calls it: the result and data.frames, no natural-coordinate sync
  nc::DeflectionOptions opt;
  opt.natural_state = false;
  size_t i = 0;
  for (auto _ : st) {
    const nc::Deflection r = nc::predictDeflection(f.c.model.model, d, f.c.model.compliance,
                                                   f.poses[i++ & 63], loads, opt);
    benchmark::DoNotOptimize(r.dp);
  }
}
BENCHMARK(BM_Roprec_StaticDeviation);

void BM_KDL_LinearCompliance(benchmark::State& st) {
  Fixture& f = fx();
  const ChainDescription& ch = f.c.robot.chain;
  KDL::Chain kc =
      test::kdlChain(f.c.robot.card.urdf_path, ch.base_link, ch.tip_link, f.c.tool.T_flange_tcp);
  KDL::ChainJntToJacSolver jac(kc);
  KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
  KDL::JntArray q(6);
  KDL::JntArray z(6);
  KDL::JntArray g(6);
  KDL::Jacobian J(6);
  KDL::Wrenches f0(kc.getNrOfSegments(), KDL::Wrench::Zero());
  Eigen::Matrix<double, 6, 1> w;
  w << 0, 0, 800, 0, 0, 0;
  const nc::Vec6 k = f.c.model.compliance.k;
  size_t i = 0;
  for (auto _ : st) {
    const nc::Vec6& p = f.poses[i++ & 63];
    for (unsigned j = 0; j < 6; ++j) q(j) = p[j];
    jac.JntToJac(q, J);
    rne.CartToJnt(q, z, z, f0, g);
    nc::Vec6 tau;
    for (unsigned j = 0; j < 6; ++j) tau[j] = g(j);
    const nc::Vec6 phi = (J.data.transpose() * w - tau).cwiseQuotient(k);
    const Eigen::Matrix<double, 6, 1> dx = J.data * phi;
    benchmark::DoNotOptimize(dx);
  }
}
BENCHMARK(BM_KDL_LinearCompliance);

void BM_PredictHole(benchmark::State& st) {
  Fixture& f = fx();
  PredictionData d(f.c.model);
  const auto& req = f.c.job.requests;
  size_t i = 0;
  for (auto _ : st) {
    const HolePrediction p = predictHole(f.c.model, d, req[i++ % req.size()], nullptr);
    benchmark::DoNotOptimize(p.U_work);
  }
}
BENCHMARK(BM_PredictHole);

/// Reports allocs_per_hole (the slope between the timed 1,000-hole call, which made
/// `allocations`, and one untimed 2,000-hole call of `run`) and allocs_per_call (the fixed rest).
template <class Run>
void reportAllocationSlope(benchmark::State& st, Fixture& f, long allocations, const Run& run) {
  const std::vector<HoleRequest> twice = f.copies(2000);
  const long before = test::threadAllocations();
  run(twice);
  const long allocations2 = test::threadAllocations() - before;
  const double extra = static_cast<double>(twice.size() - f.thousand.size());
  const double slope = static_cast<double>(allocations2 - allocations) / extra;
  st.counters["allocs_per_hole"] = slope;
  st.counters["allocs_per_call"] =
      static_cast<double>(allocations) - slope * static_cast<double>(f.thousand.size());
}

void BM_PredictHoles1000(benchmark::State& st) {
  // 1,000 holes through predictHoles with `threads` workers (wall time: UseRealTime). With one
  // thread it also reports the heap allocations as BM_Compensate1000 does: allocs_per_hole is the
  // slope between 1,000 and 2,000 holes (the returned predictions included), allocs_per_call the
  // fixed rest (with workers, their allocations are on other threads and not counted)
  Fixture& f = fx();
  PredictOptions o;
  o.threads = static_cast<int>(st.range(0));
  long allocations = 0;
  for (auto _ : st) {
    const long before = test::threadAllocations();
    const auto r = predictHoles(f.c.model, f.thousand, o);
    allocations = test::threadAllocations() - before;
    benchmark::DoNotOptimize(r.size());
  }
  if (o.threads == 1) {
    reportAllocationSlope(st, f, allocations, [&](const std::vector<HoleRequest>& holes) {
      benchmark::DoNotOptimize(predictHoles(f.c.model, holes, o).size());
    });
  }
  st.SetLabel(std::to_string(o.threads) + " thread(s)");
}
BENCHMARK(BM_PredictHoles1000)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Compensate1000(benchmark::State& st) {
  // also reports the heap allocations of the call (counting_new.hpp: every operator new of this
  // thread, the returned per-hole results included): allocs_per_hole is the slope between 1,000
  // and 2,000 holes (the 2,000-hole call runs once, outside the timing), allocs_per_call the
  // fixed rest (result vector, per-thread scratch, DP tables)
  Fixture& f = fx();
  CompensationOptions o;
  o.mode = st.range(0) == 0 ? OrientationMode::kKeep : OrientationMode::kFlipFree;
  long allocations = 0;
  for (auto _ : st) {
    const long before = test::threadAllocations();
    const auto r = compensateHoles(f.c.model, f.thousand, o);
    allocations = test::threadAllocations() - before;
    benchmark::DoNotOptimize(r.size());
  }
  reportAllocationSlope(st, f, allocations, [&](const std::vector<HoleRequest>& holes) {
    benchmark::DoNotOptimize(compensateHoles(f.c.model, holes, o).size());
  });
  st.SetLabel(st.range(0) == 0 ? "keep" : "flip-free");
}
BENCHMARK(BM_Compensate1000)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_PredictCli1000(benchmark::State& st) {
  // 1,000-hole hole list through the CLI: parse, predict, write the JSON
  const std::string dir = test::tempDir("bench");
  std::string csv = "id,x,y,z,i,j,k,diameter,depth,tolerance\n";
  const std::string src = test::readFile(test::sourceDir() + "/samples/emotor-housing/holes.csv");
  std::vector<std::string> rows;
  size_t pos = 0;
  while (pos < src.size()) {
    const size_t e = src.find('\n', pos);
    const std::string line = src.substr(pos, e - pos);
    pos = e == std::string::npos ? src.size() : e + 1;
    if (!line.empty() && line[0] != '#' && line.rfind("id,", 0) != 0) rows.push_back(line);
  }
  for (int k = 0; k < 1000; ++k) {
    const std::string& r = rows[static_cast<size_t>(k) % rows.size()];
    csv += "K" + std::to_string(k) + r.substr(r.find(','));
    csv += "\n";
  }
  test::writeFile(dir + "/h.csv", csv);
  for (auto _ : st) {
    const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                   "/samples/cells/housing-kr120.xml' '" + dir +
                                   "/h.csv' --json '" + dir + "/o.json' --quiet");
    benchmark::DoNotOptimize(r.exit_code);
  }
}
BENCHMARK(BM_PredictCli1000)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
