// The host calls per target (plugin/api/session.hpp): Session::filterTarget with the cell's drill
// and with each hole's own diameter and depth, the batch filterTargets per target, and
// predictJoints — the cost a RoboDK/OLP host pays per target (goal: <= 8 us a filter_target).
//   build/bin/roprec_bench --benchmark_filter=Session
#include <benchmark/benchmark.h>

#include <vector>

#include "plugin/api/job.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace roprec;

struct SessionFixture {
  api::Session session{test::sourceDir() + "/samples/cells/housing-kr120-tools.xml"};
  std::vector<Pose> poses;
  std::vector<api::HoleProcess> processes;
  std::vector<Vec6> joints;  ///< controller convention, rad: the filtered targets' commands
  SessionFixture() {
    const api::PredictionContext c = api::loadPredictionContext(
        test::sourceDir() + "/samples/cells/housing-kr120-tools.xml",
        test::sourceDir() + "/samples/emotor-housing/holes.csv", std::nullopt, "");
    for (const HoleRequest& r : c.job.requests) {
      poses.push_back(r.T_W_tcp);
      api::HoleProcess p;
      p.tool = r.tool;
      p.diameter = r.diameter;
      p.depth = r.depth;
      processes.push_back(p);
    }
    for (const api::Session::Filtered& f : session.filterTargets(poses, {}, processes))
      if (f.ok) joints.push_back(f.joints_controller);
  }
};
SessionFixture& sfx() {
  static SessionFixture f;
  return f;
}

void BM_Session_FilterTargetCellDrill(benchmark::State& st) {
  SessionFixture& f = sfx();
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(f.session.filterTarget(f.poses[i]));
    i = (i + 1) % f.poses.size();
  }
}
BENCHMARK(BM_Session_FilterTargetCellDrill);

void BM_Session_FilterTargetOwnDrill(benchmark::State& st) {
  SessionFixture& f = sfx();
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(f.session.filterTarget(f.poses[i], nullptr, f.processes[i]));
    i = (i + 1) % f.poses.size();
  }
}
BENCHMARK(BM_Session_FilterTargetOwnDrill);

/// The batch over the 204 holes, reported per target.
void BM_Session_FilterTargetsPerTarget(benchmark::State& st) {
  SessionFixture& f = sfx();
  for (auto _ : st) benchmark::DoNotOptimize(f.session.filterTargets(f.poses, {}, f.processes));
  st.SetItemsProcessed(static_cast<int64_t>(st.iterations()) *
                       static_cast<int64_t>(f.poses.size()));
}
BENCHMARK(BM_Session_FilterTargetsPerTarget);

void BM_Session_PredictJoints(benchmark::State& st) {
  SessionFixture& f = sfx();
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(f.session.predictJoints(f.joints[i], f.processes[i]));
    i = (i + 1) % f.joints.size();
  }
}
BENCHMARK(BM_Session_PredictJoints);

}  // namespace
