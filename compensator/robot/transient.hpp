#pragma once
/// \file transient.hpp
/// Transient of a flexible-joint robot under a position servo along a drilling cycle, integrated
/// with SUNDIALS CVODE (docs/model.md §5.3 "Direct dynamics", §6.5 "Dynamic flexible
/// joints"; Spong, ASME J. Dyn. Syst. Meas. Control 109:310–319, 1987).
///
/// ## Equations (all link side, SI: rad, rad/s, N m, kg m²)
/// Link side (mixed natural coordinates, velocity transformation R = ∂q/∂θ, Sc = A⁻¹[c; 0]):
///
///   RᵀMR θ̈ = Rᵀ(Q_ext − M Sc) + K(θ_m − θ) + D(θ̇_m − θ̇)
///
/// Motor side, B_m the reflected rotor inertias:
///
///   B_m θ̈_m + K(θ_m − θ) + D(θ̇_m − θ̇) = τ_m
///
/// Q_ext = link, tool and spindle weight + the process wrench on the TCP (inverse_dynamics.hpp
/// `generalizedForces`); the process wrench is given in the tool frame and turned into the base
/// frame with the **current** (deflected) TCP orientation (`follower_wrench`, default) or with the
/// nominal one (as `roprec deflect` does). K = diag(k), D = diag(d).
///
/// Servo (per joint, cascade of the industrial drive, link-side units):
///   ω_ref = Kv (θ_c − θ_m)                           position loop, Kv [1/s]
///   e     = ω_ref − θ̇_m                              velocity error [rad/s]
///   τ_m   = Kω (e + ω_i ξ),   ξ̇ = e                  velocity PI, Kω [N m s/rad], ω_i [1/s]
/// with θ_c = θ_cmd + command_offset (the controller's own offsets, e.g. its gravity
/// compensation). The command is constant (see "Decision" below), so there is no velocity
/// feed-forward. Steady state (θ̇ = θ̇_m = 0, ξ̇ = 0):
///   * with integral action e = 0 ⇒ θ_m = θ_c and K(θ_m − θ) = τ = −RᵀQ_ext: the static model
///     with an ideal servo (deflection.hpp, k_servo = ∞);
///   * without it τ = Kω Kv (θ_c − θ_m): the static model with k_servo = Kv·Kω in series with k.
/// `ServoMode::kIdeal` holds θ_m ≡ θ_c (infinitely stiff motor side); `kFree` sets τ_m = 0
/// (free motors: the conservative system used by the energy and closed-form tests).
///
/// State y = [θ, θ̇, θ_m, θ̇_m (, ξ)] — 24 entries, 30 with integral action. Locked joints
/// (`DriveModel::locked`) are rigid at θ = θ_m = θ_c: their rows of RᵀMR are replaced by the
/// identity and their derivatives are zero (a chain whose distal links carry no mass has a
/// singular RᵀMR otherwise).
///
/// ## Right-hand side (no allocation, no dense 72×72 factorisation)
///  1. q(θ) by the position problem (exact forward recursion + Newton check by default, or a
///     warm-started Newton; `TransientOptions::guess`);
///  2. R (6 structured sweeps, model.hpp), q̇ = R θ̇, c and Sc (one structured solve);
///  3. RᵀMR by the block mass products (jointSpaceInertia), Rᵀ(Q_ext − M Sc);
///  4. θ̈ by a 6×6 Cholesky, θ̈_m, ξ̇ explicitly.
/// A position problem that does not converge (or a non-finite derivative) returns +1: CVODE
/// retries with a smaller step; a non-finite process load returns −1 (a smaller step cannot help).
/// Any exception is caught in the C trampoline, stored as std::exception_ptr, the trampoline
/// returns −1 and the exception is rethrown after CVode returns.
///
/// ## Integrator
/// CVODE with Adams–Moulton, variable order 1–12 (the analogue of MATLAB's ode113) by default,
/// BDF (orders 1–5) selectable; Newton iteration with the dense direct linear solver and CVODE's
/// difference-quotient Jacobian. The run is split at the breakpoints of the process law
/// (contact, full engagement, breakthrough, end of feed, …): CVODE stops there (CVodeSetStopTime)
/// and restarts (CVodeReInit) so that no step straddles a kink of the load.
///
/// ## Decision: the arm holds the hole pose, only the process load varies
/// Robotic drilling end effectors feed the spindle with their own axis behind a pressure foot, so
/// the arm is commanded to one pose during the cut; when the arm itself feeds, it moves at
/// f·n ≈ 10 mm/s, whose inertial loads are negligible against the process forces, and a moving
/// command would only add the servo's following error v/Kv — which controllers cancel with
/// velocity feed-forward. So θ_cmd(t) ≡ θ_cmd (the static command of the hole), the depth is
/// kinematic, depth = f·n·(t − t_contact) (the axial deviation does not feed back into the chip
/// thickness), and the deviation is measured from the nominal rigid TCP FK(θ_cmd).
///
/// ## Drilling cycle (DrillingCycle), tool frame, drill axis +z into the material
///   approach  t < t_c                         no load
///   entry     0 < depth < (R − a)/tan p       thrust and torque ramp with the engaged lip length
///   full      lips engaged on [a, R]          steady forces (drilling_forces.hpp)
///   breakthrough (through holes) depth > T    chisel out, lips leave the plate
///   dwell     feed stopped at the end depth   chip thickness decays to zero over 1/2 revolution
///                                             (the next lip reaches the stop surface; forces
///                                             scaled linearly), then no load
///   retract   no load
/// drillingForcesAtDepth gives Fz (thrust), M, Σ Ft and the rotating residual Fr; the wrench on
/// the TCP is toolWrench(F, φ) with φ = 2π n t/60 when the rotating runout force is enabled,
/// else its in-plane part is dropped (its mean over a revolution is zero).
/// Constant processes (cell `wrench`, and milling's revolution-averaged force) act as a step
/// with a ½(1 − cos) ramp of `CycleTiming::ramp` s, held `CycleTiming::hold` s.

#include <array>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "compensator/process/process_spec.hpp"
#include "compensator/robot/deflection.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec::nc {

enum class ServoMode {
  kCascade,  ///< position P + velocity PI (or P) loop, see file comment
  kIdeal,    ///< motor side held at the command
  kFree,     ///< τ_m = 0
};

/// Drive parameters per joint, link side.
struct DriveModel {
  Vec6 k{Vec6::Constant(1e6)};       ///< joint stiffness K, N m/rad
  Vec6 damping{Vec6::Zero()};        ///< joint damping D, N m s/rad
  Vec6 motor_inertia{Vec6::Ones()};  ///< B_m, kg m² (reflected, link side)
  ServoMode servo{ServoMode::kCascade};
  Vec6 kv{Vec6::Constant(40.0)};  ///< position gain Kv, 1/s
  Vec6 kw{Vec6::Ones()};          ///< velocity gain Kω, N m s/rad
  Vec6 wi{Vec6::Constant(40.0)};  ///< integral corner ω_i, 1/s (Ki = Kω ω_i)
  bool integral{true};            ///< velocity-loop integral action
  std::array<bool, 6> locked{};   ///< rigid joints (θ = θ_m = θ_c)
  /// The static compliance this drive settles to: k and k_servo = Kv·Kω (proportional cascade)
  /// or ∞ (integral action, ideal servo). Not meaningful for kFree.
  [[nodiscard]] JointCompliance staticCompliance() const;
};

/// Estimates for what a robot card does not give. Each is an estimate (not a published value);
/// docs/transient.md explains them.
struct DriveEstimateOptions {
  /// B_m = ratio · (RᵀMR)_ii at the reference pose when the card has no motor_inertia.
  /// estimate: n²·J_rotor of large geared robots is of the order of the link inertia
  /// (KR 120 class: J_rotor ≈ 1–3e-3 kg m², n ≈ 150–250 → 20–190 kg m² on the main axes).
  double motor_inertia_ratio{0.5};
  /// Kω = ω_v (B_m + (RᵀMR)_ii) with ω_v = factor · Kv when the card has no velocity_gain.
  /// estimate: cascade rule of thumb, the velocity loop 3–10× faster than the position loop.
  double velocity_bandwidth_factor{5.0};
  /// ω_i = factor · Kv. estimate: PI corner at the position-loop bandwidth (stable cascade,
  /// Routh on the rigid loop s³ + ω_v s² + ω_v(ω_i + Kv)s + ω_v ω_i Kv).
  double integral_corner_factor{1.0};
  /// D = 2 ζ √(k J_eff), J_eff = J B_m/(J + B_m). estimate: structural damping ratio of
  /// industrial gearboxes, a few percent.
  double damping_ratio{0.05};
  bool integral{true};
};

/// Drive model of a card at the reference configuration θ_ref (link inertias (RᵀMR)_ii there).
/// Card values win: stiffness (required), position_gain (absent → ServoMode::kIdeal),
/// velocity_gain, motor_inertia. Throws InputError (card file, joint line) without stiffness.
DriveModel driveModelFromCard(const RobotCard& card, const Model& model, Data& data,
                              const Vec6& theta_ref, const DriveEstimateOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Process law

enum class CyclePhase { kApproach, kEntry, kFull, kBreakthrough, kDwell, kRetract };
/// "approach", "entry", "full", "breakthrough", "dwell", "retract".
const char* phaseName(CyclePhase p);

/// The process at one instant.
struct ProcessSample {
  CyclePhase phase{CyclePhase::kApproach};
  double depth{0.0};  ///< tip depth below the entry surface, m (0 for constant processes)
  double Fa{0.0};     ///< thrust (axial force pushing the tool back, +), N
  double Ft{0.0};     ///< tangential cutting force Σ Ft,k (constant processes: |F_xy|), N
  double M{0.0};      ///< drilling torque (constant processes: −M_z), N m
  double Fr{0.0};     ///< amplitude of the rotating residual force, N
  ToolWrench wrench;  ///< applied wrench on the TCP, tool frame
};

/// Process load as a function of time. `sample` may use internal scratch (not thread-safe) and
/// must not allocate; it must be a pure function of t (the simulator caches the last sample).
class ProcessCycle {
 public:
  virtual ~ProcessCycle() = default;
  virtual void sample(double t, ProcessSample& out) = 0;
  /// End of the natural cycle, s.
  [[nodiscard]] virtual double duration() const = 0;
  /// Times where the load has a kink or a jump (sorted, inside (0, duration)).
  [[nodiscard]] virtual std::vector<double> breakpoints() const = 0;
  /// Largest step that resolves the load (0 = no limit), s.
  [[nodiscard]] virtual double maxStepHint() const { return 0.0; }
};

struct CycleTiming {
  double approach{0.1};  ///< s before contact
  double dwell{0.1};     ///< s at the end depth (feed stopped)
  double retract{0.1};   ///< s of retract, no load
  double ramp{0.02};     ///< s, ½(1 − cos) ramp of a constant process (estimate: smooth step)
  double hold{1.0};      ///< s at the full constant load
};

/// No process: gravity only.
class NoProcess final : public ProcessCycle {
 public:
  explicit NoProcess(double duration = 1.0) : duration_(duration) {}
  void sample(double t, ProcessSample& out) override;
  [[nodiscard]] double duration() const override { return duration_; }
  [[nodiscard]] std::vector<double> breakpoints() const override { return {}; }

 private:
  double duration_;
};

/// A constant tool-frame wrench switched on and off with ramps.
class StepWrenchCycle final : public ProcessCycle {
 public:
  StepWrenchCycle(const ToolWrench& w, const CycleTiming& timing);
  void sample(double t, ProcessSample& out) override;
  [[nodiscard]] double duration() const override;
  [[nodiscard]] std::vector<double> breakpoints() const override;

 private:
  ToolWrench w_;
  CycleTiming tm_;
};

/// The drilling cycle of a DrillingSpec (see file comment).
class DrillingCycle final : public ProcessCycle {
 public:
  DrillingCycle(const DrillingSpec& spec, const CycleTiming& timing, bool rotating_runout);
  void sample(double t, ProcessSample& out) override;
  [[nodiscard]] double duration() const override;
  [[nodiscard]] std::vector<double> breakpoints() const override;
  [[nodiscard]] double maxStepHint() const override;
  [[nodiscard]] double feedRate() const { return v_f_; }  ///< m/s
  [[nodiscard]] double contactTime() const { return tm_.approach; }

 private:
  DrillingModel model_;
  DrillingData data_;
  CycleTiming tm_;
  bool runout_;
  double feed_;        ///< m/rev
  double omega_s_;     ///< spindle rad/s
  double v_f_;         ///< m/s
  double thickness_;   ///< plate thickness for through holes (0 = blind)
  double depth_full_;  ///< depth where the corner enters
  double depth_end_;   ///< depth where the feed stops
  double t_full_, t_break_, t_feed_end_, t_decay_end_, t_dwell_end_, t_end_;
};

/// The cycle of a cell's process (drilling → DrillingCycle; wrench and milling → StepWrenchCycle
/// with steadyProcessLoad's wrench).
std::unique_ptr<ProcessCycle> makeProcessCycle(const ProcessSpec& spec, const CycleTiming& timing,
                                               bool rotating_runout = false);

// ---------------------------------------------------------------------------------------------
// Integrator

enum class Method { kAdams, kBdf };

struct TransientOptions {
  Method method{Method::kAdams};
  double rtol{1e-8};        ///< CVODE relative tolerance
  double atol_angle{1e-9};  ///< rad, absolute tolerance of θ, θ_m, ξ (2.5 nm at 2.5 m reach)
  double atol_rate{1e-7};   ///< rad/s, absolute tolerance of θ̇, θ̇_m
  double max_step{5e-3};    ///< s (0 = CVODE's default: none); also capped by the process
  double min_step{1e-12};   ///< s: CVODE gives up below (a failure that smaller steps cannot cure)
  double sample{1e-3};      ///< output sampling, s
  long max_steps{2000000};  ///< CVODE steps in total
  /// Position-problem start in the right-hand side. The exact forward recursion + one Φ check
  /// measured cheaper (3.8 µs per RHS) than the warm-started Newton (5.1 µs, it iterates and now
  /// checks the branch), so it is the default; kWarmStart remains selectable.
  Guess guess{Guess::kClosedForm};
};

struct TransientProblem {
  const Model* model{nullptr};
  DriveModel drive;
  Vec6 theta_cmd{Vec6::Zero()};       ///< commanded (nominal) joints, rad
  Vec6 command_offset{Vec6::Zero()};  ///< added by the controller, not part of the nominal
  bool gravity{true};
  bool follower_wrench{true};  ///< process wrench turns with the real TCP
};

struct TransientSample {
  double t{0.0};
  ProcessSample process;
  Vec6 theta{Vec6::Zero()};    ///< link angles, rad
  Vec6 theta_m{Vec6::Zero()};  ///< motor angles (link side), rad
  Vec3 dp{Vec3::Zero()};       ///< TCP translation deviation from FK(θ_cmd), m, base frame
  Vec3 drot{Vec3::Zero()};     ///< TCP rotation deviation (rotation vector), rad, base frame
};

struct TransientStats {
  long steps{0};
  long rhs_evals{0};      ///< by the integrator
  long rhs_evals_jac{0};  ///< by the difference-quotient Jacobian
  long jac_evals{0};
  long nonlinear_iterations{0};
  long error_test_failures{0};
  long convergence_failures{0};
  int restarts{0};  ///< CVodeReInit at breakpoints
};

/// Outcome of a run. Non-convergence is a value: ok = false with the CVODE message.
struct TransientResult {
  bool ok{false};
  int cvode_flag{0};
  std::string message;
  double t_reached{0.0};
  TransientStats stats;
  std::vector<TransientSample> samples;
  Eigen::VectorXd y_final;
  Pose T_nominal{Pose::Identity()};
};

/// Owns every CVODE handle (RAII) and the right-hand-side workspace.
class TransientSimulator {
 public:
  /// `problem.model` and `process` must outlive the simulator. Throws std::invalid_argument for
  /// an inconsistent problem (non-positive k or B_m, a free joint without link inertia, …).
  TransientSimulator(const TransientProblem& problem, ProcessCycle& process,
                     const TransientOptions& options = {});
  ~TransientSimulator();
  TransientSimulator(const TransientSimulator&) = delete;
  TransientSimulator& operator=(const TransientSimulator&) = delete;

  /// 24, or 30 with integral action.
  [[nodiscard]] int stateSize() const;
  /// Rest state at the static equilibrium under gravity and the process load at t0 (follower or
  /// fixed as the problem says): θ from predictDeflection, θ_m, ξ consistent with the servo.
  [[nodiscard]] Eigen::VectorXd equilibriumState(double t0);
  /// Rest state at the command, undeflected: θ = θ_m = θ_c, rates and ξ zero.
  [[nodiscard]] Eigen::VectorXd commandState() const;
  /// The right-hand side ẏ = f(t, y) (dim stateSize). Returns 0; 1 when the position problem
  /// does not converge or ẏ is not finite; −1 for a non-finite process load. Exceptions propagate
  /// (the trampoline catches them).
  int rhs(double t, const double* y, double* ydot);
  /// Integrates from (t0, y0) to t_end, sampling every options.sample (and at t_end).
  /// Rethrows an exception raised inside the right-hand side; CVODE failures are a value.
  TransientResult run(double t0, const Eigen::VectorXd& y0, double t_end);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Convenience: equilibrium at t = 0, then the whole cycle (or `duration` s when > 0).
TransientResult simulateCycle(const TransientProblem& problem, ProcessCycle& process,
                              const TransientOptions& options = {}, double duration = 0.0);

}  // namespace roprec::nc
