#pragma once
/// \file nlopt_problem.hpp
/// The one place that owns NLopt handles: the C handle lives in
/// a unique_ptr with nlopt_destroy as deleter; every setter is checked; objective and constraint
/// trampolines are C callbacks that catch everything, store the exception, force-stop the run and
/// return HUGE_VAL; the stored exception is rethrown after nlopt_optimize returns. The result
/// (code, value, evaluations) is a value; roundoff-limited runs are usable results, not errors.
/// Evaluations allocate nothing: x and the gradient live in per-callback buffers. A problem may be
/// run again with new bounds, initial step and start (compensation.cpp's Refiner): nlopt_optimize
/// resets its stop flag and evaluation count, so a rerun is the same as a fresh problem.

#include <nlopt.h>

#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace roprec {

class NloptProblem {
 public:
  /// f(x, grad) -> value; grad is empty for derivative-free algorithms.
  using Function = std::function<double(const std::vector<double>& x, std::vector<double>& grad)>;

  NloptProblem(nlopt_algorithm algorithm, unsigned dimension);

  void setObjective(Function f);
  /// Inequality constraint c(x) ≤ 0.
  void addInequality(Function c, double tol = 1e-9);
  void setBounds(const std::vector<double>& lower, const std::vector<double>& upper);
  /// The same from `dimension` values each (no allocation: NLopt copies them into its arrays).
  void setBounds(const double* lower, const double* upper);
  void setXtolAbs(double tol);
  void setFtolAbs(double tol);
  void setMaxEvaluations(int n);
  void setInitialStep(double dx);

  struct Result {
    nlopt_result code{NLOPT_FAILURE};
    double value{0.0};
    int evaluations{0};
    [[nodiscard]] bool usable() const { return code > 0 || code == NLOPT_ROUNDOFF_LIMITED; }
  };
  /// Optimises in place from x. Rethrows an exception raised inside a callback.
  Result optimize(std::vector<double>& x);

 private:
  /// x and the gradient are handed to `f` in buffers owned here, sized once (no allocation per
  /// evaluation).
  struct Callback {
    NloptProblem* self{nullptr};
    Function f;
    std::vector<double> x;
    std::vector<double> grad;
  };
  static double trampoline(unsigned n, const double* x, double* grad, void* data);
  void check(nlopt_result r, const char* what) const;

  std::unique_ptr<std::remove_pointer_t<nlopt_opt>, decltype(&nlopt_destroy)> opt_;
  unsigned n_;
  std::unique_ptr<Callback> objective_;
  std::vector<std::unique_ptr<Callback>> constraints_;
  std::exception_ptr error_;
  int evaluations_{0};
};

}  // namespace roprec
