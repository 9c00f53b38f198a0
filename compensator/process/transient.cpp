#include "compensator/process/transient.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sundials/sundials_context.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "compensator/process/process_load.hpp"
#include "compensator/robot/fast_equilibrium.hpp"
#include "compensator/support/c_format.hpp"
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

namespace {
/// Copies the tip state into a sample (constant processes: no feed, tip = u).
void copyTip(const TipState& x, ProcessSample& out) {
  out.axial = x.axial;
  out.axial_rate = x.axial_rate;
  out.tip = x.axial;
  out.depth = x.depth;
}
}  // namespace

void NoProcess::sample(double /*t*/, const TipState& x, ProcessSample& out) {
  out = ProcessSample{};
  copyTip(x, out);
}

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

void StepWrenchCycle::sample(double t, const TipState& x, ProcessSample& out) {
  const double t0 = tm_.approach;
  const double t1 = t0 + tm_.ramp;
  const double t2 = t1 + tm_.hold;
  const double t3 = t2 + tm_.ramp;
  double s = 0.0;
  out = ProcessSample{};
  copyTip(x, out);
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
  out.wrench.force = s * w_.force;
  out.wrench.torque = s * w_.torque;
  out.Fa = -out.wrench.force.z();
  out.Ft = out.wrench.force.head<2>().norm();
  out.M = -out.wrench.torque.z();
  out.Fr = 0.0;
}

namespace {
/// Plate thickness of a through hole (0: blind), as DrillingCycle uses it.
double plateThickness(const DrillingSpec& spec, const DrillGeometry& g) {
  if (!spec.through) return 0.0;
  return spec.hole_depth > 0 ? spec.hole_depth : 2.0 * g.diameter;
}
}  // namespace

DrillingCycle::DrillingCycle(const DrillingSpec& spec, const CycleTiming& timing,
                             bool rotating_runout, ForceEvaluation forces)
    : model_(drillingModelOf(spec)),
      data_(model_),
      evaluation_(forces),
      tm_(timing),
      runout_(rotating_runout),
      feed_(spec.feed),
      omega_s_(2.0 * kPi * spec.spindle_rpm / 60.0),
      n_rps_(spec.spindle_rpm / 60.0),
      v_f_(spec.feed * spec.spindle_rpm / 60.0),
      table_(model_, plateThickness(spec, model_.geometry)) {
  if (!(v_f_ > 0) || !(omega_s_ > 0))
    throw std::invalid_argument("DrillingCycle: feed and spindle speed must be positive");
  if (!(tm_.dwell >= 0) || !(tm_.approach >= 0) || !(tm_.retract >= 0) || !(tm_.overtravel >= 0) ||
      !(tm_.cut_end_feed_fraction > 0)) {
    throw std::invalid_argument("DrillingCycle: negative duration or threshold in the timing");
  }
  const DrillGeometry& g = model_.geometry;
  const double a = g.chiselHalfLength();
  const double R = g.radius();
  const double tp = std::tan(g.halfPoint());
  const double hole = spec.hole_depth > 0 ? spec.hole_depth : 2.0 * g.diameter;
  thickness_ = spec.through ? hole : 0.0;
  depth_full_ = (R - a) / tp;
  depth_exit_ = spec.through ? hole + depth_full_ : std::numeric_limits<double>::infinity();
  depth_end_ = spec.through ? depth_exit_ + tm_.overtravel : hole;
  h_stop_ = tm_.cut_end_feed_fraction * feed_;
  const double tc = tm_.approach;
  t_feed_end_ = tc + depth_end_ / v_f_;
  // the end of the cut is checked from one lip pitch after the feed stops: the chip of the last
  // lip is still being removed, and the arm needs that long to take over the feed
  t_check_ = t_feed_end_ + std::min(1.0 / (n_rps_ * std::max(1, g.lips)), tm_.dwell);
  t_dwell_end_ = t_feed_end_ + tm_.dwell;
  t_end_ = t_dwell_end_ + tm_.retract;
}

double DrillingCycle::duration() const { return t_end_; }

double DrillingCycle::endTime() const {
  return ended_ ? std::min(t_end_, t_cut_end_ + tm_.retract) : t_end_;
}

std::vector<double> DrillingCycle::breakpoints() const {
  return cleanBreakpoints({t_feed_end_, t_check_, t_dwell_end_}, t_end_);
}

double DrillingCycle::maxStepHint() const { return runout_ ? (2.0 * kPi / omega_s_) / 16.0 : 0.0; }

void DrillingCycle::reset() {
  cutting_ = false;
  ended_ = false;
  lift_offset_ = 0.0;
  t_first_contact_ = -1.0;
  t_cut_end_ = -1.0;
  depth_at_end_ = 0.0;
}

double DrillingCycle::feedPosition(double t) const {
  const double tc = tm_.approach;
  if (ended_ && t >= t_cut_end_) {  // retract from where the feed was, at the end depth's pace
    const double back = tm_.retract > 0 ? depth_end_ * (t - t_cut_end_) / tm_.retract : depth_end_;
    return depth_at_end_ - back;
  }
  return v_f_ * (std::min(t, t_feed_end_) - tc);
}

double DrillingCycle::feedVelocity(double t) const {
  if (ended_ && t >= t_cut_end_) return tm_.retract > 0 ? -depth_end_ / tm_.retract : 0.0;
  return t < t_feed_end_ ? v_f_ : 0.0;
}

void DrillingCycle::eventFunctions(double t, const TipState& x, double* g) {
  const double s = feedPosition(t) + x.axial;
  const double sd = feedVelocity(t) + x.axial_rate;
  if (ended_ || t >= t_dwell_end_) {
    g[0] = g[1] = g[2] = -1.0;
    return;
  }
  g[0] = cutting_ ? -sd : s - x.depth - lift_offset_;
  g[1] = cutting_ && t >= t_check_ ? h_stop_ - std::max(sd, 0.0) / n_rps_ : -1.0;
  g[2] = std::isfinite(depth_exit_) ? x.depth - depth_exit_ : -1.0;
}

void DrillingCycle::onEvents(double t, const TipState& x, const int* fired) {
  if (ended_) return;
  const double s = feedPosition(t) + x.axial;
  if (fired[1] != 0 || fired[2] != 0) {
    ended_ = true;
    cutting_ = false;
    t_cut_end_ = t;
    depth_at_end_ = feedPosition(t);
    return;
  }
  if (fired[0] != 0) {
    cutting_ = !cutting_;
    if (cutting_ && t_first_contact_ < 0) t_first_contact_ = t;
    if (!cutting_) lift_offset_ = s - x.depth;
  }
}

void DrillingCycle::sample(double t, const TipState& x, ProcessSample& out) {
  out = ProcessSample{};
  out.axial = x.axial;
  out.axial_rate = x.axial_rate;
  out.depth = x.depth;
  out.feed_position = feedPosition(t);
  out.tip = out.feed_position + x.axial;
  if (ended_ || t >= t_dwell_end_) {
    out.phase = CyclePhase::kRetract;
    return;
  }
  const bool dwell = t >= t_feed_end_;
  if (x.depth <= 0.0 && !cutting_) {
    out.phase = dwell ? CyclePhase::kDwell : CyclePhase::kApproach;
  } else if (dwell) {
    out.phase = CyclePhase::kDwell;
  } else if (thickness_ > 0 && x.depth > thickness_) {
    out.phase = CyclePhase::kBreakthrough;
  } else {
    out.phase = x.depth < depth_full_ ? CyclePhase::kEntry : CyclePhase::kFull;
  }
  if (!cutting_) return;
  const double sd = feedVelocity(t) + x.axial_rate;
  out.depth_rate = std::max(sd, 0.0);
  out.feed_per_rev = out.depth_rate / n_rps_;
  out.cutting = out.depth_rate > 0.0;
  if (!out.cutting) return;
  const double depth = std::max(x.depth, 0.0);
  const DrillingForces F =
      evaluation_ == ForceEvaluation::kTabulated
          ? table_.forces(out.feed_per_rev, depth)
          : drillingForcesAtDepth(model_, data_, out.feed_per_rev, depth, thickness_);
  out.Fa = F.thrust;
  out.Ft = F.tangential;
  out.M = F.torque;
  out.Fr = F.residual;
  out.wrench = toolWrench(F, omega_s_ * t);
  if (!runout_) out.wrench.force.head<2>().setZero();
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

/// Dense LU of CVODE's Newton matrix I − γJ by Eigen (partial pivoting, storage fixed at 31×31,
/// no allocation): SUNDIALS' own dense GETRF/GETRS were ≈ 20 % of a cycle.
struct EigenLu {
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 31, 31>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 31, 1>;
  Eigen::PartialPivLU<Mat> lu;
  explicit EigenLu(int n) : lu(n) {}
};

extern "C" {
static SUNLinearSolver_Type eigenLuType(SUNLinearSolver /*S*/) { return SUNLINEARSOLVER_DIRECT; }
static SUNLinearSolver_ID eigenLuId(SUNLinearSolver /*S*/) { return SUNLINEARSOLVER_CUSTOM; }
static int eigenLuInit(SUNLinearSolver /*S*/) { return SUNLS_SUCCESS; }
static int eigenLuSetup(SUNLinearSolver S, SUNMatrix A) {
  auto* c = static_cast<EigenLu*>(S->content);
  const auto n = static_cast<Eigen::Index>(SUNDenseMatrix_Rows(A));
  c->lu.compute(Eigen::Map<const EigenLu::Mat>(SUNDenseMatrix_Data(A), n, n));
  const auto d = c->lu.matrixLU().diagonal();
  return (d.array() == 0.0).any() || !d.allFinite() ? SUNLS_LUFACT_FAIL : SUNLS_SUCCESS;
}
static int eigenLuSolve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                        sunrealtype /*tol*/) {
  const auto* c = static_cast<const EigenLu*>(S->content);
  const auto n = static_cast<Eigen::Index>(SUNDenseMatrix_Rows(A));
  const EigenLu::Vec r = c->lu.solve(Eigen::Map<const EigenLu::Vec>(N_VGetArrayPointer(b), n));
  Eigen::Map<EigenLu::Vec>(N_VGetArrayPointer(x), n) = r;
  return SUNLS_SUCCESS;
}
static int eigenLuFree(SUNLinearSolver S) {
  if (S == nullptr) return SUNLS_SUCCESS;
  delete static_cast<EigenLu*>(S->content);
  S->content = nullptr;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}
}  // extern "C"

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

/// The SUNLinearSolver of EigenLu for an n×n dense matrix (n ≤ 31).
SUNLinearSolver makeEigenLu(int n, SUNContext ctx) {
  SUNLinearSolver S = checkPtr(SUNLinSolNewEmpty(ctx), "SUNLinSolNewEmpty");
  S->ops->gettype = eigenLuType;
  S->ops->getid = eigenLuId;
  S->ops->initialize = eigenLuInit;
  S->ops->setup = eigenLuSetup;
  S->ops->solve = eigenLuSolve;
  S->ops->free = eigenLuFree;
  try {
    S->content = new EigenLu(n);
  } catch (...) {
    SUNLinSolFreeEmpty(S);
    throw;
  }
  return S;
}

}  // namespace

struct TransientSimulator::Impl {
  // problem
  const Model& model;
  TransientProblem problem;
  ProcessCycle& process;
  TransientOptions options;
  int n{25};
  int idx_depth{24};  ///< index of D in y
  bool with_integral{false};
  Vec6 theta_c{Vec6::Zero()};
  Pose T_nominal{Pose::Identity()};
  Pose T_reference{Pose::Identity()};  ///< of the samples' dp, drot (problem.controller_tcp)
  Vec3 z_n{Vec3::UnitZ()};             ///< nominal drill axis (tool z of FK(θ_cmd)), base frame
  Vec3 p_ref{Vec3::Zero()};            ///< TCP at the gravity-only static equilibrium, base frame
  int n_events{0};
  std::array<int, 8> fired{};  ///< CVodeGetRootInfo
  std::array<double, 8> g_now{};
  // right-hand-side workspace (sized once)
  Data data;
  Data out_data;
  Data root_data;
  VecQ Q{VecQ::Zero()};
  VecQ tmp{VecQ::Zero()};
  ProcessSample ps;
  double ps_time{std::numeric_limits<double>::quiet_NaN()};  ///< t of ps (cache)
  TipState ps_tip;                                           ///< tip state of ps (cache)
  PositionResult last_position;
  Eigen::LLT<Mat6> llt;             ///< of RᵀMR at cached_theta (locked rows: identity)
  Vec6 cached_theta{Vec6::Zero()};  ///< θ of data's position, R and llt
  bool theta_cached{false};
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
        out_data(*p.model),
        root_data(*p.model) {}

  [[nodiscard]] bool locked(int i) const { return problem.drive.locked[static_cast<size_t>(i)]; }

  int rhs(double t, const double* yp, double* ydp);
  /// Position problem, R and the Cholesky factor of RᵀMR at θ into data/llt. False (with
  /// rhs_failure) when the position problem does not converge.
  bool positionAndInertia(double t, const Eigen::Map<const Vec6>& th);
  int roots(double t, const double* yp, double* g);
  /// u, u̇ from data.q, data.qd (after the position and velocity problems), D from y.
  void tipFromData(const Data& d, double depth, TipState& x) const;
  /// u, u̇ by the frame recursion on `d` (d.frames, J_tcp), D from y. False for non-finite θ, θ̇.
  bool tipFromState(const double* yp, Data& d, TipState& x);
  void sampleProcess(double t, const TipState& x);
  /// Fires the events whose g is already > 0 at a restart (a jump of g at a breakpoint).
  bool eventsAtRestart(double t, const double* yp);
  void setup();
  /// Static equilibrium (predictDeflection, the drive's static compliance) under gravity and the
  /// process wrench `w` (follower or fixed as the problem says). Throws if it does not converge.
  Deflection staticDeflection(const ToolWrench& w);
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

/// CVODE root functions (process events): the same firewall.
static int roprecTransientRoots(sunrealtype t, N_Vector y, sunrealtype* g, void* user_data) {
  auto* impl = static_cast<TransientSimulator::Impl*>(user_data);
  try {
    return impl->roots(t, N_VGetArrayPointer(y), g);
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

void TransientSimulator::Impl::tipFromData(const Data& d, double depth, TipState& x) const {
  // p_tcp = p_5 + X_5 c_tcp with X_5 = [u_5 v_6 w_6] (model.hpp framePoses), linear in q
  const Vec3& c = model.c_tcp;
  const auto tcp = [&](const VecQ& q) -> Vec3 {
    return q.segment<3>(idxPnext(4)) + c.x() * q.segment<3>(idxUnext(4)) +
           c.y() * q.segment<3>(idxV(5)) + c.z() * q.segment<3>(idxW(5));
  };
  x.axial = z_n.dot(tcp(d.q) - p_ref);
  x.axial_rate = z_n.dot(tcp(d.qd));
  x.depth = depth;
}

bool TransientSimulator::Impl::tipFromState(const double* yp, Data& d, TipState& x) {
  // the frame recursion (fast_equilibrium.hpp): the same TCP as the natural coordinates, without
  // the position problem; ṗ_tcp = J_v θ̇
  const Eigen::Map<const Vec6> th(yp);
  const Eigen::Map<const Vec6> thd(yp + 6);
  if (!th.allFinite() || !thd.allFinite()) return false;
  chainFrames(model, d, th);
  const Mat6& J = tcpJacobianFromFrames(model, d);
  x.axial = z_n.dot(d.frames.p_tcp - p_ref);
  x.axial_rate = z_n.dot(J.topRows<3>() * thd);
  x.depth = yp[idx_depth];
  return true;
}

void TransientSimulator::Impl::sampleProcess(double t, const TipState& x) {
  // Newton iterations and the difference-quotient Jacobian reuse one (t, x)
  if (t == ps_time && x.axial == ps_tip.axial && x.axial_rate == ps_tip.axial_rate &&
      x.depth == ps_tip.depth)
    return;
  process.sample(t, x, ps);
  ps_time = t;
  ps_tip = x;
}

int TransientSimulator::Impl::roots(double t, const double* yp, double* g) {
  TipState x;
  if (!tipFromState(yp, root_data, x)) {
    for (int i = 0; i < n_events; ++i) g[i] = -1.0;  // the RHS reports the failure
    return 0;
  }
  process.eventFunctions(t, x, g);
  return 0;
}

bool TransientSimulator::Impl::eventsAtRestart(double t, const double* yp) {
  if (n_events == 0) return false;
  TipState x;
  if (!tipFromState(yp, root_data, x)) return false;
  process.eventFunctions(t, x, g_now.data());
  bool any = false;
  for (int i = 0; i < n_events; ++i) {
    fired[static_cast<size_t>(i)] = g_now[static_cast<size_t>(i)] > 0.0 ? 1 : 0;
    any = any || fired[static_cast<size_t>(i)] != 0;
  }
  if (any) {
    process.onEvents(t, x, fired.data());
    ps_time = std::numeric_limits<double>::quiet_NaN();
  }
  return any;
}

bool TransientSimulator::Impl::positionAndInertia(double t, const Eigen::Map<const Vec6>& th) {
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
                  numberText(last_position.residual) + " after " +
                  std::to_string(last_position.iterations) + " iterations)";
    return false;
  }
  Mat6 Mbar = jointSpaceInertia(model, data);  // builds data.R
  for (int i = 0; i < 6; ++i) {
    if (!locked(i)) continue;
    Mbar.row(i).setZero();
    Mbar.col(i).setZero();
    Mbar(i, i) = 1.0;
  }
  llt.compute(Mbar);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error(
        "transient: the joint-space inertia RᵀMR is not positive definite at t = " +
        cGeneral(t, 6) + " s");
  }
  return true;
}

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

  // 1. position problem, R and RᵀMR: functions of θ alone, kept while θ does not change (the
  // difference-quotient Jacobian perturbs θ̇, θ_m, θ̇_m, ξ and D with θ fixed)
  if (!(theta_cached && th == cached_theta)) {
    theta_cached = false;
    if (!positionAndInertia(t, th)) return 1;
    cached_theta = th;
    theta_cached = true;
  }

  // 2. q̇ = R θ̇, the tip state, the process at (t, tip)
  data.qd.noalias() = data.R * thd;
  TipState tip;
  tipFromData(data, yp[idx_depth], tip);
  sampleProcess(t, tip);
  if (!ps.wrench.force.allFinite() || !ps.wrench.torque.allFinite() ||
      !std::isfinite(ps.depth_rate)) {
    rhs_failure = "non-finite process load at t = " + cGeneral(t, 6) + " s";
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

  // 3. c and Sc, Rᵀ(Q − M Sc)
  accelerationTerm(model, data, thd);
  generalizedForces(model, data, loads, Q);
  tmp = -data.Sc;
  addMassTimes(model, tmp, Q);
  Vec6 f = data.R.transpose() * Q;
  const Vec6 spring = dm.k.cwiseProduct(thm - th) + dm.damping.cwiseProduct(thmd - thd);
  f += spring;
  for (int i = 0; i < 6; ++i) {
    if (locked(i)) f[i] = 0.0;
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
  ydp[idx_depth] = ps.depth_rate;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(ydp[i])) {
      rhs_failure = "non-finite derivative at t = " + cGeneral(t, 6) + " s";
      return 1;
    }
  }
  return 0;
}

void TransientSimulator::Impl::setup() {
  const DriveModel& dm = problem.drive;
  with_integral = dm.servo == ServoMode::kCascade && dm.integral;
  n = with_integral ? 31 : 25;
  idx_depth = n - 1;
  n_events = process.eventCount();
  if (n_events < 0 || n_events > static_cast<int>(fired.size()))
    throw std::invalid_argument("transient: the process has too many event functions");
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
  if (options.bdf_max_order < 0 || options.bdf_max_order > 5) {
    throw std::invalid_argument("transient: bdf_max_order must be 0 (CVODE's 5) or 1 to 5");
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
  T_reference = problem.controller_tcp.value_or(T_nominal);
  z_n = T_nominal.linear().col(2);
  p_ref = staticDeflection(ToolWrench{}).T_real.translation();
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
  at[idx_depth] = options.atol_depth;
  Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(y.get()), n).setZero();
  mem.reset(checkPtr(CVodeCreate(options.method == Method::kAdams ? CV_ADAMS : CV_BDF, ctx),
                     "CVodeCreate"));
  check(CVodeSetErrHandlerFn(mem.get(), roprecTransientErr, this), "CVodeSetErrHandlerFn");
  check(CVodeInit(mem.get(), roprecTransientRhs, 0.0, y.get()), "CVodeInit");
  check(CVodeSVtolerances(mem.get(), options.rtol, abstol.get()), "CVodeSVtolerances");
  A.reset(checkPtr(SUNDenseMatrix(n, n, ctx), "SUNDenseMatrix"));
  LS.reset(makeEigenLu(n, ctx));
  check(CVodeSetLinearSolver(mem.get(), LS.get(), A.get()), "CVodeSetLinearSolver");
  check(CVodeSetUserData(mem.get(), this), "CVodeSetUserData");
  check(CVodeSetMaxNumSteps(mem.get(), options.max_steps), "CVodeSetMaxNumSteps");
  double hmax = options.max_step;
  const double hint = process.maxStepHint();
  if (hint > 0) hmax = hmax > 0 ? std::min(hmax, hint) : hint;
  if (hmax > 0) check(CVodeSetMaxStep(mem.get(), hmax), "CVodeSetMaxStep");
  check(CVodeSetMinStep(mem.get(), options.min_step), "CVodeSetMinStep");
  if (options.method == Method::kBdf && options.bdf_max_order > 0) {
    check(CVodeSetMaxOrd(mem.get(), options.bdf_max_order), "CVodeSetMaxOrd");
  }
  if (n_events > 0) {
    check(CVodeRootInit(mem.get(), n_events, roprecTransientRoots), "CVodeRootInit");
    std::array<int, 8> dir{};
    dir.fill(1);  // an event is g rising through 0
    check(CVodeSetRootDirection(mem.get(), dir.data()), "CVodeSetRootDirection");
  }
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
  s.theta = Eigen::Map<const Vec6>(yp);
  s.theta_d = Eigen::Map<const Vec6>(yp + 6);
  s.theta_m = Eigen::Map<const Vec6>(yp + 12);
  TipState x;
  x.depth = yp[idx_depth];
  if (tipFromState(yp, out_data, x)) {
    process.sample(t, x, s.process);
    s.dp = out_data.frames.p_tcp - T_reference.translation();
    s.drot = smallRotationDifference(out_data.frames.R_tcp, T_reference.linear());
  } else {
    process.sample(t, x, s.process);
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

Deflection TransientSimulator::Impl::staticDeflection(const ToolWrench& w) {
  const DriveModel& dm = problem.drive;
  Loads loads;
  loads.gravity = problem.gravity;
  if (problem.follower_wrench) {
    loads.tcp_tool.force = w.force;
    loads.tcp_tool.moment = w.torque;
  } else {
    loads.tcp = toBaseFrame(w, T_nominal.linear());
  }
  JointCompliance c = dm.staticCompliance();
  if (dm.servo != ServoMode::kCascade) c.k_servo.setConstant(1e300);
  for (int i = 0; i < 6; ++i) {
    if (locked(i)) c.k[i] = c.k_servo[i] = 1e300;
  }
  Deflection d =
      predictDeflection(model, out_data, c, problem.theta_cmd, loads, {}, problem.command_offset);
  if (!d.converged) {
    throw std::runtime_error("transient: the static equilibrium did not converge (residual " +
                             numberText(d.residual) + " rad)");
  }
  return d;
}

Eigen::VectorXd TransientSimulator::equilibriumState(double t0) {
  Impl& m = *impl_;
  const DriveModel& dm = m.problem.drive;
  // the load at t0 with the tip at the reference (u = u̇ = 0, nothing cut yet)
  m.process.reset();
  m.process.sample(t0, TipState{}, m.ps);
  m.ps_time = std::numeric_limits<double>::quiet_NaN();
  const Deflection d = m.staticDeflection(m.ps.wrench);
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

bool TransientSimulator::tipState(const Eigen::VectorXd& y, TipState& x) {
  if (y.size() != impl_->n) throw std::invalid_argument("transient: tipState: wrong state size");
  return impl_->tipFromState(y.data(), impl_->out_data, x);
}

Vec3 TransientSimulator::referenceTcp() const { return impl_->p_ref; }
Vec3 TransientSimulator::drillAxis() const { return impl_->z_n; }

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
  m.theta_cached = false;
  m.process.reset();
  Eigen::Map<Eigen::VectorXd> y(N_VGetArrayPointer(m.y.get()), m.n);
  y = y0;
  if (m.eventsAtRestart(t0, y.data())) ++r.stats.events;
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
  const auto restart = [&](double t) {
    m.accumulate(r.stats);
    check(CVodeReInit(m.mem.get(), t, m.y.get()), "CVodeReInit");
    ++r.stats.restarts;
  };
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
      const bool at_tout = tret >= tout - 1e-12 * std::max(1.0, std::abs(tout));
      if (flag == CV_ROOT_RETURN) {
        // a process event: latch the new mode, restart the multistep method there
        check(CVodeGetRootInfo(m.mem.get(), m.fired.data()), "CVodeGetRootInfo");
        TipState x;
        if (m.tipFromState(y.data(), m.root_data, x)) m.process.onEvents(tret, x, m.fired.data());
        m.ps_time = std::numeric_limits<double>::quiet_NaN();
        ++r.stats.events;
        restart(tret);
        // an event on a breakpoint (a jump of g there) passes that breakpoint too
        const double eps = 1e-12 * std::max(1.0, std::abs(tret));
        while (ib + 1 < bp.size() && bp[ib] <= tret + eps) ++ib;
        if (bp[ib] > tret + eps) check(CVodeSetStopTime(m.mem.get(), bp[ib]), "CVodeSetStopTime");
        if (at_tout) break;
        continue;
      }
      const double tstop = bp[ib];
      if (ib + 1 < bp.size() && tret >= tstop - 1e-12 * std::max(1.0, std::abs(tstop))) {
        // a kink of the load: restart the multistep method there
        if (m.eventsAtRestart(tret, y.data())) ++r.stats.events;
        restart(tret);
        ++ib;
        check(CVodeSetStopTime(m.mem.get(), bp[ib]), "CVodeSetStopTime");
        if (at_tout) break;
        continue;
      }
      break;
    }
    if (r.ok) m.record(tout, y.data(), r);
    if (r.ok && m.options.stop_at_cycle_end &&
        tout >= m.process.endTime() - 1e-12 * std::max(1.0, std::abs(tout))) {
      break;
    }
  }
  m.accumulate(r.stats);
  r.t_reached = tret;
  r.y_final = y;
  return r;
}

TransientResult simulateCycle(const TransientProblem& problem, ProcessCycle& process,
                              const TransientOptions& options, double duration) {
  TransientSimulator sim(problem, process, options);
  Eigen::VectorXd y0;
  try {
    y0 = sim.equilibriumState(0.0);
  } catch (const std::runtime_error& e) {  // no start equilibrium: a result, not a crash
    TransientResult r;
    r.message = e.what();
    return r;
  }
  const double t_end = duration > 0 ? duration : process.duration();
  return sim.run(0.0, y0, t_end);
}

Settling settling(const std::vector<TransientSample>& samples, const Vec3& dp_ref, double t_from,
                  double t_to, double tol) {
  Settling st;
  // the window, the largest error and its direction
  size_t first = samples.size();
  size_t last = 0;
  Vec3 dir = Vec3::Zero();
  for (size_t i = 0; i < samples.size(); ++i) {
    const TransientSample& s = samples[i];
    if (s.t < t_from - 1e-12 || s.t > t_to + 1e-12 || !s.dp.allFinite()) continue;
    first = std::min(first, i);
    last = i;
    const Vec3 e = s.dp - dp_ref;
    if (e.norm() > st.initial_error) {
      st.initial_error = e.norm();
      dir = e;
    }
  }
  if (first >= samples.size()) return st;
  st.final_error = (samples[last].dp - dp_ref).norm();
  st.settled = st.final_error <= tol;
  if (!st.settled) return st;
  size_t k = last;  // the band is left for the last time before samples[k]
  while (k > first && (samples[k - 1].dp - dp_ref).norm() <= tol) --k;
  st.at = samples[k].t;
  st.time = st.at - t_from;
  // oscillation frequency from the zero crossings of the projected error
  if (dir.norm() > 0) dir.normalize();
  double t_prev = -1.0;
  double spacing = 0.0;
  int crossings = 0;
  for (size_t i = first + 1; i <= last; ++i) {
    const double a = (samples[i - 1].dp - dp_ref).dot(dir);
    const double b = (samples[i].dp - dp_ref).dot(dir);
    if ((a < 0) == (b < 0) || a == b) continue;
    const double tz = samples[i - 1].t + (samples[i].t - samples[i - 1].t) * a / (a - b);
    if (t_prev >= 0) {
      spacing += tz - t_prev;
      ++crossings;
    }
    t_prev = tz;
  }
  if (crossings >= 2 && spacing > 0) {
    const double half_period = spacing / crossings;
    st.frequency_hz = 0.5 / half_period;
    const double omega = 2.0 * kPi * st.frequency_hz;
    if (st.time > 0 && st.initial_error > tol) {
      st.damping_ratio = std::log(st.initial_error / tol) / (omega * st.time);
    }
  }
  return st;
}

}  // namespace roprec::nc
