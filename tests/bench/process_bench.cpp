/// Process-model timings: drilling forces per hole (edge integration over both lips included),
/// one depth sample of the entry ramp (node table rebuilt with quaternion edge frames), the
/// milling force profile over one revolution, and one coupled milling path point.
#include <benchmark/benchmark.h>

#include "compensator/process/drilling_forces.hpp"
#include "compensator/process/milling.hpp"

namespace roprec {
namespace {

DrillingModel benchDrill() {
  DrillGeometry g;
  g.diameter = 10e-3;
  g.web_thickness = 1.6e-3;
  g.runout = 10e-6;
  return makeDrillingModel(g, findMaterial("Al 6061-T6")->drilling, AngleLaw::kGeometric, 0.2e-3);
}

void BM_DrillingForcesPerHole(benchmark::State& state) {
  const DrillingModel m = benchDrill();
  double f = 0.2e-3;
  for (auto _ : state) {
    const DrillingForces F = drillingForces(m, f);
    benchmark::DoNotOptimize(F);
    f = f == 0.2e-3 ? 0.2001e-3 : 0.2e-3;  // defeat hoisting
  }
}
BENCHMARK(BM_DrillingForcesPerHole);

void BM_DrillingForcesAtEntryDepth(benchmark::State& state) {
  const DrillingModel m = benchDrill();
  DrillingData d(m);
  for (auto _ : state) {
    const DrillingForces F = drillingForcesAtDepth(m, d, 0.2e-3, 1.0e-3, 0.0);
    benchmark::DoNotOptimize(F);
  }
}
BENCHMARK(BM_DrillingForcesAtEntryDepth);

void BM_DrillingModelBuild(benchmark::State& state) {
  DrillGeometry g;
  for (auto _ : state) {
    const DrillingModel m =
        makeDrillingModel(g, findMaterial("Al 6061-T6")->drilling, AngleLaw::kGeometric, 0.2e-3);
    benchmark::DoNotOptimize(m.full.r.data());
  }
}
BENCHMARK(BM_DrillingModelBuild);

MillingModel benchMill() {
  MillingTool t;
  MillingCut c;
  c.ae = 2e-3;
  c.fz = 0.1e-3;
  return makeMillingModel(t, c, findMaterial("Al 7075-T6")->milling, 720, 20);
}

void BM_MillingProfileOneRevolution(benchmark::State& state) {
  const MillingModel m = benchMill();
  for (auto _ : state) {
    const MillingProfile P = millingForceProfile(m);
    benchmark::DoNotOptimize(P.mean);
  }
}
BENCHMARK(BM_MillingProfileOneRevolution);

void BM_MillingCoupledPathPoint(benchmark::State& state) {
  const MillingModel m = benchMill();
  const ComplianceFunction C = linearCompliance(Mat3::Identity() * 1e-6);
  CouplingState st;
  for (auto _ : state) {
    const CouplingResult r = coupleMillingPoint(m, C, st, CouplingOptions{});
    benchmark::DoNotOptimize(r.delta);
  }
}
BENCHMARK(BM_MillingCoupledPathPoint);

}  // namespace
}  // namespace roprec
