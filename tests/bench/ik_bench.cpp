// Inverse kinematics per target: roprec's analytic OPW-form IK (all branches; all turns), roprec's
// seeded Newton (per-hole use), vs Orocos KDL ChainIkSolverPos_NR_JL and ChainIkSolverPos_LMA on
// the same URDF chain (KR 120 R2500 pro), for targets near a seed (joints perturbed by ≤ 0.01 rad,
// i.e. a few mm / tenths of a degree). Counters: fraction converged (roprec: ≤ 1e-9 m / rad;
// KDL: its own return code at its default tolerances, which are far looser).
#include <benchmark/benchmark.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include <algorithm>
#include <memory>
#include <random>

#include "compensator/robot/ik.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace roprec;

struct IkFixture {
  ChainDescription chain;
  IkModel model;
  KDL::Chain kchain;
  std::vector<Vec6> seeds;
  std::vector<Pose> targets;
  IkFixture() {
    const auto names = bundledRobotNames();
    if (std::find(names.begin(), names.end(), "kuka-kr120-r2500-pro") != names.end()) {
      const Robot r = loadRobot({"kuka-kr120-r2500-pro", "", ""});
      chain = r.chain;
      model = buildIkModel(r);
    } else {
      chain = loadUrdfChain(test::corpusDir() + "/urdf/kr120r2500pro.urdf", {"", "flange"});
      model = buildIkModel(chain);
    }
    kchain = test::kdlChain(chain.file, chain.base_link, chain.tip_link);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_real_distribution<double> small(-0.01, 0.01);
    while (seeds.size() < 256) {
      Vec6 q;
      q << u(rng), -1.2 + 0.5 * u(rng), 1.3 + 0.5 * u(rng), u(rng), 0.9 + 0.5 * u(rng), u(rng);
      Vec6 qt = q;
      for (int k = 0; k < 6; ++k) qt[k] += small(rng);
      seeds.push_back(q);
      targets.push_back(chainForwardKinematics(chain, qt));
    }
  }
};

IkFixture& fixture() {
  static IkFixture f;
  return f;
}

void BM_Roprec_IkAnalytic_8Branches(benchmark::State& st) {
  IkFixture& f = fixture();
  auto result = std::make_unique<IkResult>();
  size_t i = 0;
  int ok = 0;
  int n = 0;
  for (auto _ : st) {
    solveIk(f.model, f.targets[i++ & 255], IkOptions{}, *result);
    benchmark::DoNotOptimize(result->count);
    ok += result->count == 8 ? 1 : 0;
    ++n;
  }
  st.counters["eight_branches"] = static_cast<double>(ok) / n;
}
BENCHMARK(BM_Roprec_IkAnalytic_8Branches);

void BM_Roprec_IkAnalytic_AllTurns(benchmark::State& st) {
  IkFixture& f = fixture();
  auto result = std::make_unique<IkResult>();
  IkOptions o;
  o.turns = IkTurns::kAll;
  size_t i = 0;
  double solutions = 0;
  int n = 0;
  for (auto _ : st) {
    solveIk(f.model, f.targets[i++ & 255], o, *result);
    benchmark::DoNotOptimize(result->count);
    solutions += result->count;
    ++n;
  }
  st.counters["solutions"] = solutions / n;
}
BENCHMARK(BM_Roprec_IkAnalytic_AllTurns);

void BM_Roprec_IkSeededNewton(benchmark::State& st) {
  IkFixture& f = fixture();
  size_t i = 0;
  int ok = 0;
  int n = 0;
  double iterations = 0;
  for (auto _ : st) {
    const size_t k = i++ & 255;
    const IkNearResult r = solveIkNear(f.model, f.targets[k], f.seeds[k]);
    benchmark::DoNotOptimize(r.q);
    ok += (r.converged && !r.analytic_fallback) ? 1 : 0;
    iterations += r.iterations;
    ++n;
  }
  st.counters["converged_newton"] = static_cast<double>(ok) / n;
  st.counters["iterations"] = iterations / n;
}
BENCHMARK(BM_Roprec_IkSeededNewton);

KDL::JntArray toJnt(const Vec6& q) {
  KDL::JntArray a(6);
  for (int k = 0; k < 6; ++k) a(static_cast<unsigned>(k)) = q[k];
  return a;
}

/// Times a KDL position IK solver on the fixture's 256 seeded targets; counts convergence.
template <class Solver>
void runKdlIk(benchmark::State& st, IkFixture& f, Solver& ik) {
  std::vector<KDL::JntArray> seeds;
  std::vector<KDL::Frame> targets;
  for (size_t k = 0; k < 256; ++k) {
    seeds.push_back(toJnt(f.seeds[k]));
    targets.push_back(test::toKdl(f.targets[k]));
  }
  KDL::JntArray out(6);
  size_t i = 0;
  int ok = 0;
  int n = 0;
  for (auto _ : st) {
    const size_t k = i++ & 255;
    const int rc = ik.CartToJnt(seeds[k], targets[k], out);
    benchmark::DoNotOptimize(out.data);
    ok += rc >= 0 ? 1 : 0;
    ++n;
  }
  st.counters["converged"] = static_cast<double>(ok) / n;
}

void BM_KDL_ChainIkSolverPos_NR_JL(benchmark::State& st) {
  IkFixture& f = fixture();
  KDL::ChainFkSolverPos_recursive fk(f.kchain);
  KDL::ChainIkSolverVel_pinv vel(f.kchain);
  KDL::JntArray qmin(6);
  KDL::JntArray qmax(6);
  for (unsigned k = 0; k < 6; ++k) {
    qmin(k) = f.chain.joints[k].lower;
    qmax(k) = f.chain.joints[k].upper;
  }
  KDL::ChainIkSolverPos_NR_JL ik(f.kchain, qmin, qmax, fk, vel);
  runKdlIk(st, f, ik);
}
BENCHMARK(BM_KDL_ChainIkSolverPos_NR_JL);

void BM_KDL_ChainIkSolverPos_LMA(benchmark::State& st) {
  IkFixture& f = fixture();
  KDL::ChainIkSolverPos_LMA ik(f.kchain);
  runKdlIk(st, f, ik);
}
BENCHMARK(BM_KDL_ChainIkSolverPos_LMA);

}  // namespace
