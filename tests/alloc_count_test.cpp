// Heap allocations per hole, counted by a replacement of the global operator new (all forms) in
// this test binary. Counting is off by default and per thread (a thread_local switch), so the
// other tests are unaffected; unlike Eigen's EIGEN_RUNTIME_NO_MALLOC assert it works in Release
// (-DNDEBUG) and sees every allocation (std::vector, std::string, std::function, ...), not only
// Eigen's. Checked, after one warm-up call that sizes the caller-owned scratch:
//  * the static deviation kernels (fast_equilibrium, predictDeflection, compensateCommand, the
//    model-of-record staticTorques): 0 per call;
//  * predictHole into a reused HolePrediction over the 204 holes of the housing sample: 0;
//  * an NLopt evaluation (the trampoline hands x and the gradient over in owned buffers): 0;
//  * the counter itself: a deliberate std::vector allocation is counted (the test can fail).
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "compensator/compensation/nlopt_problem.hpp"
#include "compensator/robot/deflection.hpp"
#include "compensator/robot/fast_equilibrium.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/support/test_support.hpp"

namespace {
thread_local bool t_counting = false;
thread_local long t_allocations = 0;

void* countedAlloc(std::size_t n) {
  if (t_counting) ++t_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* countedAlignedAlloc(std::size_t n, std::align_val_t a) {
  if (t_counting) ++t_allocations;
  const std::size_t al = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(al, (n + al - 1) / al * al)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return countedAlloc(n); }
void* operator new[](std::size_t n) { return countedAlloc(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return countedAlloc(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return countedAlloc(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t a) { return countedAlignedAlloc(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return countedAlignedAlloc(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace roprec {
namespace {

/// Allocations made by f() on this thread.
template <class F>
long allocationsOf(const F& f) {
  t_allocations = 0;
  t_counting = true;
  f();
  t_counting = false;
  return t_allocations;
}

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
    sink = v[7];
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

}  // namespace
}  // namespace roprec
