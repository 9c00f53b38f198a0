#include "compensator/robot/transient.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sundials/sundials_context.hpp>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "compensator/process/process_load.hpp"
#include "compensator/support/error.hpp"

namespace roprec::nc {

// ---------------------------------------------------------------------------------------------
// Drive model

JointCompliance DriveModel::staticCompliance() const {
  JointCompliance c;
  c.k = k;
  if (servo == ServoMode::kCascade && !integral) c.k_servo = kv.cwiseProduct(kw);
  return c;
}

DriveModel driveModelFromCard(const RobotCard& card, const Model& model, Data& data,
                              const Vec6& theta_ref, const DriveEstimateOptions& o) {
  if (!solvePosition(model, data, theta_ref, Guess::kClosedForm).converged) {
    throw std::invalid_argument(
        "driveModelFromCard: the position problem did not converge at the reference pose");
  }
  const Mat6 Mbar = jointSpaceInertia(model, data);
  DriveModel d;
  d.integral = o.integral;
  bool all_gains = true;
  bool no_gains = true;
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = card.joints[static_cast<size_t>(i)];
    if (!(j.stiffness > 0)) {
      throw InputError(
          card.file, j.line,
          "joint '" + j.name + "' has no stiffness: give it in the robot card or with --stiffness");
    }
    d.k[i] = j.stiffness;
    const double J = Mbar(i, i);
    d.motor_inertia[i] = j.motor_inertia > 0 ? j.motor_inertia : o.motor_inertia_ratio * J;
    const double B = d.motor_inertia[i];
    const double Jeff = J + B > 0 ? J * B / (J + B) : 0.0;
    d.damping[i] = 2.0 * o.damping_ratio * std::sqrt(d.k[i] * Jeff);
    if (j.position_gain) {
      no_gains = false;
      d.kv[i] = *j.position_gain;
      d.kw[i] =
          j.velocity_gain ? *j.velocity_gain : o.velocity_bandwidth_factor * d.kv[i] * (B + J);
      d.wi[i] = o.integral_corner_factor * d.kv[i];
    } else {
      all_gains = false;
    }
  }
  if (!all_gains && !no_gains) {
    const JointCard& j0 = card.joints[0];
    throw InputError(card.file, j0.line,
                     "position_gain must be given for all six joints or for none (ideal servo)");
  }
  d.servo = no_gains ? ServoMode::kIdeal : ServoMode::kCascade;
  return d;
}

// ---------------------------------------------------------------------------------------------
// Process laws

const char* phaseName(CyclePhase p) {
  switch (p) {
    case CyclePhase::kApproach:
      return "approach";
    case CyclePhase::kEntry:
      return "entry";
    case CyclePhase::kFull:
      return "full";
    case CyclePhase::kBreakthrough:
      return "breakthrough";
    case CyclePhase::kDwell:
      return "dwell";
    case CyclePhase::kRetract:
      return "retract";
  }
  return "?";
}

namespace {
/// ½(1 − cos πs), s clamped to [0, 1].
double smoothRamp(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return 0.5 * (1.0 - std::cos(kPi * s));
}

std::vector<double> cleanBreakpoints(std::vector<double> b, double end) {
  std::sort(b.begin(), b.end());
  std::vector<double> out;
  for (const double t : b) {
    if (!(t > 0.0) || !(t < end) || !std::isfinite(t)) continue;
    if (!out.empty() && t - out.back() < 1e-12) continue;
    out.push_back(t);
  }
  return out;
}
}  // namespace

void NoProcess::sample(double /*t*/, ProcessSample& out) { out = ProcessSample{}; }

StepWrenchCycle::StepWrenchCycle(const ToolWrench& w, const CycleTiming& timing)
    : w_(w), tm_(timing) {
  if (!(tm_.ramp >= 0) || !(tm_.hold >= 0) || !(tm_.approach >= 0) || !(tm_.retract >= 0)) {
    throw std::invalid_argument("StepWrenchCycle: negative duration in the cycle timing");
  }
}

double StepWrenchCycle::duration() const {
  return tm_.approach + 2 * tm_.ramp + tm_.hold + tm_.retract;
}

std::vector<double> StepWrenchCycle::breakpoints() const {
  const double t0 = tm_.approach;
  return cleanBreakpoints(
      {t0, t0 + tm_.ramp, t0 + tm_.ramp + tm_.hold, t0 + 2 * tm_.ramp + tm_.hold}, duration());
}

void StepWrenchCycle::sample(double t, ProcessSample& out) {
  const double t0 = tm_.approach;
  const double t1 = t0 + tm_.ramp;
  const double t2 = t1 + tm_.hold;
  const double t3 = t2 + tm_.ramp;
  double s = 0.0;
  if (t < t0) {
    out.phase = CyclePhase::kApproach;
  } else if (t < t1) {
    out.phase = CyclePhase::kEntry;
    s = tm_.ramp > 0 ? smoothRamp((t - t0) / tm_.ramp) : 1.0;
  } else if (t < t2) {
    out.phase = CyclePhase::kFull;
    s = 1.0;
  } else if (t < t3) {
    out.phase = CyclePhase::kDwell;
    s = tm_.ramp > 0 ? 1.0 - smoothRamp((t - t2) / tm_.ramp) : 0.0;
  } else {
    out.phase = CyclePhase::kRetract;
  }
  out.depth = 0.0;
  out.wrench.force = s * w_.force;
  out.wrench.torque = s * w_.torque;
  out.Fa = -out.wrench.force.z();
  out.Ft = out.wrench.force.head<2>().norm();
  out.M = -out.wrench.torque.z();
  out.Fr = 0.0;
}

DrillingCycle::DrillingCycle(const DrillingSpec& spec, const CycleTiming& timing,
                             bool rotating_runout)
    : model_(drillingModelOf(spec)),
      data_(model_),
      tm_(timing),
      runout_(rotating_runout),
      feed_(spec.feed),
      omega_s_(2.0 * kPi * spec.spindle_rpm / 60.0),
      v_f_(spec.feed * spec.spindle_rpm / 60.0) {
  if (!(v_f_ > 0) || !(omega_s_ > 0))
    throw std::invalid_argument("DrillingCycle: feed and spindle speed must be positive");
  if (!(tm_.dwell >= 0) || !(tm_.approach >= 0) || !(tm_.retract >= 0)) {
    throw std::invalid_argument("DrillingCycle: negative duration in the cycle timing");
  }
  const DrillGeometry& g = model_.geometry;
  const double a = g.chiselHalfLength();
  const double R = g.radius();
  const double tp = std::tan(g.halfPoint());
  const double hole = spec.hole_depth > 0 ? spec.hole_depth : 2.0 * g.diameter;
  thickness_ = spec.through ? hole : 0.0;
  depth_full_ = (R - a) / tp;
  depth_end_ = spec.through ? hole + depth_full_ : hole;
  const double tc = tm_.approach;
  t_full_ = tc + std::min(depth_full_, depth_end_) / v_f_;
  t_break_ = spec.through ? tc + thickness_ / v_f_ : tc + depth_end_ / v_f_;
  t_feed_end_ = tc + depth_end_ / v_f_;
  // after the feed stops the next lip reaches the stop surface within 1/lips of a revolution
  const double t_decay = spec.through ? 0.0 : 2.0 * kPi / omega_s_ / std::max(1, g.lips);
  t_decay_end_ = t_feed_end_ + std::min(t_decay, tm_.dwell);
  t_dwell_end_ = t_feed_end_ + tm_.dwell;
  t_end_ = t_dwell_end_ + tm_.retract;
}

double DrillingCycle::duration() const { return t_end_; }

std::vector<double> DrillingCycle::breakpoints() const {
  return cleanBreakpoints(
      {tm_.approach, t_full_, t_break_, t_feed_end_, t_decay_end_, t_dwell_end_}, t_end_);
}

double DrillingCycle::maxStepHint() const { return runout_ ? (2.0 * kPi / omega_s_) / 16.0 : 0.0; }

void DrillingCycle::sample(double t, ProcessSample& out) {
  const double tc = tm_.approach;
  out = ProcessSample{};
  double scale = 1.0;
  if (t < tc) {
    out.phase = CyclePhase::kApproach;
    return;
  }
  if (t < t_feed_end_) {
    out.depth = v_f_ * (t - tc);
    out.phase = out.depth < depth_full_ ? CyclePhase::kEntry : CyclePhase::kFull;
    if (thickness_ > 0 && out.depth > thickness_) out.phase = CyclePhase::kBreakthrough;
  } else if (t < t_dwell_end_) {
    out.depth = depth_end_;
    out.phase = CyclePhase::kDwell;
    scale = t < t_decay_end_ ? 1.0 - (t - t_feed_end_) / (t_decay_end_ - t_feed_end_) : 0.0;
  } else {
    out.phase = CyclePhase::kRetract;
    out.depth =
        tm_.retract > 0 ? depth_end_ * std::max(0.0, 1.0 - (t - t_dwell_end_) / tm_.retract) : 0.0;
    return;
  }
  if (scale <= 0.0) return;
  const DrillingForces F = drillingForcesAtDepth(model_, data_, feed_, out.depth, thickness_);
  out.Fa = F.thrust;
  out.Ft = F.tangential;
  out.M = F.torque;
  out.Fr = F.residual;
  out.wrench = toolWrench(F, omega_s_ * t);
  if (!runout_) out.wrench.force.head<2>().setZero();
  out.wrench.force *= scale;
  out.wrench.torque *= scale;
  out.Fa *= scale;
  out.Ft *= scale;
  out.M *= scale;
  out.Fr *= scale;
}

std::unique_ptr<ProcessCycle> makeProcessCycle(const ProcessSpec& spec, const CycleTiming& timing,
                                               bool rotating_runout) {
  if (spec.type == ProcessType::kDrilling) {
    return std::make_unique<DrillingCycle>(spec.drilling, timing, rotating_runout);
  }
  return std::make_unique<StepWrenchCycle>(steadyProcessLoad(spec).wrench, timing);
}

// ---------------------------------------------------------------------------------------------
// CVODE wrapper

namespace {

struct NVectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinSolDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
using NVectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, NVectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinSolPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinSolDeleter>;
using CvodePtr = std::unique_ptr<void, CvodeDeleter>;

void check(int flag, const char* what) {
  if (flag < 0)
    throw std::runtime_error(std::string("CVODE: ") + what + " failed (flag " +
                             std::to_string(flag) + ")");
}
template <class T>
T* checkPtr(T* p, const char* what) {
  if (p == nullptr) throw std::runtime_error(std::string("CVODE: ") + what + " returned null");
  return p;
}

}  // namespace

struct TransientSimulator::Impl {
  // problem
  const Model& model;
  TransientProblem problem;
  ProcessCycle& process;
  TransientOptions options;
  int n{24};
  bool with_integral{false};
  Vec6 theta_c{Vec6::Zero()};
  Pose T_nominal{Pose::Identity()};
  // right-hand-side workspace (sized once)
  Data data;
  Data out_data;
  VecQ Q{VecQ::Zero()};
  VecQ tmp{VecQ::Zero()};
  ProcessSample ps;
  double ps_time{std::numeric_limits<double>::quiet_NaN()};  ///< t of ps (cache)
  PositionResult last_position;
  std::exception_ptr eptr;
  std::string cvode_message;
  std::string rhs_failure;  ///< why the right-hand side refused (no allocation unless it fails)
  // CVODE handles: the context is declared first so that it is destroyed last
  sundials::Context ctx;
  NVectorPtr y;
  NVectorPtr abstol;
  MatrixPtr A;
  LinSolPtr LS;
  CvodePtr mem;

  Impl(const TransientProblem& p, ProcessCycle& proc, const TransientOptions& o)
      : model(*p.model),
        problem(p),
        process(proc),
        options(o),
        data(*p.model),
        out_data(*p.model) {}

  [[nodiscard]] bool locked(int i) const { return problem.drive.locked[static_cast<size_t>(i)]; }

  int rhs(double t, const double* yp, double* ydp);
  void setup();
  void accumulate(TransientStats& s) const;
  void record(double t, const double* yp, TransientResult& r);
};

namespace {
extern "C" {
/// CVODE right-hand side: the C firewall. Everything thrown is stored and rethrown by run().
static int roprecTransientRhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* impl = static_cast<TransientSimulator::Impl*>(user_data);
  try {
    return impl->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  } catch (...) {
    impl->eptr = std::current_exception();
    return -1;
  }
}

/// CVODE error messages go into the result instead of stderr.
static void roprecTransientErr(int error_code, const char* module, const char* function, char* msg,
                               void* user_data) {
  auto* impl = static_cast<TransientSimulator::Impl*>(user_data);
  try {
    impl->cvode_message = std::string(module ? module : "CVODE") +
                          "::" + (function ? function : "?") + " (" + std::to_string(error_code) +
                          "): " + (msg ? msg : "");
  } catch (...) {
    if (!impl->eptr) impl->eptr = std::current_exception();
  }
}
}  // extern "C"
}  // namespace

int TransientSimulator::Impl::rhs(double t, const double* yp, double* ydp) {
  const DriveModel& dm = problem.drive;
  const Eigen::Map<const Vec6> th(yp);
  const Eigen::Map<const Vec6> thd(yp + 6);
  const Eigen::Map<const Vec6> thm(yp + 12);
  const Eigen::Map<const Vec6> thmd(yp + 18);
  Eigen::Map<Vec6> d_th(ydp);
  Eigen::Map<Vec6> d_thd(ydp + 6);
  Eigen::Map<Vec6> d_thm(ydp + 12);
  Eigen::Map<Vec6> d_thmd(ydp + 18);

  // 1. position problem (warm start; the closed-form guess as a fallback)
  // (‖Φ‖∞ of a NaN vector need not be NaN: check the angles and the solution explicitly)
  if (!th.allFinite()) {
    last_position = PositionResult{false, 0, std::numeric_limits<double>::quiet_NaN()};
  } else {
    last_position = solvePosition(model, data, th, options.guess);
    if ((!last_position.converged || !data.q.allFinite()) && options.guess == Guess::kWarmStart) {
      last_position = solvePosition(model, data, th, Guess::kClosedForm);
    }
    if (!data.q.allFinite()) last_position.converged = false;
  }
  if (!last_position.converged) {
    rhs_failure = "position problem did not converge (residual " +
                  std::to_string(last_position.residual) + " after " +
                  std::to_string(last_position.iterations) + " iterations)";
    return 1;
  }

  // 2. loads: gravity + process wrench at the current (or nominal) TCP orientation
  if (t != ps_time) {  // Newton iterations and the difference-quotient Jacobian reuse one t
    process.sample(t, ps);
    ps_time = t;
  }
  if (!ps.wrench.force.allFinite() || !ps.wrench.torque.allFinite()) {
    rhs_failure = "non-finite process load at t = " + std::to_string(t) + " s";
    return -1;  // a smaller step cannot help
  }
  Loads loads;
  loads.gravity = problem.gravity;
  if (problem.follower_wrench) {
    loads.tcp_tool.force = ps.wrench.force;  // turned by R_W_tcp(q) in generalizedForces
    loads.tcp_tool.moment = ps.wrench.torque;
  } else {
    loads.tcp = toBaseFrame(ps.wrench, T_nominal.linear());
  }

  // 3. RᵀMR (builds data.R), q̇ = R θ̇, c and Sc, Rᵀ(Q − M Sc)
  Mat6 Mbar = jointSpaceInertia(model, data);
  data.qd.noalias() = data.R * thd;
  accelerationTerm(model, data, thd);
  generalizedForces(model, data, loads, Q);
  tmp = -data.Sc;
  addMassTimes(model, tmp, Q);
  Vec6 f = data.R.transpose() * Q;
  const Vec6 spring = dm.k.cwiseProduct(thm - th) + dm.damping.cwiseProduct(thmd - thd);
  f += spring;
  for (int i = 0; i < 6; ++i) {
    if (!locked(i)) continue;
    Mbar.row(i).setZero();
    Mbar.col(i).setZero();
    Mbar(i, i) = 1.0;
    f[i] = 0.0;
  }
  const Eigen::LLT<Mat6> llt(Mbar);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error(
        "transient: the joint-space inertia RᵀMR is not positive definite at t = " +
        std::to_string(t) + " s");
  }
  d_th = thd;
  d_thd = llt.solve(f);

  // 4. motor side and servo
  Vec6 tau_m = Vec6::Zero();
  Vec6 verr = Vec6::Zero();
  if (dm.servo == ServoMode::kCascade) {
    verr = dm.kv.cwiseProduct(theta_c - thm) - thmd;
    tau_m = dm.kw.cwiseProduct(verr);
    if (with_integral) {
      const Eigen::Map<const Vec6> xi(yp + 24);
      tau_m += dm.kw.cwiseProduct(dm.wi.cwiseProduct(xi));
    }
  }
  if (dm.servo == ServoMode::kIdeal) {
    d_thm.setZero();
    d_thmd.setZero();
  } else {
    d_thm = thmd;
    d_thmd = (tau_m - spring).cwiseQuotient(dm.motor_inertia);
  }
  for (int i = 0; i < 6; ++i) {
    if (!locked(i)) continue;
    d_th[i] = d_thd[i] = d_thm[i] = d_thmd[i] = 0.0;
    verr[i] = 0.0;
  }
  if (with_integral) Eigen::Map<Vec6>(ydp + 24) = verr;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(ydp[i])) {
      rhs_failure = "non-finite derivative at t = " + std::to_string(t) + " s";
      return 1;
    }
  }
  return 0;
}

void TransientSimulator::Impl::setup() {
  const DriveModel& dm = problem.drive;
  with_integral = dm.servo == ServoMode::kCascade && dm.integral;
  n = with_integral ? 30 : 24;
  theta_c = problem.theta_cmd + problem.command_offset;
  for (int i = 0; i < 6; ++i) {
    const std::string j = "joint " + std::to_string(i + 1);
    if (!(dm.k[i] > 0) || !std::isfinite(dm.k[i]))
      throw std::invalid_argument("transient: " + j + ": stiffness must be positive");
    if (!(dm.damping[i] >= 0))
      throw std::invalid_argument("transient: " + j + ": damping must be >= 0");
    if (locked(i)) continue;
    if (dm.servo != ServoMode::kIdeal && !(dm.motor_inertia[i] > 0)) {
      throw std::invalid_argument("transient: " + j + ": motor inertia must be positive");
    }
    if (dm.servo == ServoMode::kCascade &&
        (!(dm.kv[i] >= 0) || !(dm.kw[i] >= 0) || !(dm.wi[i] >= 0))) {
      throw std::invalid_argument("transient: " + j + ": servo gains must be >= 0");
    }
  }
  if (!(options.rtol > 0) || !(options.atol_angle > 0) || !(options.atol_rate > 0) ||
      !(options.sample > 0) || !(options.max_step >= 0) || !(options.min_step >= 0)) {
    throw std::invalid_argument("transient: tolerances and the sampling interval must be positive");
  }
  if (!solvePosition(model, out_data, problem.theta_cmd, Guess::kClosedForm).converged) {
    throw std::invalid_argument("transient: the position problem does not converge at the command");
  }
  framePoses(model, out_data);
  T_nominal = out_data.T_W_tcp;
  if (!solvePosition(model, data, theta_c, Guess::kClosedForm).converged) {
    throw std::invalid_argument("transient: the position problem does not converge at the command");
  }
  const Mat6 Mbar = jointSpaceInertia(model, data);
  for (int i = 0; i < 6; ++i) {
    if (!locked(i) && !(Mbar(i, i) > 1e-12 * std::max(1.0, Mbar.diagonal().maxCoeff()))) {
      throw std::invalid_argument("transient: joint " + std::to_string(i + 1) +
                                  " carries no link inertia; lock it (DriveModel::locked)");
    }
  }

  y.reset(checkPtr(N_VNew_Serial(n, ctx), "N_VNew_Serial"));
  abstol.reset(checkPtr(N_VNew_Serial(n, ctx), "N_VNew_Serial"));
  Eigen::Map<Eigen::VectorXd> at(N_VGetArrayPointer(abstol.get()), n);
  at.segment<6>(0).setConstant(options.atol_angle);
  at.segment<6>(6).setConstant(options.atol_rate);
  at.segment<6>(12).setConstant(options.atol_angle);
  at.segment<6>(18).setConstant(options.atol_rate);
  if (with_integral) at.segment<6>(24).setConstant(options.atol_angle);
  Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(y.get()), n).setZero();
  A.reset(checkPtr(SUNDenseMatrix(n, n, ctx), "SUNDenseMatrix"));
  LS.reset(checkPtr(SUNLinSol_Dense(y.get(), A.get(), ctx), "SUNLinSol_Dense"));
  mem.reset(checkPtr(CVodeCreate(options.method == Method::kAdams ? CV_ADAMS : CV_BDF, ctx),
                     "CVodeCreate"));
  check(CVodeSetErrHandlerFn(mem.get(), roprecTransientErr, this), "CVodeSetErrHandlerFn");
  check(CVodeInit(mem.get(), roprecTransientRhs, 0.0, y.get()), "CVodeInit");
  check(CVodeSVtolerances(mem.get(), options.rtol, abstol.get()), "CVodeSVtolerances");
  check(CVodeSetLinearSolver(mem.get(), LS.get(), A.get()), "CVodeSetLinearSolver");
  check(CVodeSetUserData(mem.get(), this), "CVodeSetUserData");
  check(CVodeSetMaxNumSteps(mem.get(), options.max_steps), "CVodeSetMaxNumSteps");
  double hmax = options.max_step;
  const double hint = process.maxStepHint();
  if (hint > 0) hmax = hmax > 0 ? std::min(hmax, hint) : hint;
  if (hmax > 0) check(CVodeSetMaxStep(mem.get(), hmax), "CVodeSetMaxStep");
  check(CVodeSetMinStep(mem.get(), options.min_step), "CVodeSetMinStep");
}

void TransientSimulator::Impl::accumulate(TransientStats& s) const {
  long v = 0;
  void* m = mem.get();
  if (CVodeGetNumSteps(m, &v) == CV_SUCCESS) s.steps += v;
  if (CVodeGetNumRhsEvals(m, &v) == CV_SUCCESS) s.rhs_evals += v;
  if (CVodeGetNumLinRhsEvals(m, &v) == CV_SUCCESS) s.rhs_evals_jac += v;
  if (CVodeGetNumJacEvals(m, &v) == CV_SUCCESS) s.jac_evals += v;
  if (CVodeGetNumNonlinSolvIters(m, &v) == CV_SUCCESS) s.nonlinear_iterations += v;
  if (CVodeGetNumErrTestFails(m, &v) == CV_SUCCESS) s.error_test_failures += v;
  if (CVodeGetNumNonlinSolvConvFails(m, &v) == CV_SUCCESS) s.convergence_failures += v;
}

void TransientSimulator::Impl::record(double t, const double* yp, TransientResult& r) {
  TransientSample s;
  s.t = t;
  process.sample(t, s.process);
  s.theta = Eigen::Map<const Vec6>(yp);
  s.theta_m = Eigen::Map<const Vec6>(yp + 12);
  if (solvePosition(model, out_data, s.theta, Guess::kClosedForm).converged) {
    framePoses(model, out_data);
    s.dp = out_data.T_W_tcp.translation() - T_nominal.translation();
    s.drot = smallRotationDifference(out_data.T_W_tcp.linear(), T_nominal.linear());
  } else {
    s.dp.setConstant(std::numeric_limits<double>::quiet_NaN());
    s.drot.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  r.samples.push_back(s);
}

TransientSimulator::TransientSimulator(const TransientProblem& problem, ProcessCycle& process,
                                       const TransientOptions& options) {
  if (problem.model == nullptr) throw std::invalid_argument("transient: problem.model is null");
  impl_ = std::make_unique<Impl>(problem, process, options);
  impl_->setup();
}

TransientSimulator::~TransientSimulator() = default;

int TransientSimulator::stateSize() const { return impl_->n; }

int TransientSimulator::rhs(double t, const double* y, double* ydot) {
  return impl_->rhs(t, y, ydot);
}

Eigen::VectorXd TransientSimulator::commandState() const {
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(impl_->n);
  y0.segment<6>(0) = impl_->theta_c;
  y0.segment<6>(12) = impl_->theta_c;
  return y0;
}

Eigen::VectorXd TransientSimulator::equilibriumState(double t0) {
  Impl& m = *impl_;
  const DriveModel& dm = m.problem.drive;
  m.process.sample(t0, m.ps);
  m.ps_time = t0;
  Loads loads;
  loads.gravity = m.problem.gravity;
  if (m.problem.follower_wrench) {
    loads.tcp_tool.force = m.ps.wrench.force;
    loads.tcp_tool.moment = m.ps.wrench.torque;
  } else {
    loads.tcp = toBaseFrame(m.ps.wrench, m.T_nominal.linear());
  }
  JointCompliance c = dm.staticCompliance();
  if (dm.servo != ServoMode::kCascade) c.k_servo.setConstant(1e300);
  for (int i = 0; i < 6; ++i) {
    if (m.locked(i)) c.k[i] = c.k_servo[i] = 1e300;
  }
  const Deflection d = predictDeflection(m.model, m.out_data, c, m.problem.theta_cmd, loads, {},
                                         m.problem.command_offset);
  if (!d.converged) {
    throw std::runtime_error("transient: the static equilibrium at t0 did not converge (residual " +
                             std::to_string(d.residual) + " rad)");
  }
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(m.n);
  y0.segment<6>(0) = d.theta;
  y0.segment<6>(12) = m.theta_c + d.dpsi;
  for (int i = 0; i < 6; ++i) {
    if (m.locked(i)) y0[i] = y0[12 + i] = m.theta_c[i];
  }
  if (m.with_integral) {
    for (int i = 0; i < 6; ++i) {
      const double g = dm.kw[i] * dm.wi[i];
      y0[24 + i] = m.locked(i) || !(g > 0) ? 0.0 : d.tau[i] / g;
    }
  }
  return y0;
}

TransientResult TransientSimulator::run(double t0, const Eigen::VectorXd& y0, double t_end) {
  Impl& m = *impl_;
  if (y0.size() != m.n) {
    throw std::invalid_argument("transient: initial state: expected " + std::to_string(m.n) +
                                " entries, got " + std::to_string(y0.size()));
  }
  if (!(t_end > t0)) throw std::invalid_argument("transient: t_end must be after t0");
  TransientResult r;
  r.T_nominal = m.T_nominal;
  m.eptr = nullptr;
  m.cvode_message.clear();
  m.rhs_failure.clear();
  m.ps_time = std::numeric_limits<double>::quiet_NaN();
  Eigen::Map<Eigen::VectorXd> y(N_VGetArrayPointer(m.y.get()), m.n);
  y = y0;
  check(CVodeReInit(m.mem.get(), t0, m.y.get()), "CVodeReInit");

  std::vector<double> bp;
  for (const double b : m.process.breakpoints()) {
    if (b > t0 + 1e-12 && b < t_end - 1e-12) bp.push_back(b);
  }
  bp.push_back(t_end);
  const double dt = m.options.sample;
  const long n_out = std::max(1L, static_cast<long>(std::ceil((t_end - t0) / dt - 1e-9)));
  r.samples.reserve(static_cast<size_t>(n_out) + 1);
  m.record(t0, y.data(), r);

  size_t ib = 0;
  check(CVodeSetStopTime(m.mem.get(), bp[ib]), "CVodeSetStopTime");
  double tret = t0;
  r.ok = true;
  for (long k = 1; k <= n_out && r.ok; ++k) {
    const double tout = std::min(t0 + static_cast<double>(k) * dt, t_end);
    for (;;) {
      const int flag = CVode(m.mem.get(), tout, m.y.get(), &tret, CV_NORMAL);
      if (m.eptr) {
        const std::exception_ptr e = m.eptr;
        m.eptr = nullptr;
        std::rethrow_exception(e);
      }
      if (flag < 0) {
        r.ok = false;
        r.cvode_flag = flag;
        r.message = m.cvode_message.empty()
                        ? std::string("CVODE failed (flag ") + std::to_string(flag) + ")"
                        : m.cvode_message;
        if (!m.rhs_failure.empty()) r.message += "; right-hand side: " + m.rhs_failure;
        break;
      }
      const double tstop = bp[ib];
      if (ib + 1 < bp.size() && tret >= tstop - 1e-12 * std::max(1.0, std::abs(tstop))) {
        // a kink of the load: restart the multistep method there
        m.accumulate(r.stats);
        check(CVodeReInit(m.mem.get(), tret, m.y.get()), "CVodeReInit");
        ++r.stats.restarts;
        ++ib;
        check(CVodeSetStopTime(m.mem.get(), bp[ib]), "CVodeSetStopTime");
        if (tret >= tout - 1e-12 * std::max(1.0, std::abs(tout))) break;
        continue;
      }
      break;
    }
    if (r.ok) m.record(tout, y.data(), r);
  }
  m.accumulate(r.stats);
  r.t_reached = tret;
  r.y_final = y;
  return r;
}

TransientResult simulateCycle(const TransientProblem& problem, ProcessCycle& process,
                              const TransientOptions& options, double duration) {
  TransientSimulator sim(problem, process, options);
  const Eigen::VectorXd y0 = sim.equilibriumState(0.0);
  const double t_end = duration > 0 ? duration : process.duration();
  return sim.run(0.0, y0, t_end);
}

}  // namespace roprec::nc
