#pragma once
/// \file prediction.hpp
/// Per-hole prediction: where the robot really drills, with what uncertainty, and whether the
/// hole meets its position tolerance (Ferreras-Higuero et al., RCIM 2020; docs/process.md §5).
///
/// For a programmed hole (TCP pose T_W_tcp at the drill point, tool +z = drilling direction):
///  1. IK: the solution the program's configuration selects; without one (hole lists) the
///     in-limit, non-singular solution nearest the seed (the previous hole's joints, else the
///     vendor's reference pose) — continuity, so no flips are introduced by the choice.
///  2. δrobot: static deviation with flexible joints and servo gain under link weight, tool and
///     spindle weight (cell) and the process wrench at its maximum steady value (deflection.hpp).
///  3. δmach: the systematic machining deviation (machining_deviation.hpp; zero-mean terms only
///     add uncertainty). δwork = δrobot + δmach.
///  4. Position error e = |δwork − (δwork·a)a| ⊥ the hole axis a, and the axis tilt |δrot × a|.
///  5. Budget, per in-plane axis standard uncertainties combined by root-sum-square (GUM,
///  independent
///     terms): u_robpos = RP/3.616 (ISO 9283, uncertainty.hpp); u_robdef propagated from the
///     joint-stiffness, servo-gain and process-coefficient uncertainties (linearised — the Jacobian
///     at the deflected pose times the joint deformations — or Monte Carlo with a fixed seed);
///     u_axis, u_runout, u_deftool from the process. u_robot² = u_robpos² + u_robdef²,
///     u_mach² = Σ process terms, u_work² = u_robot² + u_mach². Expanded with the 2-D radial
///     coverage factor k = 2.4477 (95 %, Rayleigh): U_work = √(U_robot² + U_mach²).
///  6. Verdict (ISO 14253-1 guard band, position ⌀t, docs/process.md §5.4) with U = U₉₅, the
///     exact 95 % radius of the anisotropic in-plane total Σ = Σ_def + (u_robpos² + u_mach²)·I
///     (radialCoverage; U₉₅ ≥ U_work, equality for an isotropic Σ — the RSS U_work would
///     under-cover an elongated scatter by up to ~11 %). The limits are inclusive (ISO 1101):
///       conforms                     e + U ≤ t/2
///       conforms-after-compensation  U ≤ t/2 < e + U   (the systematic part is too large)
///       not-capable                  U > t/2           (the scatter alone exceeds t/2)
///       unreachable / singular       no admissible IK solution / wrist or shoulder singular;
///                                    unreachable too when the hole is deeper than the drill cuts
///                                    (ProcessAtDiameter::cutting_length): no IK, no time

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "compensator/process/machining_deviation.hpp"
#include "compensator/process/process_load.hpp"
#include "compensator/process/process_spec.hpp"
#include "compensator/robot/configuration.hpp"
#include "compensator/robot/deflection.hpp"
#include "compensator/robot/ik.hpp"
#include "compensator/support/inline_vector.hpp"

namespace roprec {

struct UncertaintyInputs {
  enum class Method { kLinear, kMonteCarlo };
  Method method{Method::kLinear};
  double stiffness_rel{0.10};      ///< relative standard uncertainty of each k_i (independent)
  double position_gain_rel{0.20};  ///< relative standard uncertainty of each servo stiffness
  double process_halfwidth{0.15};  ///< rectangular half-width of the process force scale
  int samples{400};                ///< Monte Carlo samples
  unsigned seed{20201};            ///< Monte Carlo seed (fixed: deterministic output)
  double coverage_probability{0.95};
  std::string source;
};

/// Defaults with their sources (see prediction.cpp).
UncertaintyInputs defaultUncertaintyInputs();

/// The absolute-accuracy term of the budget: how far the robot's geometry may put the TCP from
/// where the model says (docs/process.md §5). Per in-plane axis standard uncertainty, m:
///   kDataSheet        uncalibrated robot: u = AP / 2.7955 (card <accuracy ap_mm>: AP read as the
///                     95 % bound of the 3-D error of an isotropic normal error, whose magnitude is
///                     Maxwell-distributed: P(|e| ≤ 2.7955 σ) = 0.95);
///   kCalibrated       robot card <calibration>: the fit's covariance of its components (with
///                     their correlations, the calibration part's registration as the base
///                     components; each stated σ independent when the block has no
///                     <covariance>) through ∂p_tcp/∂component at the hole's pose, plus the
///                     block's model error (calibrationPositionCovariance), in-plane;
///   kControllerOption the cell declares the controller's absolute-accuracy option
///                     (<absolute_accuracy ap_mm source/>): its residual AP, as kDataSheet;
/// plus the cell's registration σ (<workobject sigma_mm>) in quadrature; kNone: no term.
struct AccuracyInputs {
  enum class Kind { kNone, kDataSheet, kCalibrated, kControllerOption };
  Kind kind{Kind::kNone};
  double u{0.0};                   ///< m per axis (kDataSheet, kControllerOption)
  double registration_sigma{0.0};  ///< m per axis (0: not stated)
  std::string source;              ///< what the term rests on (JSON, report)
};

struct CapabilityInputs {
  double mc_approach_s{2.0};  ///< machining-center positioning + approach + retract per hole
  std::string source;
};

/// The process at one hole diameter: steady wrench on the TCP, rotating force, machining deviation.
struct ProcessAtDiameter {
  double diameter{0};        ///< m
  ToolWrench wrench;         ///< tool frame
  double rotating_force{0};  ///< N
  MachiningDeviation mach;
  double feed_rate{0};      ///< m/s (feed per rev × spindle speed)
  double default_depth{0};  ///< m
  /// The deepest hole the drill cuts (cuttingLengthAt), m; 0: no limit (no drilling process).
  /// A deeper hole fails on its own (verdict unreachable, HolePrediction::beyond_drill).
  double cutting_length{0};
  std::string cutting_length_source;
};

/// Which process a hole is drilled with, resolved against the cell's tool table: the drill
/// (index into ProcessSpec::drills), the hole diameter, feed and spindle speed (units: µm, nm/rev,
/// 1/1000 min⁻¹, so that equal values compare equal).
struct HoleProcessKey {
  int drill{0};
  long diameter_um{0};
  long feed_nm{0};
  long rpm_milli{0};
  auto operator<=>(const HoleProcessKey&) const = default;
};

/// A calibrated robot (robot card <calibration>, geometry_calibration.hpp): `model` is the REAL
/// robot (robot.real_chain: every deflection, equilibrium and real TCP is computed on it) and `ik`
/// the CONTROLLER's nominal IK (programmed targets → commands, configuration flags, limits);
/// `nominal_model` is the controller's FK_nom and `real_ik` solves FK_real(θ) = target (the link
/// angles a compensation wants). Without a calibration `calibrated` is false, `model`/`ik` are
/// both nominal and real, and nominal_model/real_ik are left empty (controllerModel/realIk).
struct PredictionModel {
  Robot robot;
  nc::Model model;
  IkModel ik;
  bool calibrated{false};
  nc::Model nominal_model;
  IkModel real_ik;
  nc::JointCompliance compliance;
  Vec6 reference_pose{Vec6::Zero()};
  bool has_process{false};
  ProcessSpec process;
  std::map<long, ProcessAtDiameter> process_by_diameter;  ///< key: diameter in µm
  /// Holes drilled with another drill of the tool table, or with their own feed or spindle
  /// speed (HoleRequest::drill, feed, spindle_rpm); the cell's first drill at its own cut data is
  /// in process_by_diameter.
  std::map<HoleProcessKey, ProcessAtDiameter> process_by_hole;
  UncertaintyInputs uncertainty;
  AccuracyInputs accuracy;
  CapabilityInputs capability;
  ConfigurationOptions config_options;
  double default_tolerance{0.2e-3};  ///< m, ⌀
  bool gravity{true};
  /// How the controller's joint values relate to the loaded arm (nc::ControllerReference,
  /// docs/model.md §6.3): the absolute-accuracy option's own gravity compensation (robot card
  /// `<controller gravity_compensated>` or the cell's `<controller>`), else the mastering
  /// reference at the card's calibration pose; roprec predicts only the part beyond it.
  nc::ControllerReference controller;
  /// The model of each drill of the tool table that has its own TCP (PredictionSetup::
  /// drill_tools, ProcessSpec::drills order; null: the drill sits at this model's tool): the same
  /// robot, process and budget inputs with that TCP and tool mass. modelFor picks a hole's.
  std::vector<std::shared_ptr<PredictionModel>> drill_models;
};

struct HoleRequest;

/// The model hole `h` is predicted and compensated with: its drill's own (drill_models, the
/// first drill's for a hole nothing assigns), else `m` itself.
const PredictionModel& modelFor(const PredictionModel& m, const HoleRequest& h);
/// Whether some drill of the tool table has a TCP of its own (drill_models).
bool hasDrillModels(const PredictionModel& m);

/// The controller's kinematic model: nominal_model when calibrated, else model.
const nc::Model& controllerModel(const PredictionModel& m);
/// The IK of the real robot: real_ik when calibrated, else ik.
const IkModel& realIk(const PredictionModel& m);
/// FK_nom of the TCP at the command θ (rad): the pose the controller means (base frame).
Pose controllerTcp(const PredictionModel& m, const Vec6& theta);

/// The process at a hole diameter (m; ≤ 0: the cell's drill), nullptr without a process.
const ProcessAtDiameter* processFor(const PredictionModel& m, double diameter);

/// Gravity (unless disabled) + the process wrench in the tool frame, following the real drill axis.
nc::Loads processLoads(const PredictionModel& m, const ProcessAtDiameter* proc);

/// The controller's offset Δθ_c at command θ (nc::controllerReferenceOffset) with the model's
/// compliance, or with `c` (identification candidates, Monte Carlo samples).
Vec6 controllerOffset(const PredictionModel& m, nc::Data& data, const Vec6& theta);
Vec6 controllerOffset(const PredictionModel& m, nc::Data& data, const Vec6& theta,
                      const nc::JointCompliance& c);

/// A drill of the tool table with its own TCP (cell <drill><tcp/>): the tool attachment while it
/// is in the spindle, and the load the controller's gravity compensation then assumes.
struct DrillTool {
  nc::ToolAttachment tool;
  nc::ToolAttachment calibration_load;
};

struct PredictionSetup {
  Robot robot;
  nc::ToolAttachment tool;
  std::optional<ProcessSpec> process;
  UncertaintyInputs uncertainty = defaultUncertaintyInputs();
  AccuracyInputs accuracy;
  CapabilityInputs capability;
  double default_tolerance{0.2e-3};
  std::vector<double> hole_diameters;  ///< diameters the holes use (m); the process's is added
  /// The holes' requests whose process is not the first drill's at its cut data (every drill of
  /// the tool table at its own diameter and cut data is built anyway).
  std::vector<HoleRequest> hole_processes;
  bool controller_gravity{false};       ///< absolute-accuracy option (api::controllerGravityOf)
  nc::ToolAttachment calibration_load;  ///< load the controller's gravity compensation assumes
  /// Per drill of the tool table (ProcessSpec::drills order): its own TCP, nullopt (or a shorter
  /// list) where the drill sits at `tool` (PredictionModel::drill_models).
  std::vector<std::optional<DrillTool>> drill_tools;
};

/// Builds the model once (process evaluated per distinct diameter).
PredictionModel buildPredictionModel(const PredictionSetup& setup);

struct HoleRequest {
  std::string id;
  Pose T_W_tcp{Pose::Identity()};      ///< programmed TCP pose at the drill point, base frame
  double tolerance{0.0};               ///< ⌀ position tolerance, m (0: the cell default)
  double diameter{0.0};                ///< m (0: the process drill)
  double depth{0.0};                   ///< m (0: the process depth)
  std::optional<VendorConfig> config;  ///< the program's configuration, if it states one
  /// The flags written at the hole's targets even where the controller ignores them (linear
  /// moves): the compensation keeps them unless its target cannot be reached with them
  /// (docs/configuration.md §6). Does not steer the prediction's IK choice.
  std::optional<VendorConfig> written_config;
  int line{0};  ///< source line (messages)
  /// What made it a hole (JSON "evidence"): "feed segment along the tool axis", "call X after
  /// the motion at line N", "on the hole list"; empty for a pose a host gives (none written).
  std::string evidence;
  /// Where the hole starts: the surface point on the drill axis (base frame, m), when the
  /// program's cycle shows it (the feed starts there); T_W_tcp is the bottom (drill point).
  std::optional<Vec3> surface_W;
  /// The nominal hole (hole list): a point on its axis and the drilling direction, base frame.
  /// When given, the prediction also reports the real drill point's distance from that axis.
  std::optional<std::pair<Vec3, Vec3>> nominal_axis;
  /// Joints (URDF convention, rad) the IK choice of a hole without a configuration is nearest
  /// to; overrides the sequence's continuity seed (a host's approximate joints).
  std::optional<Vec6> ik_seed;
  /// The hole's process (docs/process.md §8, tool table): the drill of the cell's tool table (index
  /// into ProcessSpec::drills; -1: the first, i.e. the single drill of a cell without a table), and
  /// its own feed (m/rev) and spindle speed (1/min); 0: the drill's <cut> values.
  int drill{-1};
  double feed{0.0};
  double spindle_rpm{0.0};
  std::string tool;  ///< the tool key that selected `drill` (<drill tool>), for the outputs
};

/// The process fields of `h` alone (diameter, drill, feed, speed): PredictionSetup::hole_processes.
HoleRequest holeProcessOf(const HoleRequest& h);
/// The process key of a hole (its drill, diameter, feed and speed with the cell's defaults).
HoleProcessKey holeProcessKey(const PredictionModel& m, const HoleRequest& h);
/// Builds the process of hole `h` into `m` when not there yet (a host's per-call process).
void addHoleProcess(PredictionModel& m, const HoleRequest& h);
/// The process of hole `h` (addHoleProcess must have run for it, or buildPredictionModel with it
/// in PredictionSetup::hole_processes), nullptr without a process.
const ProcessAtDiameter* processFor(const PredictionModel& m, const HoleRequest& h);

enum class HoleStatus { kOk, kUnreachable, kSingular, kNotConverged };
enum class Verdict {
  kConforms,
  kConformsAfterCompensation,
  kNotCapable,
  kUnreachable,
  kSingular,
  kNotConverged
};
const char* verdictName(Verdict v);
/// "verdict: reason" for messages, without saying the verdict twice when the reason already
/// starts with it ("unreachable: the wrist centre is …").
std::string verdictAndReason(Verdict v, const std::string& reason);

/// ISO 14253-1 decision for a predicted position error e (m) with expanded radial uncertainty U
/// (m) against a ⌀t position tolerance (m): see the file comment.
Verdict verdictFor(double e, double U, double t);

/// Terms of a hole's uncertainty budget: 4 robot terms (with the absolute accuracy) + the 3
/// machining components.
inline constexpr std::size_t kMaxBudgetTerms = 7;

struct BudgetTerm {
  const char* name;
  double u{0};                  ///< per-axis standard uncertainty, m
  bool process{false};          ///< belongs to the process (for the process share)
  const char* source{nullptr};  ///< what the term rests on, when it states one (else null)
};

struct HolePrediction {
  std::string id;
  HoleStatus status{HoleStatus::kOk};
  std::string reason;
  /// Deeper than the drill cuts (status and verdict unreachable, the reason says so): not
  /// predicted, no machining-center time.
  bool beyond_drill{false};
  Vec6 joints{Vec6::Zero()};  ///< motor-side command (rigid IK of the programmed pose), rad
  std::string config;         ///< vendor flags
  int branch{0};
  double wrist_margin{0};  ///< |sin(θ5 + α)|
  nc::Deflection deflection;
  Vec3 d_robot{Vec3::Zero()};  ///< m, base frame
  Vec3 d_mach{Vec3::Zero()};
  Vec3 d_work{Vec3::Zero()};
  Vec3 d_rot{Vec3::Zero()};                         ///< rad, base frame
  Eigen::Vector2d e_tool{Eigen::Vector2d::Zero()};  ///< δwork in the tool XY plane (m)
  double position_error{0};                         ///< m, ⊥ hole axis
  double axis_tilt{0};                              ///< rad
  std::optional<double>
      nominal_axis_error;  ///< m: real drill point ⊥ distance from the nominal axis
  /// u per in-plane axis: robot repeatability, deflection model, deflection from the process
  /// force, then the machining model's components (machining_deviation.hpp: axis, runout, tool
  /// deflection) — at most kMaxBudgetTerms, stored inline (no allocation per hole).
  InlineVector<BudgetTerm, kMaxBudgetTerms> budget;
  Eigen::Matrix2d robdef_cov{Eigen::Matrix2d::Zero()};
  double u_robot{0}, u_mach{0}, u_work{0};
  double k{2.4477};
  double U_robot{0}, U_mach{0}, U_work{0};
  /// The exact 95 % radius of the anisotropic in-plane total (JSON `U_work_anisotropic`): the U
  /// of the verdict. ≥ U_work (equal only for an isotropic total), see the file comment.
  double U_work_exact{0};
  double process_share{
      0};  ///< machining-process variance share u_mach² / u_work² (the study's figure)
  double process_force_share{
      0};               ///< share of the robot deflection caused by process-force uncertainty
  double tolerance{0};  ///< ⌀, m
  Verdict verdict{Verdict::kConforms};
  double mc_time{0};  ///< machining-center time for this hole, s
  double diameter{0};
  double depth{0};
  int drill{0};                   ///< index into the cell's tool table (ProcessSpec::drills)
  double feed{0};                 ///< m/rev (0: no drilling process)
  double spindle_rpm{0};          ///< 1/min
  Vec3 force_base{Vec3::Zero()};  ///< process force on the TCP, base frame, N
};

struct PredictionData {
  explicit PredictionData(const PredictionModel& m);
  nc::Data nc;
  IkResult ik;
  std::mt19937 rng;
};

/// Predicts one hole. `seed` (rad) steers the default IK choice; nullptr: the reference pose.
HolePrediction predictHole(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                           const Vec6* seed);
/// The same into `out`, reusing its strings' storage (the budget is inline): no heap allocation
/// per hole once `out` has held a prediction (linear budget; the Monte Carlo budget allocates its
/// samples). A fresh prediction allocates only for strings beyond the short-string buffer.
void predictHole(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                 const Vec6* seed, HolePrediction& out);

/// Step 1 of predictHole alone (the IK choice) into `out`: status and reason, joints, branch,
/// wrist margin and flags, and the hole's process figures (tolerance, diameter, depth, drill, feed,
/// speed, machining-center time) — no deflection, no budget, no verdict beyond a failed IK. The
/// same values as predictHole's for them.
void chooseHoleSolution(const PredictionModel& m, PredictionData& d, const HoleRequest& h,
                        const Vec6* seed, HolePrediction& out);

/// δrobot of hole `h` at a known command `joints` (rad): predictHole's step 2 alone (the compliance
/// equilibrium under gravity, tool weight and the hole's process wrench, the controller's offset
/// applied, referred to the controller's pose when calibrated) without the IK choice, the budget or
/// the verdict. The same bits as predictHole's d_robot when its IK chooses `joints`; nullopt when
/// the equilibrium does not converge.
std::optional<Vec3> robotDeviationAt(const PredictionModel& m, PredictionData& d,
                                     const HoleRequest& h, const Vec6& joints);

/// The IK choice of a sequence of holes (predictHoles' first step: per hole, in order, the
/// solution nearest the previous admissible one; `chosen[i]` 0: none, the hole is predicted from
/// its seed alone), in storage the caller owns: one entry per hole.
struct IkChoice {
  std::span<IkSolution> sol;
  std::span<char> chosen;
  /// false: predictHoles makes the choice and writes it here; true: it was made by a call for
  /// the same holes, model and PredictOptions::seed, and is not made again (the same result, bit
  /// for bit: a caller predicting the holes twice keeps it between the calls).
  bool given{false};
};

struct PredictOptions {
  /// Worker threads over holes (≥ 1; 1: the calling thread only). The output is byte-identical
  /// for every count: a sequential pass fixes the IK choice that seeds each next hole (the
  /// analytic IK candidates it chooses from, which do not depend on the seed, computed on the
  /// workers first: ikCandidates), the rest of each hole runs on the workers with per-thread
  /// scratch.
  int threads{1};
  /// Continuity seed before the first hole (the last admissible joints of a previous block, rad):
  /// predicting a sequence block by block with it gives the same result as in one call.
  std::optional<Vec6> seed;
  /// false: each hole up to its compliance equilibrium only — status, reason, joints, branch,
  /// flags, the hole's figures and the deflection, the same values as with it — without δwork,
  /// the uncertainty budget and the verdict (a caller that reads only which solution each hole
  /// takes and whether it is predicted).
  bool budget{true};
  /// Where the IK choice goes or comes from (IkChoice); empty: predictHoles' own.
  IkChoice choice{};
};

/// Predicts a sequence, each hole seeded with the previous admissible solution.
std::vector<HolePrediction> predictHoles(const PredictionModel& m,
                                         std::span<const HoleRequest> holes);
std::vector<HolePrediction> predictHoles(const PredictionModel& m,
                                         std::span<const HoleRequest> holes,
                                         const PredictOptions& options);
/// The same into storage the caller owns: hole i's prediction is written into at(i), a
/// default-constructed HolePrediction (compensateHoles: each hole's `before`, no second array of
/// predictions to fill and move). at(i) is called from the workers when options.threads > 1: it
/// must give distinct objects for distinct i and be safe to call at once.
void predictHoles(const PredictionModel& m, std::span<const HoleRequest> holes,
                  const PredictOptions& options, const std::function<HolePrediction&(size_t)>& at);

struct CapabilitySummary {
  int holes{0};
  int conforms{0}, conforms_after_compensation{0}, not_capable{0}, unreachable{0}, singular{0},
      not_converged{0};
  int robot_can_take{0};    ///< conforms + conforms-after-compensation
  double mc_time_taken{0};  ///< s of machining-center time the robot can take
  double mc_time_total{0};
  double max_process_share{0};
  double mean_process_share{0};
};
CapabilitySummary summarize(const std::vector<HolePrediction>& p);

/// summarize() over holes given one at a time (a streamed prediction): the same operations in the
/// same order, so the same bits.
class SummaryAccumulator {
 public:
  void add(const HolePrediction& h);
  [[nodiscard]] CapabilitySummary summary() const;

 private:
  CapabilitySummary s_;
  double share_sum_{0};
  int share_n_{0};
};

}  // namespace roprec
