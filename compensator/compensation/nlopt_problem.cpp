#include "compensator/compensation/nlopt_problem.hpp"

#include <cmath>
#include <stdexcept>

namespace roprec {

NloptProblem::NloptProblem(nlopt_algorithm algorithm, unsigned dimension)
    : opt_(nlopt_create(algorithm, dimension), &nlopt_destroy), n_(dimension) {
  if (!opt_)
    throw std::runtime_error("nlopt_create failed for " +
                             std::string(nlopt_algorithm_name(algorithm)));
}

/// `what` is a literal: checking a setter allocates nothing (the Refiner sets bounds per hole).
void NloptProblem::check(nlopt_result r, const char* what) const {
  if (r < 0)
    throw std::runtime_error(std::string("NLopt: could not ") + what + ": " +
                             nlopt_result_to_string(r));
}

double NloptProblem::trampoline(unsigned n, const double* x, double* grad, void* data) {
  auto* cb = static_cast<Callback*>(data);
  try {
    ++cb->self->evaluations_;
    cb->x.assign(x, x + n);  // capacity reserved at registration: no allocation
    cb->grad.resize(grad ? n : 0);
    const double v = cb->f(cb->x, cb->grad);
    if (grad) {
      for (unsigned i = 0; i < n; ++i) grad[i] = cb->grad[i];
    }
    return v;
  } catch (...) {
    // Keep the real exception; stop the run; NLopt sees a useless value.
    cb->self->error_ = std::current_exception();
    nlopt_force_stop(cb->self->opt_.get());
    return HUGE_VAL;
  }
}

void NloptProblem::setObjective(Function f) {
  objective_ = std::make_unique<Callback>(Callback{this, std::move(f), {}, {}});
  objective_->x.reserve(n_);
  objective_->grad.reserve(n_);
  check(nlopt_set_min_objective(opt_.get(), &NloptProblem::trampoline, objective_.get()),
        "set the objective");
}

void NloptProblem::addInequality(Function c, double tol) {
  constraints_.push_back(std::make_unique<Callback>(Callback{this, std::move(c), {}, {}}));
  constraints_.back()->x.reserve(n_);
  constraints_.back()->grad.reserve(n_);
  check(nlopt_add_inequality_constraint(opt_.get(), &NloptProblem::trampoline,
                                        constraints_.back().get(), tol),
        "add an inequality constraint");
}

void NloptProblem::setBounds(const std::vector<double>& lower, const std::vector<double>& upper) {
  if (lower.size() != n_ || upper.size() != n_)
    throw std::invalid_argument("NloptProblem::setBounds: wrong dimension");
  setBounds(lower.data(), upper.data());
}

void NloptProblem::setBounds(const double* lower, const double* upper) {
  check(nlopt_set_lower_bounds(opt_.get(), lower), "set the lower bounds");
  check(nlopt_set_upper_bounds(opt_.get(), upper), "set the upper bounds");
}

void NloptProblem::setXtolAbs(double tol) {
  check(nlopt_set_xtol_abs1(opt_.get(), tol), "set xtol_abs");
}
void NloptProblem::setFtolAbs(double tol) {
  check(nlopt_set_ftol_abs(opt_.get(), tol), "set ftol_abs");
}
void NloptProblem::setMaxEvaluations(int n) {
  check(nlopt_set_maxeval(opt_.get(), n), "set maxeval");
}
void NloptProblem::setInitialStep(double dx) {
  check(nlopt_set_initial_step1(opt_.get(), dx), "set the initial step");
}

NloptProblem::Result NloptProblem::optimize(std::vector<double>& x) {
  if (x.size() != n_) throw std::invalid_argument("NloptProblem::optimize: wrong dimension");
  error_ = nullptr;
  evaluations_ = 0;
  Result r;
  r.code = nlopt_optimize(opt_.get(), x.data(), &r.value);
  r.evaluations = evaluations_;
  if (error_) std::rethrow_exception(error_);
  return r;
}

}  // namespace roprec
