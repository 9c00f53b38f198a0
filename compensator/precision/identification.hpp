#pragma once
/// \file identification.hpp
/// Shop-floor verification and re-identification from measured holes: residuals of
/// the measured holes against the prediction, a regularised Levenberg–Marquardt identification of
/// the joint compliances on the full nonlinear flexible-joint model, the verification statistics
/// (coverage of U_work, ISO 14253-1 decision on the measured value), and a D-optimal test-program
/// planner. Free functions over the PredictionModel (prediction.hpp); nothing here prints.
///
/// ## Frames and units
/// SI throughout (m, rad, N·m/rad, kg). W = robot base frame. For a hole, T_W_hole is the
/// **nominal** hole pose: origin = the nominal drill point, z = the drilling direction (into the
/// material), x/y = the in-plane basis (e₁, e₂) every 2-D quantity is expressed in. The workobject
/// frame T_W_wobj is the frame the CMM's positions are given in (after the part alignment).
///
/// ## The model of a measured hole
/// For the command θ_cmd (motor side: what the controller was given) and a parameter vector x:
///
///   θ(x)   solves θ = θ_cmd + Δθ_ctrl(θ_cmd) − C_eff(x) τ(θ)          (deflection.hpp, re-solved
///                                                                      at every evaluation)
///   p̂_W(x) = FK_tcp(θ(x)) + δmach                                     (real drill point)
///   m̂_W(x) = T_W_wobj · ( R(ω) · (T_W_wobj⁻¹ · p̂_W(x)) + t )          (registration)
///   r_i(x) = [e₁ e₂]ᵀ (p_W,measured − m̂_W(x)) / σ_i  ∈ ℝ²              (⊥ the nominal axis)
///
/// A measured point (tracker) has all three axes of T_W_hole as rows; with a measured orientation
/// R_W,measured three more: with R̂_W(x) the real TCP orientation (FK_cal at θ(x)) seen through the
/// registration, R_W_wobj R(ω) R_W_wobjᵀ R̂_W(x),
///   r_i,rot(x) = R_W_holeᵀ vee(log(R_W,measured · (R_W_wobj R(ω) R_W_wobjᵀ R̂_W(x))ᵀ)) / σ_rot,i
/// (the small rotation from the predicted to the measured orientation, rad).
///
/// with C_eff = diag(c_eff,j), c_eff,j = 1/k_j + 1/k_servo,j the **effective** compliance (joint
/// and servo in series). τ includes link, tool and spindle weight and the process wrench of the
/// hole's diameter following the real drill axis (processLoads). Δθ_ctrl = C_eff τ_g,cal(θ_cmd)
/// is the offset of a gravity-compensating controller (PredictionModel::controller_gravity),
/// computed — as everywhere in roprec — with the same compliance. The along-axis component of
/// p_measured − m̂ is not used (it holds the CMM's probing depth, not the robot's error).
///
/// Static holes see only c_eff,j: the joint and servo compliances of one joint cannot be told
/// apart (their sum enters every equation), so the servo keeps its prior and the identified
/// joint stiffness is k_j = 1/(c_eff,j − 1/k_servo,j).
///
/// ## Parameters x (dimensionless or SI, see IdentifiedParameter::unit)
///   x_j = c_eff,j / c_eff,j⁰ (j = 1..6, relative to the card), prior 1 ± s_j (s_j: 50 % for an
///   `estimate:` source, 10 % for an identified or measured one — compliancePriorSigma);
///   optionally Δm_tool (kg) and Δcom_tool (m, flange frame), prior 0 ± σ;
///   optionally the registration t (m, workobject axes) and ω (rad, small-angle rotation vector
///   about the workobject origin, R(ω) exact), prior 0 ± weak σ.
///
/// ## Estimation (regularised Gauss–Newton / Levenberg–Marquardt)
///   minimise  F(x) = Σ_i ‖r_i(x)‖² + Σ_k ((x_k − x⁰_k)/σ⁰_k)²
///   J_d = ∂r/∂x by central differences (steps in IdentificationOptions; registration columns
///   reuse the robot prediction), J_w = [J_d; diag(1/σ⁰)],
///   step (J_wᵀJ_w + λ diag(J_wᵀJ_w)) Δx = −J_wᵀ r_w, λ ×10 on a rejected step, ÷10 on an accepted
///   one; converged when max_k |Δx_k|/σ⁰_k ≤ step_tolerance (or ≤ 100 × step_tolerance when no
///   step lowers F any more: the rounding floor of the 1e-12 rad equilibrium).
///   Posterior covariance P = (J_wᵀ J_w)⁻¹ at the solution (prior rows included).
///   Identifiability of x_k: ratio ρ_k = √P_kk / σ⁰_k with every parameter free (1 = the data add
///   nothing). Parameters with ρ_k > identifiable_ratio are **not identifiable**: they are fixed at
///   their prior and the others re-estimated without them. The fixed ones are "consider"
///   parameters: their prior covariance S_f is carried into the estimated ones through the
///   estimate's sensitivity G = A_aa⁻¹ J_aᵀ J_f (A_aa = J_wᵀJ_w on the estimated columns):
///     P_aa = A_aa⁻¹ + G S_f Gᵀ,  P_af = −G S_f,  P_ff = S_f,
///   so fixing a parameter the data see a little does not make the others overconfident.
///   Bounds inside the fit (projected Levenberg–Marquardt: each trial point is projected onto the
///   box before its cost is evaluated, and the convergence test uses the projected step): every
///   effective compliance stays ≥ c_servo,j + 1e-3 (c0_j − c_servo,j) (a joint at most 1000 ×
///   stiffer than its card, never stiffer than its servo); the geometry within ±5 mm / ±20 mrad.
///   A compliance that ends on its bound (the data want it non-physical) is reported in
///   `message` and the card keeps that joint's stiffness.
///   Condition number: of the data-only normal matrix J_dᵀJ_d of the identifiable parameters at
///   the estimate, its columns scaled to unit norm (λ_max/λ_min). A large value (≳ 1e8) says that
///   a combination of them is fixed only by the priors — e.g. a rigid registration from holes on
///   two plane faces: the rotation about the faces' common direction moves each face like a
///   translation, exactly.
///   Deterministic: no random numbers, fixed iteration order.
///
/// ## Verification (per hole; ISO 14253-1 at the measurement stage)
///   e_meas = [e₁ e₂]ᵀ (p_measured − p_nominal)    measured deviation ⊥ the axis
///   δ̂      = [e₁ e₂]ᵀ (p̂ − p_nominal)            predicted δwork⊥
///   r      = e_meas − δ̂                          residual
///   inside ⇔ |r| ≤ R₉₅(Σ_work + u_meas² I)        the predicted 95 % region of the residual
///   (Σ_work the prediction's 2-D covariance of the real hole: deflection-model, repeatability and
///   process terms; the measurement's own scatter is added because r contains it)
///   U_meas = 2.4477 u_meas (2-D radial, 95 %); decision for ⌀t:
///     conformance proven      |e_meas| + U_meas ≤ t/2
///     non-conformance proven  |e_meas| − U_meas > t/2
///     no decision             otherwise
///   Summary: RMS/mean/max of |e_meas|, |δ̂|, |r|; explained share 1 − RMS(r)/RMS(e_meas);
///   coverage = fraction inside; Pearson correlation of δ̂ and e_meas per axis of a frame.
///
/// ## Test planning (D-optimal)
///   Information of a candidate hole: J_iᵀJ_i with J_i the 2×n data Jacobian (σ-weighted) at the
///   prior; M = Σ_chosen J_iᵀJ_i + diag(1/σ⁰²). Greedy: add the candidate maximising
///   log det M_cc|n — the compliance block after eliminating the nuisance (registration)
///   parameters, log det M − log det M_nn — until N are chosen. Without nuisance log det M is
///   submodular: the greedy is lazy (each candidate's last gain bounds its next in a max-heap;
///   only the top is evaluated again), with the choice of a scan over all candidates. Expected
///   posterior σ of x_j: √((M⁻¹)_jj).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/prediction.hpp"

namespace roprec {

// ---------------------------------------------------------------- identification

/// One measured hole as the identification sees it.
struct IdentificationHole {
  std::string id;
  Vec6 theta_cmd{Vec6::Zero()};  ///< commanded (motor-side) joints, URDF convention, rad
  Pose T_W_hole{
      Pose::Identity()};  ///< nominal hole: drill point, z = drilling direction; base frame
  double diameter{0.0};   ///< m (0: the process drill): selects the process wrench and δmach
  /// The hole's drill of the cell's tool table and its own feed (m/rev) and spindle speed (1/min)
  /// (HoleRequest::drill, feed, spindle_rpm; -1 and 0: the first drill at its cut data): with
  /// `diameter` they select the process wrench and δmach (processFor).
  int drill{-1};
  double feed{0.0};
  double spindle_rpm{0.0};
  Vec3 p_W_measured{Vec3::Zero()};  ///< measured hole position, base frame (via the workobject), m
  double sigma{5e-6};  ///< standard uncertainty per in-plane axis of measured − predicted, m
                       ///< (residualSigma: measurement, repeatability, machining)
  /// A measured TCP point (laser tracker, CMM probe on the flange) rather than a drilled hole:
  /// all three components of measured − predicted are equations (T_W_hole's axes), and there is
  /// no δmach. The TCP is the point measured (the reflector's centre on the cell's tool).
  bool point{false};
  /// A point's measured TCP orientation (base frame), when the tracker measured it (a 6-DoF
  /// probe): three more equations, the small-angle rotation from the predicted to the measured
  /// orientation, ω = vee(log(R_measured · R̂ᵀ)) in T_W_hole's axes, each over sigma_rotation.
  std::optional<Mat3> R_W_measured;
  double sigma_rotation{100e-6};  ///< standard uncertainty per axis of ω, rad
  /// The loads at this observation when they are not the drilling process's at `diameter`
  /// (a tracker point: gravity plus the payload/wrench of its row). nullopt: processLoads.
  std::optional<nc::Loads> loads;
  /// The tool at this observation when it is not the model's (the cell's tool plus a payload of
  /// a pose-file row): the model is rebuilt with it once. Not combinable with an identified tool.
  std::optional<nc::ToolAttachment> tool;
};

/// Position rows of an observation's residual: 2 for a hole (⊥ its axis), 3 for a point.
inline int observationRows(const IdentificationHole& h) { return h.point ? 3 : 2; }
/// Orientation rows: 3 for a point with a measured orientation, else 0.
inline int orientationRows(const IdentificationHole& h) {
  return h.point && h.R_W_measured ? 3 : 0;
}

/// Which robot parameter groups the identification may move (the registration is always
/// estimated when asked): `all` = compliances and (when the options carry a geometry prior)
/// geometry; `none` = the robot kept at its card (only the registration is estimated — the
/// baseline of the original card in the held-out validation).
enum class IdentifySet { kAll, kStiffness, kGeometry, kNone };
/// "all", "stiffness", "geometry", "none".
const char* identifySetName(IdentifySet s);
std::optional<IdentifySet> identifySetFromName(const std::string& name);

enum class Registration { kNone, kTranslation, kRigid };
/// "none", "translation", "rigid".
const char* registrationName(Registration r);
/// Parses a registration name; nullopt when unknown.
std::optional<Registration> registrationFromName(const std::string& name);

struct IdentificationOptions {
  IdentifySet identify{IdentifySet::kAll};
  Vec6 compliance_prior_rel{Vec6::Constant(0.5)};  ///< s_j: relative σ of each prior c_eff,j
  Registration registration{Registration::kNone};
  Pose T_W_wobj{Pose::Identity()};  ///< workobject frame (registration origin and axes), base frame
  double translation_prior{5e-3};   ///< m, σ of each registration translation (weak)
  double rotation_prior{10e-3};     ///< rad, σ of each registration rotation (weak)
  /// Tool mass and centre of mass: identified when set — to the tool the PredictionModel was
  /// built with (the cell's). The model is rebuilt with the candidate tool at every evaluation; a
  /// gravity-compensating controller keeps the calibration load it was configured with.
  std::optional<nc::ToolAttachment> tool;
  /// Identify the robot's geometry too (geometry_calibration.hpp): per joint origin δxyz (m) and
  /// δrpy (rad; about the joint axis = its zero offset) and the tip (flange) error, relative to
  /// the nominal URDF. Prior: the card's <calibration> values (0 without one), σ the card's stated
  /// σ, else the data-sheet class values below. The base error is not a parameter: it is exactly
  /// joint 1's origin error (folded into it), and it keeps the card's value.
  /// Inside the fit each component stays within ±5 mm / ±20 mrad (a step leaving the box is
  /// rejected and the damping raised).
  bool geometry{false};
  double geometry_xyz_prior{0.3e-3};  ///< m: link length/offset errors 0.1–0.5 mm (calibration.md)
  double geometry_rpy_prior{0.5e-3};  ///< rad: zero offsets 0.2–0.9 mrad, axis errors 0.1–1 mrad
  double geometry_xyz_step{1e-6};     ///< m
  double geometry_rpy_step{1e-6};     ///< rad
  /// Exact dependencies: the prior-scaled data Jacobian J_d·diag(σ⁰) at the prior is factorised
  /// (QR) column by column in priority order — registration (the part's, never the robot's),
  /// compliances, tool, geometry — and a column of which less than dependency_tolerance of its
  /// norm lies outside the span of the columns kept before it is a linear combination of them
  /// (joint-1 origin vs registration, joint-6 origin vs tip, …): it keeps its prior (a consider
  /// parameter) and the combination is reported.
  double dependency_tolerance{1e-6};
  double tool_mass_prior{2.0};  ///< kg, σ of Δm_tool
  double tool_com_prior{0.02};  ///< m, σ of each Δcom_tool component
  // central-difference steps
  double relative_step{1e-4};     ///< on x_j (relative compliance)
  double translation_step{1e-6};  ///< m
  double rotation_step{1e-6};     ///< rad
  double mass_step{1e-3};         ///< kg
  double com_step{1e-5};          ///< m
  int max_iterations{30};
  double step_tolerance{1e-6};     ///< on max |Δx_k| / σ⁰_k
  double identifiable_ratio{0.9};  ///< ρ_k above this: not identifiable, keeps the prior
};

/// s_j per joint from the card's sources: `estimate_rel` for a joint whose source is an estimate
/// (JointCard::estimated), `known_rel` otherwise (identified or measured).
Vec6 compliancePriorSigma(const RobotCard& card, double estimate_rel = 0.5, double known_rel = 0.1);

struct IdentifiedParameter {
  std::string name;  ///< c1..c6, tool_mass, tool_com_x/y/z, reg_tx/ty/tz, reg_rx/ry/rz
  std::string unit;  ///< "rad/(N m)", "kg", "m", "rad"
  double prior{0};   ///< prior value (for c_j: the card's c_eff,j; for Δ terms 0)
  double prior_sigma{0};
  double value{0};  ///< estimate (the prior when not identifiable)
  double sigma{0};  ///< posterior standard uncertainty
  double ratio{1};  ///< ρ = σ_posterior / σ_prior from the estimate with every parameter free
  bool identifiable{false};
};

struct RegistrationEstimate {
  Registration kind{Registration::kNone};
  Vec3 translation{Vec3::Zero()};  ///< t, m, workobject axes
  Vec3 rotation{Vec3::Zero()};     ///< ω, rad, rotation vector about the workobject origin
  Vec3 translation_sigma{Vec3::Zero()};
  Vec3 rotation_sigma{Vec3::Zero()};
  /// The model maps a robot position to the measured one: m = T_W_wobj (R(ω) T_W_wobj⁻¹ p + t).
  /// This is the inverse: a measured position (base frame) in the robot's frame.
  [[nodiscard]] Vec3 unregister(const Pose& T_W_wobj, const Vec3& p_W_measured) const;
};

struct IdentificationResult {
  bool converged{false};  ///< LM met the step tolerance (non-convergence is a value)
  int iterations{0};      ///< LM iterations, both passes
  std::string message;    ///< why not converged / notes
  int holes{0};
  std::vector<IdentifiedParameter> parameters;  ///< c1..c6 first, then tool, then registration
  Eigen::MatrixXd covariance;  ///< posterior covariance in parameter units, order of `parameters`
  double condition_number{0};  ///< scaled data-only normal matrix of the identifiable parameters
  nc::JointCompliance compliance;  ///< the model's compliance with the identified joints
  Vec6 k_sigma{
      Vec6::Zero()};  ///< σ of k_j (first order σ_c k²), N m/rad; prior σ if not identified
  std::array<bool, 6> joint_identified{};
  std::optional<double> tool_mass;  ///< kg (identified tool mass) when the tool was identified
  std::optional<Vec3> tool_com;     ///< m, flange frame
  RegistrationEstimate registration;
  /// With IdentificationOptions::geometry: the identified geometric errors (non-identifiable
  /// components at their prior), σ from the posterior covariance; base = the card's; its
  /// covariance = the posterior covariance of the geometry and the registration together, the
  /// registration stated as the base components (consider parameters and correlations included:
  /// the budget's calibrated accuracy term).
  std::optional<GeometryCalibration> geometry;
  /// Parameters removed as exact linear combinations of the others, each as
  /// "name ≡ coefficient × name + …" in prior-σ units (largest three terms).
  std::vector<std::string> dependencies;
  /// Final measured − predicted per observation, m: ⊥ axis (e₁, e₂) for a hole, (x, y, z) of
  /// T_W_hole's axes for a point.
  std::vector<Eigen::VectorXd> residuals;
  /// Final orientation residual ω per observation (rad, T_W_hole's axes; zero without a measured
  /// orientation).
  std::vector<Vec3> rotation_residuals;
  double rms_prior{0};  ///< RMS |measured − predicted| with the card (and no registration), m
  double rms_final{0};  ///< the same at the estimate, m
  /// Goodness of fit: χ² = Σ (residual/σ)² over the equations at the estimate; dof = equations −
  /// estimated parameters (identifiable ones).
  double chi2{0};
  int equations{0};
  int dof{0};
  /// σ-weighted data Jacobian ∂r/∂x of the estimated parameters at the estimate (rows as the
  /// residuals, internal units): what the fit could absorb (fit_validation.hpp). Empty when it
  /// could not be evaluated.
  Eigen::MatrixXd jacobian;
};

/// Identifies the effective joint compliances (and optionally the tool and the registration)
/// from measured holes; see the file comment. Throws InputError("", 0, …) when there are no holes
/// or a σ is not positive, and when the model cannot be evaluated at the card's values (the
/// equilibrium or the position problem fails at a hole: its id is named). Non-convergence of
/// the LM iteration is a value (IdentificationResult::converged).
IdentificationResult identifyStiffness(const PredictionModel& m,
                                       const std::vector<IdentificationHole>& holes,
                                       const IdentificationOptions& options);

/// Measured − predicted (m, per observation as IdentificationResult::residuals) of `holes` with
/// the parameters of `r` (an identification of the same model and options on other holes): the
/// held-out residuals of a validation. Throws InputError("", 0, …) naming an observation whose
/// equilibrium fails.
std::vector<Eigen::VectorXd> residualsAt(const PredictionModel& m, const IdentificationResult& r,
                                         const std::vector<IdentificationHole>& holes,
                                         const IdentificationOptions& options);

/// The orientation residuals ω (rad, as IdentificationResult::rotation_residuals) of `holes`
/// with the parameters of `r`, as residualsAt: zero for an observation without a measured
/// orientation.
std::vector<Vec3> rotationResidualsAt(const PredictionModel& m, const IdentificationResult& r,
                                      const std::vector<IdentificationHole>& holes,
                                      const IdentificationOptions& options);

/// The σ to give an IdentificationHole: the scatter of measured − predicted that the
/// identification does not model, per in-plane axis: √(u_meas² + u_robpos² + u_mach²) (the
/// measurement, the robot's repeatability and the machining terms of the hole's prediction; the
/// deflection-model terms are what is being estimated). m.
double residualSigma(const HolePrediction& p, double u_measurement);

/// The geometry prior of a model: its card's <calibration> (zero without one).
GeometryCalibration cardGeometry(const PredictionModel& m);

/// `m` with the identified compliance (and tool, when identified) for predict/compensate.
PredictionModel withIdentification(const PredictionModel& m, const IdentificationResult& r,
                                   const std::optional<nc::ToolAttachment>& tool = std::nullopt);

/// Predicted real hole position p̂_W = FK_tcp(θ) + δmach (base frame, m) for the command θ_cmd
/// under the model's compliance, loads and controller: the quantity the identification fits.
/// Throws InputError("", 0, …) when the equilibrium does not converge.
Vec3 predictedHolePosition(const PredictionModel& m, nc::Data& data, const Vec6& theta_cmd,
                           double diameter);

// ---------------------------------------------------------------- verification

/// ISO 14253-1 decision on a measured position error at the measurement stage.
enum class MeasuredDecision { kConformanceProven, kNonConformanceProven, kNoDecision };
/// "conformance-proven", "non-conformance-proven", "no-decision".
const char* measuredDecisionName(MeasuredDecision d);
/// e: measured radial deviation (m), U_meas: expanded measurement uncertainty (m), t: ⌀ tolerance
/// (m).
MeasuredDecision measuredDecision(double e, double U_meas, double t);

/// 2-D radial coverage factor for 95 % (Rayleigh): U_meas = kRadial95 · u_meas.
constexpr double kRadial95 = 2.4477;

struct VerificationInput {
  std::string id;
  Pose T_W_hole{Pose::Identity()};   ///< nominal hole (base frame)
  Vec3 p_W_measured{Vec3::Zero()};   ///< measured position (base frame, registration removed), m
  double u_measurement{0};           ///< standard measurement uncertainty per axis, m
  Vec3 p_W_predicted{Vec3::Zero()};  ///< predicted real hole p̂_W (real TCP + δmach), m
  Eigen::Matrix2d cov_work{
      Eigen::Matrix2d::Zero()};  ///< predicted 2-D covariance of the real hole ⊥ axis, m²
  double U_work{0};              ///< the prediction's expanded uncertainty (reported), m
  double tolerance{0};           ///< ⌀ position tolerance, m
};

/// From a hole's prediction (status kOk): p̂_W = deflection.T_real + δmach, Σ_work = robdef_cov +
/// (u_robpos² + u_mach²) I, U_work and the tolerance as predicted.
VerificationInput verificationInput(const HolePrediction& p, const Pose& T_W_hole,
                                    const Vec3& p_W_measured, double u_measurement);

struct HoleVerification {
  std::string id;
  Eigen::Vector2d e_meas{Eigen::Vector2d::Zero()};  ///< measured deviation ⊥ axis (e₁, e₂), m
  double e_meas_norm{0};
  double e_along{0};  ///< along-axis measured deviation (reported only), m
  Eigen::Vector2d d_pred{Eigen::Vector2d::Zero()};  ///< predicted δwork⊥, m
  double d_pred_norm{0};
  Eigen::Vector2d r{Eigen::Vector2d::Zero()};  ///< residual e_meas − δ̂, m
  double r_norm{0};
  Vec3 e_meas_W{Vec3::Zero()};  ///< e_meas as a base-frame vector
  Vec3 d_pred_W{Vec3::Zero()};  ///< δ̂ as a base-frame vector
  double U_work{0};             ///< as predicted, m
  double U_region{0};           ///< R₉₅(Σ_work + u² I): what |r| is checked against, m
  bool inside{false};
  double U_meas{0};  ///< kRadial95 · u, m
  double tolerance{0};
  MeasuredDecision decision{MeasuredDecision::kNoDecision};
};

HoleVerification verifyHole(const VerificationInput& in);

struct MagnitudeStats {
  double rms{0}, mean{0}, max{0};  ///< of the norms, m
};

struct VerificationSummary {
  int holes{0};
  MagnitudeStats measured, predicted, residual;
  double explained{0};  ///< 1 − RMS(r)/RMS(e_meas) (0 when RMS(e_meas) = 0)
  int inside{0};
  double coverage{0};  ///< inside / holes
  /// Pearson correlation of δ̂ and e_meas along each axis of the frame given to summarize
  /// (NaN when an axis has no variance).
  Vec3 correlation{Vec3::Zero()};
  int conformance_proven{0}, nonconformance_proven{0}, no_decision{0};
};

/// Statistics over holes; correlations along the axes of R_W_frame (e.g. the workobject's).
VerificationSummary summarizeVerification(const std::vector<HoleVerification>& holes,
                                          const Mat3& R_W_frame = Mat3::Identity());

// ---------------------------------------------------------------- test planning

struct PlanOptions {
  Vec6 compliance_prior_rel{Vec6::Constant(0.5)};
  double sigma{5e-6};  ///< expected σ per in-plane axis of a residual, m
  Registration registration{
      Registration::kNone};  ///< nuisance parameters eliminated in the criterion
  Pose T_W_wobj{Pose::Identity()};
  double translation_prior{5e-3};
  double rotation_prior{10e-3};
  double relative_step{1e-4};
  double min_spacing{0.02};  ///< m: holes closer than this to a chosen one are not candidates
  /// Plan for the geometry too (IdentificationOptions::geometry, priors as there): the criterion
  /// is then over compliances + geometry, the registration still the nuisance.
  /// Inside the fit each component stays within ±5 mm / ±20 mrad (a step leaving the box is
  /// rejected and the damping raised).
  bool geometry{false};
  double identifiable_ratio{0.9};  ///< expected ρ above this: reported as unobservable
};

struct TestPlan {
  std::vector<int> chosen;    ///< candidate indices, in selection order
  std::vector<int> rejected;  ///< candidates without an admissible prediction
  std::vector<std::string> rejected_reason;
  Vec6 prior_sigma_rel{Vec6::Zero()};     ///< s_j
  Vec6 expected_sigma_rel{Vec6::Zero()};  ///< expected posterior σ(c_j)/c_j with the chosen holes
  Vec6 expected_sigma_k{Vec6::Zero()};    ///< the same as σ of k_j, N m/rad (first order)
  double log_det{0};                      ///< final criterion value
  /// Every parameter (IdentifiedParameter names): prior σ and the expected posterior σ with the
  /// chosen holes (internal units: relative for c_j, m / rad otherwise).
  std::vector<std::string> names;
  Eigen::VectorXd prior_sigma, expected_sigma;
  /// Robot parameters whose expected ρ = σ/σ_prior exceeds identifiable_ratio (they would keep
  /// their prior) or that are exact combinations of others (IdentificationResult::dependencies).
  std::vector<std::string> unobservable;
  std::vector<std::string> dependencies;
  /// Predicted accuracy after calibration: RMS over the admissible candidates of the standard
  /// uncertainty of the predicted in-plane position (√trace of J C Jᵀ, 2-D) with the expected
  /// covariance C of all parameters, the registration included (the next part in the same
  /// fixture: robot and registration are used together, as `verify --write-cell` writes them) —
  /// what a calibrated model still does not know. m.
  double predicted_accuracy{0};
  /// Before calibration: the same with the robot parameters' prior covariance alone. m.
  double prior_accuracy{0};
};

/// Greedy D-optimal choice of `count` holes among `candidates` (each predicted with predictHole:
/// the configuration the request states, else the IK solution nearest the vendor's reference
/// pose; unreachable/singular ones are rejected with their reason). Deterministic (ties go to the
/// lower index). Throws InputError("", 0, …) when count < 1, when fewer than `count` candidates
/// are admissible, or when the equilibrium fails at a candidate.
TestPlan planTest(const PredictionModel& m, const std::vector<HoleRequest>& candidates, int count,
                  const PlanOptions& options);

/// The greedy D-optimal selection of planTest: `count` of the candidates, candidate i being rows
/// 2i and 2i + 1 of the σ-weighted data Jacobian J (2 · candidates × n parameters, prior σ s0),
/// each step the one of the largest gain of the D_s criterion log det M − log det M_nn (M =
/// diag(s0)⁻² + Σ chosen Jᵢᵀ Jᵢ, the last `nn` parameters a nuisance), the lowest index among
/// equal gains. A candidate closer than `min_spacing` (m; positions p_W) to a chosen one is not
/// drillable any more (one hole per place). Returns the chosen indices in selection order, fewer
/// than `count` when the well-spaced candidates run out; `criterion` = the final D_s value.
/// Without nuisance the gains shrink as M grows: a lazy greedy re-evaluates a candidate only
/// while its last gain may still win. M grows by the rank-2 update Jᵢᵀ Jᵢ of the chosen hole.
std::vector<int> greedyDOptimal(const Eigen::MatrixXd& J, const Eigen::VectorXd& s0, int count,
                                Eigen::Index nn, const std::vector<Vec3>& p_W, double min_spacing,
                                double& criterion);

/// Candidate holes for planning: a grid of `per_axis`³ points over the box [lo, hi] (m,
/// workobject frame; an axis with lo = hi gets one point), each with every drilling direction
/// (workobject frame, normalised) and every rotation ψ about it (rad). TCP x = the workobject x
/// axis projected ⊥ the direction (y when within 26° of x), then rotated by ψ. Ids "C0001"….
std::vector<HoleRequest> planningCandidates(const Pose& T_W_wobj, const Vec3& lo, const Vec3& hi,
                                            int per_axis, const std::vector<Vec3>& directions,
                                            const std::vector<double>& psi);

}  // namespace roprec
