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
/// State y = [θ, θ̇, θ_m, θ̇_m (, ξ), D] — 25 entries, 31 with integral action (D: the cut depth
/// of the drilling cycle, see "Decision"; Ḋ = 0 for processes that do not penetrate). Locked joints
/// (`DriveModel::locked`) are rigid at θ = θ_m = θ_c: their rows of RᵀMR are replaced by the
/// identity and their derivatives are zero (a chain whose distal links carry no mass has a
/// singular RᵀMR otherwise).
///
/// ## Right-hand side (fixed-size Eigen types only, no allocation, no dense 72×72 factorisation)
///  1. q(θ) by the position problem (exact forward recursion + Newton check by default, or a
///     warm-started Newton; `TransientOptions::guess`), R and the Cholesky factor of RᵀMR: kept
///     while θ is unchanged (the difference-quotient Jacobian perturbs θ̇, θ_m, θ̇_m, ξ and D with θ
///     fixed: 25 of its 31 columns reuse them);
///  2. q̇ = R θ̇; the tip state u = z_nᵀ(p_tcp − p_ref),
///     u̇ = z_nᵀ ṗ_tcp (p_tcp linear in q and q̇) and D = y[n−1]; the process at (t, u, u̇, D)
///     (cached: the Jacobian's perturbations of θ_m, θ̇_m, ξ reuse it);
///  3. c and Sc (one structured solve), RᵀMR by the block mass products (jointSpaceInertia),
///     Rᵀ(Q_ext − M Sc);
///  4. θ̈ by a 6×6 Cholesky, θ̈_m, ξ̇ explicitly, Ḋ from the process.
/// The drilling forces come from the table of transient_forces.hpp (≤ 1e-5 of the steady load from
/// drillingForcesAtDepth; exact at full engagement). The root functions (process events) and the
/// output samples take the tip state from the frame recursion (fast_equilibrium.hpp chainFrames
/// and tcpJacobianFromFrames: p_tcp and ṗ_tcp = J_v θ̇ without the position problem) on their own
/// workspace and call ProcessCycle::eventFunctions; they go through the same C firewall.
/// A position problem that does not converge (or a non-finite derivative) returns +1: CVODE
/// retries with a smaller step; a non-finite process load returns −1 (a smaller step cannot help).
/// Any exception is caught in the C trampoline, stored as std::exception_ptr, the trampoline
/// returns −1 and the exception is rethrown after CVode returns.
///
/// ## Integrator
/// CVODE with BDF (orders 1–3 by default, `bdf_max_order`; the analogue of MATLAB's ode15s) by
/// default, Adams–Moulton
/// (variable order 1–12, ode113) selectable; Newton iteration with the dense direct linear solver
/// and CVODE's difference-quotient Jacobian. Default tolerances from the convergence study of
/// docs/transient.md (TransientOptions). The run is split at the breakpoints of the process law
/// (contact, full engagement, breakthrough, end of feed, …): CVODE stops there (CVodeSetStopTime)
/// and restarts (CVodeReInit) so that no step straddles a kink of the load.
///
/// ## Decision: the arm holds the hole pose; the depth follows the real penetration
/// Robotic drilling end effectors feed the spindle with their own axis behind a pressure foot, so
/// the arm is commanded to one pose during the cut; when the arm itself feeds, it moves at
/// f·n ≈ 10 mm/s, whose inertial loads are negligible against the process forces, and a moving
/// command would only add the servo's following error v/Kv — which controllers cancel with
/// velocity feed-forward. So θ_cmd(t) ≡ θ_cmd (the static command of the hole) and the feed is
/// the commanded spindle position p_c(t) along the nominal drill axis z_n (tool z of FK(θ_cmd)).
/// The arm's compliance feeds back into the chip (docs/transient.md "Decision"):
///
///   u   = z_nᵀ (p_tcp(θ) − p_ref)          axial TCP deviation, + into the material [m]
///                                          (p_ref: TCP at the gravity-only static equilibrium,
///                                          i.e. the pose in which the tip touches at t_c)
///   u̇   = z_nᵀ ṗ_tcp = z_nᵀ J_v(θ) θ̇        [m/s]
///   s   = p_c(t) + u                       tip position below the entry surface [m]
///   p_c = f n/60 (t − t_c) during the feed, constant at the end depth once the feed stops
///   D   = max_{τ ≤ t} s(τ)                 cut depth (material removed), an extra CVODE state
///   Ḋ   = ṡ⁺ while cutting (tip at the bottom, s = D, and advancing), 0 when lifted (s < D)
///   h   = Ḋ · 60/n                         real feed per revolution [m/rev]
///   (Fz, M, Ft, Fr) = drillingForcesAtDepth(h, D)   engaged lips from D (drilling_forces.hpp;
///                                          evaluated by the table of transient_forces.hpp)
///
/// The forces are a function of the state (through D and ṡ), not of t alone. The thrust
/// acts like a non-linear damper on the tip (Fz ∝ ṡ^{1−m}, no force at ṡ = 0), so the tip
/// never moves back while thrust is applied. Cutting/lifted and the end of the cut are modes
/// latched by CVODE root finding (`ProcessCycle::eventFunctions`, restarts at each event):
///   lifted → cutting   s − D rises through 0 (contact; first at t ≈ t_c)
///   cutting → lifted   ṡ falls through 0 (the tip leaves the bottom; D stays)
///   end of cut         dwell: h falls below `CycleTiming::cut_end_feed_fraction`·f (checked
///                      from one lip pitch after the feed stops); through hole: D reaches the
///                      exit depth T + (R − a)/tan p. The spindle then retracts (no load).
/// The deviation is measured from the nominal rigid TCP FK(θ_cmd).
///
/// ## Drilling cycle (DrillingCycle), tool frame, drill axis +z into the material
///   approach  s < 0                           no load, p_c = v_f (t − t_c)
///   entry     0 < D < (R − a)/tan p           thrust and torque grow with the engaged lip length
///   full      lips engaged on [a, R]          steady forces at the real feed h
///   breakthrough (through holes) D > T        chisel out, lips leave the plate
///   dwell     feed stopped at the end depth   the recovering arm keeps cutting: thrust decays
///                                             with the real advance until the end of cut
///                                             (at most `CycleTiming::dwell` s)
///   retract   no load
/// drillingForcesAtDepth gives Fz (thrust), M, Σ Ft and the rotating residual Fr; the wrench on
/// the TCP is toolWrench(F, φ) with φ = 2π n t/60 when the rotating runout force is enabled,
/// else its in-plane part is dropped (its mean over a revolution is zero).
/// Constant processes (cell `wrench`, and milling's revolution-averaged force) act as a step
/// with a ½(1 − cos) ramp of `CycleTiming::ramp` s, held `CycleTiming::hold` s; they ignore the
/// tip state.

#include <array>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compensator/process/process_spec.hpp"
#include "compensator/process/transient_forces.hpp"
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

/// What the simulator passes to the process: the drill tip's axial state (see "Decision").
struct TipState {
  double axial{0.0};       ///< u = z_nᵀ(p_tcp − p_ref), m, + into the material
  double axial_rate{0.0};  ///< u̇, m/s
  double depth{0.0};       ///< D, cut depth state, m
};

/// The process at one instant.
struct ProcessSample {
  CyclePhase phase{CyclePhase::kApproach};
  bool cutting{false};        ///< tip at the bottom and advancing (drilling)
  double feed_position{0.0};  ///< p_c, commanded spindle position below the entry surface, m
  double axial{0.0};          ///< u, m (copied from the TipState)
  double axial_rate{0.0};     ///< u̇, m/s
  double tip{0.0};            ///< s = p_c + u, m
  double depth{0.0};          ///< D, cut depth, m (0 for constant processes)
  double depth_rate{0.0};     ///< Ḋ, m/s (the state derivative)
  double feed_per_rev{0.0};   ///< h = Ḋ·60/n, real feed per revolution, m/rev
  double Fa{0.0};             ///< thrust (axial force pushing the tool back, +), N
  double Ft{0.0};             ///< tangential cutting force Σ Ft,k (constant processes: |F_xy|), N
  double M{0.0};              ///< drilling torque (constant processes: −M_z), N m
  double Fr{0.0};             ///< amplitude of the rotating residual force, N
  ToolWrench wrench;          ///< applied wrench on the TCP, tool frame
};

/// Process load as a function of time and of the tip state. `sample` may use internal scratch
/// (not thread-safe) and must not allocate; between two events it must be a pure function of
/// (t, x) (the simulator caches the last sample). Events: the simulator finds the roots of
/// `eventFunctions` (each g_i rising through 0) with CVODE, calls `onEvents` there (the process
/// latches a mode) and restarts the integrator.
class ProcessCycle {
 public:
  virtual ~ProcessCycle() = default;
  virtual void sample(double t, const TipState& x, ProcessSample& out) = 0;
  /// End of the natural cycle (upper bound), s.
  [[nodiscard]] virtual double duration() const = 0;
  /// Times where the load has a kink or a jump (sorted, inside (0, duration)).
  [[nodiscard]] virtual std::vector<double> breakpoints() const = 0;
  /// Largest step that resolves the load (0 = no limit), s.
  [[nodiscard]] virtual double maxStepHint() const { return 0.0; }
  /// Clears the latched modes (called at the start of every run).
  virtual void reset() {}
  /// Number of event functions (fixed for the object).
  [[nodiscard]] virtual int eventCount() const { return 0; }
  /// g(t, x) into g[0 .. eventCount()); an event is g_i rising through 0. No allocation.
  virtual void eventFunctions(double /*t*/, const TipState& /*x*/, double* /*g*/) {}
  /// Called at an event (fired[i] ≠ 0 for the roots found).
  virtual void onEvents(double /*t*/, const TipState& /*x*/, const int* /*fired*/) {}
  /// End of the cycle as known now (≤ duration(); earlier once the cut has ended), s.
  [[nodiscard]] virtual double endTime() const { return duration(); }
};

struct CycleTiming {
  double approach{0.1};  ///< s before contact
  /// Maximum s at the end depth (feed stopped); the cut normally ends earlier (end-of-cut event).
  double dwell{2.0};
  double retract{0.1};  ///< s of retract, no load
  /// The cut ends (dwell) when the real feed per revolution falls below this fraction of the
  /// programmed feed. estimate: 1 % (2 µm/rev at 0.2 mm/rev) is below the edge-radius floor h_min
  /// (5 µm) under which no chip is formed.
  double cut_end_feed_fraction{0.01};
  /// Feed travel beyond the exit of the corner for through holes (estimate: 1 mm breakthrough
  /// allowance), m.
  double overtravel{1e-3};
  double ramp{0.02};  ///< s, ½(1 − cos) ramp of a constant process (estimate: smooth step)
  double hold{1.0};   ///< s at the full constant load
};

/// No process: gravity only.
class NoProcess final : public ProcessCycle {
 public:
  explicit NoProcess(double duration = 1.0) : duration_(duration) {}
  void sample(double t, const TipState& x, ProcessSample& out) override;
  [[nodiscard]] double duration() const override { return duration_; }
  [[nodiscard]] std::vector<double> breakpoints() const override { return {}; }

 private:
  double duration_;
};

/// A constant tool-frame wrench switched on and off with ramps.
class StepWrenchCycle final : public ProcessCycle {
 public:
  StepWrenchCycle(const ToolWrench& w, const CycleTiming& timing);
  void sample(double t, const TipState& x, ProcessSample& out) override;
  [[nodiscard]] double duration() const override;
  [[nodiscard]] std::vector<double> breakpoints() const override;
  /// Start of the constant (held) load, s.
  [[nodiscard]] double holdStart() const { return tm_.approach + tm_.ramp; }
  /// End of the held load, s.
  [[nodiscard]] double holdEnd() const { return tm_.approach + tm_.ramp + tm_.hold; }

 private:
  ToolWrench w_;
  CycleTiming tm_;
};

/// The drilling cycle of a DrillingSpec, coupled to the real penetration (see file comment).
class DrillingCycle final : public ProcessCycle {
 public:
  /// `forces`: the tabulated law (transient_forces.hpp, default) or the exact evaluator.
  DrillingCycle(const DrillingSpec& spec, const CycleTiming& timing, bool rotating_runout,
                ForceEvaluation forces = ForceEvaluation::kTabulated);
  void sample(double t, const TipState& x, ProcessSample& out) override;
  [[nodiscard]] double duration() const override;
  [[nodiscard]] std::vector<double> breakpoints() const override;
  [[nodiscard]] double maxStepHint() const override;
  void reset() override;
  [[nodiscard]] int eventCount() const override { return 3; }
  /// g0: lifted s − D (contact) / cutting −ṡ (lift); g1: end of cut in dwell (h_stop − h);
  /// g2: through hole, D − D_exit.
  void eventFunctions(double t, const TipState& x, double* g) override;
  void onEvents(double t, const TipState& x, const int* fired) override;
  [[nodiscard]] double endTime() const override;

  [[nodiscard]] double feedRate() const { return v_f_; }             ///< m/s
  [[nodiscard]] double contactTime() const { return tm_.approach; }  ///< nominal t_c, s
  [[nodiscard]] double feedEndTime() const { return t_feed_end_; }   ///< s
  [[nodiscard]] double endDepth() const { return depth_end_; }       ///< commanded, m
  [[nodiscard]] double cutEndFeed() const { return h_stop_; }        ///< h_stop, m/rev
  [[nodiscard]] double revolutionsPerSecond() const { return n_rps_; }
  /// Time of the first contact and of the end of the cut (negative: not yet).
  [[nodiscard]] double firstContact() const { return t_first_contact_; }
  [[nodiscard]] double cutEnd() const { return t_cut_end_; }

 private:
  [[nodiscard]] double feedPosition(double t) const;  ///< p_c(t)
  [[nodiscard]] double feedVelocity(double t) const;  ///< ṗ_c(t)

  DrillingModel model_;
  DrillingData data_;
  ForceEvaluation evaluation_;
  CycleTiming tm_;
  bool runout_;
  double feed_;        ///< m/rev
  double omega_s_;     ///< spindle rad/s
  double n_rps_;       ///< spindle rev/s
  double v_f_;         ///< m/s
  double thickness_;   ///< plate thickness for through holes (0 = blind)
  double depth_full_;  ///< depth where the corner enters
  double depth_exit_;  ///< through holes: depth where the corner leaves the plate (else ∞)
  double depth_end_;   ///< commanded depth where the feed stops
  double h_stop_;      ///< end-of-cut feed per revolution, m/rev
  double t_feed_end_, t_check_, t_dwell_end_, t_end_;
  // latched modes (reset() clears them)
  bool cutting_{false};
  bool ended_{false};
  double lift_offset_{0.0};  ///< s − D at the last lift (integration drift), m
  double t_first_contact_{-1.0};
  double t_cut_end_{-1.0};
  double depth_at_end_{0.0};  ///< p_c when the cut ended (start of the retract), m
  DrillingForceTable table_;  ///< built after thickness_ (declaration order)
};

/// The cycle of a cell's process (drilling → DrillingCycle; wrench and milling → StepWrenchCycle
/// with steadyProcessLoad's wrench).
std::unique_ptr<ProcessCycle> makeProcessCycle(const ProcessSpec& spec, const CycleTiming& timing,
                                               bool rotating_runout = false);

// ---------------------------------------------------------------------------------------------
// Integrator

enum class Method { kAdams, kBdf };

struct TransientOptions {
  /// Method and tolerances: chosen by the convergence study of docs/transient.md ("Integrator
  /// tolerances"): against a tight reference (Adams, rtol 1e-11, exact force law) this setting
  /// keeps the TCP deviation within 0.5 µm at the hole bottom and 1 µm during the cut, in
  /// the fewest steps of the settings tried (BDF: the cutting damper and the drive modes are
  /// stiff; fixed-point iteration needs ≈ 13,000 steps per 2 s cycle).
  Method method{Method::kBdf};
  /// Highest BDF order (0: CVODE's 5). BDF4 and BDF5 are not stable near the imaginary axis, where
  /// the lightly damped joint modes sit: with them the step count jumps between ≈ 570 and ≈ 1600
  /// per 2 s cycle with the output interval; capped at 3 it stays at ≈ 590–620 (docs/transient.md).
  int bdf_max_order{3};
  double rtol{1e-4};        ///< CVODE relative tolerance
  double atol_angle{1e-7};  ///< rad, absolute tolerance of θ, θ_m, ξ (0.25 µm at 2.5 m reach)
  double atol_rate{1e-5};   ///< rad/s, absolute tolerance of θ̇, θ̇_m
  double max_step{5e-3};    ///< s (0 = CVODE's default: none); also capped by the process
  double min_step{1e-12};   ///< s: CVODE gives up below (a failure that smaller steps cannot cure)
  double sample{1e-3};      ///< output sampling, s
  long max_steps{2000000};  ///< CVODE steps in total
  /// Position-problem start in the right-hand side. The exact forward recursion + one Φ check
  /// measured cheaper (3.8 µs per RHS) than the warm-started Newton (5.1 µs, it iterates and now
  /// checks the branch), so it is the default; kWarmStart remains selectable.
  Guess guess{Guess::kClosedForm};
  double atol_depth{1e-8};  ///< m, absolute tolerance of the cut depth D
  /// Stop at the first output sample at or after ProcessCycle::endTime() (the drilling cycle ends
  /// early when the cut ends before the maximum dwell).
  bool stop_at_cycle_end{false};
};

struct TransientProblem {
  const Model* model{nullptr};
  DriveModel drive;
  Vec6 theta_cmd{Vec6::Zero()};       ///< commanded (nominal) joints, rad
  Vec6 command_offset{Vec6::Zero()};  ///< added by the controller, not part of the nominal
  bool gravity{true};
  bool follower_wrench{true};  ///< process wrench turns with the real TCP
  /// The pose the controller means by θ_cmd, the reference of the samples' dp and drot:
  /// FK_nom(θ_cmd) of the TCP for a calibrated robot (its deviation then holds the geometric error
  /// too, as deflect's, docs/model.md §6.8); unset: the model's rigid FK(θ_cmd).
  std::optional<Pose> controller_tcp;
};

struct TransientSample {
  double t{0.0};
  ProcessSample process;
  Vec6 theta{Vec6::Zero()};    ///< link angles, rad
  Vec6 theta_d{Vec6::Zero()};  ///< link rates, rad/s
  Vec6 theta_m{Vec6::Zero()};  ///< motor angles (link side), rad
  Vec3 dp{Vec3::Zero()};       ///< TCP deviation from FK(θ_cmd) (controller_tcp), m, base frame
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
  int restarts{0};  ///< CVodeReInit at breakpoints and events
  int events{0};    ///< process events (contact, lift, end of cut)
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

  /// 25, or 31 with integral action (the last entry is the cut depth D).
  [[nodiscard]] int stateSize() const;
  /// Rest state at the static equilibrium under gravity and the process load at t0 (follower or
  /// fixed as the problem says): θ from predictDeflection, θ_m, ξ consistent with the servo, D = 0.
  [[nodiscard]] Eigen::VectorXd equilibriumState(double t0);
  /// Rest state at the command, undeflected: θ = θ_m = θ_c, rates, ξ and D zero.
  [[nodiscard]] Eigen::VectorXd commandState() const;
  /// The right-hand side ẏ = f(t, y) (dim stateSize). Returns 0; 1 when the position problem
  /// does not converge or ẏ is not finite; −1 for a non-finite process load. Exceptions propagate
  /// (the trampoline catches them).
  int rhs(double t, const double* y, double* ydot);
  /// Integrates from (t0, y0) to t_end, sampling every options.sample (and at t_end).
  /// Rethrows an exception raised inside the right-hand side; CVODE failures are a value.
  TransientResult run(double t0, const Eigen::VectorXd& y0, double t_end);
  /// The tip state of y (u, u̇ from the FK of θ and θ̇, D from the state). False when the position
  /// problem does not converge.
  bool tipState(const Eigen::VectorXd& y, TipState& x);
  /// The reference TCP position p_ref (gravity-only equilibrium) and the nominal drill axis z_n.
  [[nodiscard]] Vec3 referenceTcp() const;
  [[nodiscard]] Vec3 drillAxis() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// Convenience: equilibrium at t = 0, then the whole cycle (or `duration` s when > 0). A start
/// equilibrium that does not converge is a result with `ok` false and the reason in `message`
/// (t_reached 0, no samples); an inconsistent problem still throws std::invalid_argument.
TransientResult simulateCycle(const TransientProblem& problem, ProcessCycle& process,
                              const TransientOptions& options = {}, double duration = 0.0);

/// Settling of a sampled history onto a static deviation `dp_ref` (base frame, m): the first
/// sample time t_s ≥ t_from after which every sample up to `t_to` has |dp − dp_ref| ≤ tol.
/// `settled` is false when the last sample in [t_from, t_to] is outside the band. The equivalent
/// damping ratio is the one of a single mode whose envelope A0 e^{−ζωt} falls from the largest
/// error A0 after t_from to tol in t_s − t_from: ζ = ln(A0/tol)/(ω (t_s − t_from)), with ω from
/// the mean zero-crossing spacing of the error projected on its largest excursion (0 when the
/// error does not oscillate; then only t_s is meaningful).
struct Settling {
  bool settled{false};
  double time{0.0};           ///< t_s − t_from, s
  double at{0.0};             ///< t_s, s
  double initial_error{0.0};  ///< A0, m
  double final_error{0.0};    ///< |dp − dp_ref| at the last sample in the window, m
  double frequency_hz{0.0};   ///< ω/2π of the projected error (0: no oscillation)
  double damping_ratio{0.0};  ///< equivalent ζ (0 when not settled or no oscillation)
};
Settling settling(const std::vector<TransientSample>& samples, const Vec3& dp_ref, double t_from,
                  double t_to, double tol);

}  // namespace roprec::nc
