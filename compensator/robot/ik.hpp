#pragma once
/// \file ik.hpp
/// Inverse kinematics of spherical-wrist 6R industrial robots: all analytic solutions (8 branches
/// and the ±360° turns the joint limits allow) and a seeded Newton refinement for per-hole use.
///
/// Geometry (Brandstötter, Angerer, Hofbaur, "An analytical solution of the inverse kinematics
/// problem of industrial serial manipulators with an ortho-parallel basis and a spherical wrist",
/// Austrian Robotics Workshop 2014 — docs/programs.md §10 [S31]). The model is extracted from the
/// ChainDescription at q = 0 and requires
///   * axis 2 ∥ axis 3, both ⊥ axis 1 (the ortho-parallel basis), and
///   * axes 4, 5, 6 intersecting in one point, the wrist centre C, with axis 4 ⊥ axis 5 ⊥ axis 6.
/// Axis 4 need not be ⊥ axis 3 and no Denavit–Hartenberg frames are assumed: the solver works on
/// the geometric form of the OPW equations, which is equivalent and needs no per-robot signs or
/// offsets. The OPW parameters (a1, a2, b, c1..c4) are read out for reports (OpwParameters).
///
/// Frames: F0 has its origin o on axis 1 at the height of axis 2, z0 = axis-1 direction,
/// y0 = axis-2 direction at q = 0, x0 = y0 × z0. With u0 = P3 − P2 and v0 = C − P3 (x-z
/// components in F0, at q = 0), b = y-coordinate of C in F0 (lateral offset) and
/// Ry(θ) the rotation about +y0:
///   C(q) = o + Rz(q1) · [ P2 + Ry(q2) (u0 + Ry(σ3 q3) v0) ],        σ3 = axis3 · y0 = ±1
/// Position IK (wrist centre C from the target flange pose T: C = T · c_tip):
///   x = ±sqrt(cx² + cy² − b²)                       (shoulder front / back)
///   q1 = atan2(cy, cx) − atan2(b, x)
///   cos ψ = (|d|² − L2² − L3²) / (2 L2 L3),  d = (x − P2x, cz), L2 = |u0|, L3 = |v0|  (elbow ±)
///   q3 = σ3 (ψ − ψ0),  q2 = ang(d) − ang(u0 + Ry(ψ − ψ0) v0),  ang(v) = atan2(v_x, v_z)
/// Orientation (wrist axes w4, w5, w6 in the link-3 frame at q = 0, E = [w4, w5, w4 × w5],
/// w6 = Rot(w5, α) w4, R_w0 = rotation L3 → flange at q4 = q5 = q6 = 0):
///   Rx(q4) Ry(q5 + α) Rx(q6) = Eᵀ R_B_L3(q1..q3)ᵀ R_T R_w0ᵀ E Ry(α)      (X-Y-X Euler angles)
/// Singularities (reported per solution, with margins):
///   * wrist:    sin(q5 + α) = 0 — only q4 ± q6 is defined; q4 := seed q4 (or 0), flag
///   singular_wrist;
///   * shoulder: C on axis 1 (x = 0) — q1 := seed q1 (or 0) when undefined, flag singular_shoulder;
///   * elbow:    sin ψ = 0 (arm stretched or folded) — the two elbow branches coincide, flag
///               singular_elbow; cos ψ is clamped when the target is within 1e-9 of the boundary.
/// A URDF that deviates slightly from the ideal geometry (≤ 0.02 rad / 20 mm) is solved
/// analytically on the ideal model and refined by Newton iterations on the exact chain; larger
/// deviations are rejected at construction with an InputError naming the URDF joint.
///
/// Every returned solution is checked against the exact chain (same product as
/// chainForwardKinematics): `converged` ⇔ position residual ≤ 1e-9 m and rotation residual ≤ 1e-9
/// rad.
///
/// Branch labels (docs/programs.md §7.1), computed from the joint vector:
///   shoulder s = 0 (front) / 1 (back): sign of the x-coordinate of C in the frame rotating with
///   axis 1,
///                calibrated so that the vendor's reference pose is front;
///   elbow    e = 0 (up) / 1 (down): sign of ((P3 − P2) × (C − P3)) · axis2, calibrated so that the
///                reference pose (KUKA {0,−90,90,0,0,0}, ABB and FANUC all-zero, controller joints)
///                is up;
///   wrist    w = 0 / 1: controller θ5 wrapped to [−180°, 180°) is ≥ 0 / < 0;
///   branch = 4 s + 2 e + w (equals ABB cfx).
/// Units: SI (m, rad); poses are T_base_flange (the chain's base link to its tip link).

#include <array>
#include <cstdint>
#include <string>

#include "compensator/robot/chain.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// OPW parameters [S31] (m), read out of the geometry for reports:
/// a1 radial offset of axis 2 from axis 1 (positive towards the front), c1 height of axis 2 above
/// the base origin along axis 1, c2 = |P2P3|, c3 = component of P3→C along the forearm (axis 4), a2
/// = OPW sign convention: −(offset of C from the forearm line, positive on the side the upper arm
/// points to in the elbow-up posture), b lateral offset of C from the arm plane through axis 1, c4
/// = distance from C to the flange along axis 6.
struct OpwParameters {
  double a1{0.0};
  double a2{0.0};
  double b{0.0};
  double c1{0.0};
  double c2{0.0};
  double c3{0.0};
  double c4{0.0};
};

/// How far the chain is from the ideal OPW geometry (all zero for an exact robot).
struct IkGeometryDeviation {
  double axis12_rad{0.0};               ///< |90° − angle(axis 1, axis 2)|
  double axis23_rad{0.0};               ///< angle(axis 2, axis 3)
  double wrist_intersection_m{0.0};     ///< max distance of C from axes 4, 5, 6
  double wrist_orthogonality_rad{0.0};  ///< max |90° − angle| of (w4, w5), (w5, w6)
  bool exact{true};                     ///< all ≤ 1e-12: no refinement needed
};

/// Immutable IK model, built once from the chain (and the robot card for branch labels).
struct IkModel {
  // exact chain, for forward kinematics and refinement (same product as chainForwardKinematics)
  std::array<Mat3, 6> origin_R;
  std::array<Vec3, 6> origin_p;
  std::array<Vec3, 6> axis;  ///< unit axis in the joint frame
  std::array<int, 6>
      axis_kind{};  ///< 0/1/2: axis = ±x/±y/±z of the joint frame (fast path); -1 general
  std::array<double, 6> axis_sign{};  ///< ±1 for the fast path
  std::array<bool, 6> origin_rotation_identity{};
  Mat3 tip_R{Mat3::Identity()};
  Vec3 tip_p{Vec3::Zero()};
  Vec6 lower{Vec6::Constant(-kPi)};  ///< joint limits (rad)
  Vec6 upper{Vec6::Constant(kPi)};

  // position sub-problem (F0, see file comment)
  Vec3 o{Vec3::Zero()};                         ///< origin of F0 on axis 1, base frame
  Mat3 F0{Mat3::Identity()};                    ///< columns x0, y0, z0 in the base frame
  double p2x{0.0};                              ///< x of P2 in F0 (its z is 0 by construction)
  Eigen::Vector2d u0{Eigen::Vector2d::Zero()};  ///< (x, z) of P3 − P2 in F0 at q = 0
  Eigen::Vector2d v0{Eigen::Vector2d::Zero()};  ///< (x, z) of C − P3 in F0 at q = 0
  double b{0.0};                                ///< y of C in F0
  double L2{0.0};
  double L3{0.0};
  double psi0{0.0};          ///< ang(v0) − ang(u0)
  double sigma3{1.0};        ///< axis 3 · y0
  double reach_slack{1e-9};  ///< |cos ψ| − 1 clamped to the boundary (larger for non-ideal chains)
  Vec3 c_tip{Vec3::Zero()};  ///< wrist centre in the tip frame

  // orientation sub-problem
  Mat3 E{Mat3::Identity()};  ///< [w4 w5 w4×w5] in the link-3 frame
  Mat3 B{Mat3::Identity()};  ///< R_w0ᵀ E Ry(α)
  double alpha{0.0};         ///< w6 = Rot(w5, α) w4

  // branch labels
  double shoulder_sign{1.0};  ///< front ⇔ shoulder_sign · x ≥ 0
  double elbow_sign{1.0};     ///< up ⇔ elbow_sign · sin ψ ≥ 0
  double ctrl_sign5{1.0};     ///< controller θ5 = ctrl_sign5 · q5 + ctrl_offset5
  double ctrl_offset5{0.0};

  OpwParameters opw;
  IkGeometryDeviation deviation;
  std::string file;  ///< URDF (for messages)
};

/// Options of the model construction.
struct IkModelOptions {
  Vec6 reference_q{Vec6::Zero()};  ///< URDF joints of the vendor's elbow-up, front reference pose
  double ctrl_sign5{1.0};
  double ctrl_offset5{0.0};
};

/// Builds the model. Throws InputError (URDF file, joint line) when the chain is not a
/// spherical-wrist ortho-parallel 6R robot within the tolerated deviation, or when the reference
/// pose is itself singular.
IkModel buildIkModel(const ChainDescription& chain, const IkModelOptions& options = {});
/// Reference pose and θ5 convention from the robot card (vendor reference pose in controller
/// joints: KUKA {0,−90°,90°,0,0,0}, ABB / FANUC / generic all-zero; converted with
/// fromControllerJoints).
IkModel buildIkModel(const Robot& robot);
/// The same on robot.real_chain (geometry_calibration.hpp): the analytic solution of the ideal
/// model refined by Newton on the calibrated chain, so `converged` solutions satisfy FK_real(q) =
/// target to 1e-9. Equals buildIkModel(robot) for a robot without a calibration.
IkModel buildRealIkModel(const Robot& robot);
/// The vendor's elbow-up reference pose in URDF joints.
Vec6 vendorReferencePose(const RobotCard& card);

/// Exact forward kinematics T_base_tip(q) (same product as chainForwardKinematics).
Pose ikForwardKinematics(const IkModel& model, const Vec6& q);
/// Forward kinematics and the geometric Jacobian at the tip origin, base frame:
/// column i = [z_i × (p_tip − o_i); z_i] (rows: linear m/rad, angular rad/rad).
void ikForwardKinematicsJacobian(const IkModel& model, const Vec6& q, Pose& T, Mat6& J);

/// Residual of q against a target: position error (m) and rotation angle (rad, exact for all
/// angles).
struct IkResidual {
  double position{0.0};
  double rotation{0.0};
};
IkResidual ikResidual(const IkModel& model, const Vec6& q, const Pose& target);

/// Branch labels and singularity margins of a joint vector (URDF, rad).
struct IkBranch {
  int shoulder{0};  ///< 0 front, 1 back
  int elbow{0};     ///< 0 up, 1 down
  int wrist{0};     ///< 0: controller θ5 ≥ 0, 1: < 0
  [[nodiscard]] int index() const { return 4 * shoulder + 2 * elbow + wrist; }
  double shoulder_margin_m{0.0};  ///< |x| of the wrist centre from axis 1 (lateral offset removed)
  double elbow_margin_rad{0.0};   ///< |sin ψ|
  double wrist_margin_rad{0.0};   ///< |sin(q5 + α)|
};
IkBranch ikBranch(const IkModel& model, const Vec6& q);

/// Failure reasons of a whole IK call.
enum class IkFailure : std::uint8_t {
  kNone,
  kOutOfReach,     ///< wrist centre farther than L2 + L3 from axis 2 (both shoulders)
  kTooClose,       ///< wrist centre closer than |L2 − L3| to axis 2 (both shoulders)
  kLateralOffset,  ///< wrist centre closer to axis 1 than the lateral offset b
  kNotFinite,      ///< target pose contains NaN/Inf
};

struct IkSolution {
  Vec6 q{Vec6::Zero()};  ///< URDF joints (rad)
  IkBranch branch;
  bool within_limits{true};
  bool singular_wrist{false};
  bool singular_shoulder{false};
  bool singular_elbow{false};
  bool converged{false};  ///< residuals ≤ 1e-9 m / 1e-9 rad on the exact chain
  int iterations{0};      ///< Newton refinement iterations used
  IkResidual residual;
  std::array<std::int8_t, 6> turn{};  ///< q_i = wrapped(q_i) + 2π · turn_i
};

enum class IkTurns : std::uint8_t {
  kPrimary,  ///< per branch one solution: per joint the in-limit representative nearest the seed
             ///< (or 0)
  kAll,      ///< per branch every in-limit combination of ±360° turns
};

/// What solveIk keeps from one call to the next for solutions that share joints 1–3 to the last
/// bit (e.g. the rotations of one drill target about its axis, whose wrist centre is one point):
/// the forward kinematics up to joint 3 and the shoulder/elbow margins of the last solution,
/// reused only where joints 1–3 are the same bits, so the result is solveIk's without it, bit
/// for bit. Caller-owned scratch for one IkModel: a caller that solves with another model starts
/// a new one. No allocation.
struct IkArmCache {
  // ikForwardKinematics up to joint 3 at fk_q (joints 1–3)
  bool fk_valid{false};
  std::array<double, 3> fk_q{};
  Mat3 fk_R{Mat3::Identity()};
  Vec3 fk_t{Vec3::Zero()};
  // ikBranch's x and sin ψ at joints 2, 3
  bool branch_valid{false};
  std::array<double, 2> branch_q{};
  double branch_x{0.0};
  double branch_spsi{0.0};
};

struct IkOptions {
  IkTurns turns{IkTurns::kPrimary};
  const Vec6* seed{nullptr};       ///< resolves singular joints and the primary turn choice
  double singular_angle{1e-3};     ///< flag wrist/elbow singular when the margin (rad) is below
  double singular_distance{1e-3};  ///< flag the shoulder singular when |x| (m) is below
  int max_refine_iterations{20};
  /// Only this branch (0..7, branch = 4 s + 2 e + w) when ≥ 0: a known configuration needs one
  /// branch, not eight (its raw solution is finished and expanded alone; an exact chain skips the
  /// other branches' refinement too). −1: every branch.
  int branch{-1};
  /// Scratch kept between calls with one IkModel (null: none); solveIk only.
  IkArmCache* arm_cache{nullptr};
};

constexpr int kIkMaxTurnsPerBranch = 16;
constexpr int kIkMaxSolutions = 8 * kIkMaxTurnsPerBranch;

/// Caller-owned, fixed-capacity result (no allocation per call). Ordered by branch index, then by
/// the turn vector (lexicographic), then by q.
struct IkResult {
  std::array<IkSolution, kIkMaxSolutions> solutions;
  int count{0};
  IkFailure failure{IkFailure::kNone};  ///< set when count == 0
  double failure_value{0.0};            ///< kOutOfReach/kTooClose/kLateralOffset: the violation (m)
  bool truncated{false};                ///< more turn combinations than kIkMaxTurnsPerBranch
};

/// All analytic solutions for T_base_flange. Out-of-limit branches are kept (within_limits = false;
/// in kAll mode such a branch contributes its wrapped representative only).
void solveIk(const IkModel& model, const Pose& target, const IkOptions& options, IkResult& result);

/// The admissible solution (converged, within the limits, neither wrist- nor shoulder-singular)
/// nearest `ref` in the weighted distance Σ wᵢ (qᵢ − refᵢ)², of solveIk with seed = &ref and
/// primary turns: the same solution solveIk's list gives (ties: the first in its order). On an
/// exact chain only the candidates nearer than the best admissible one are finished (refinement
/// check, branch labels, turns): their distance is known before, since finishing keeps q there;
/// otherwise, or when finishing moved q, every branch is solved. Returns false when none is
/// admissible; `result` then holds solveIk's full list (for the reason). On success `result` is
/// scratch (count 0).
bool solveIkNearest(const IkModel& model, const Pose& target, const Vec6& ref,
                    const std::array<double, 6>& weights, IkResult& result, IkSolution& best);

/// The analytic solutions of a target before the choice (the larger part of solveIkNearest's
/// cost), computed ahead without the reference: for a sequence of targets each solved nearest
/// the previous solution, these run in parallel and only the choice runs in order. `valid` is
/// false when they depend on the reference (the wrist centre on axis 1 or a wrist-singular
/// branch: the reference picks q1 or q4 there) or when the chain is not exact (solveIkNearest
/// then solves every branch anyway): solveIkNearest then solves from the start. A few hundred
/// bytes, no allocation.
struct IkCandidates {
  std::array<Vec6, 8> q;  ///< wrapped raw solutions, in branch-construction order
  int count{0};
  IkFailure failure{IkFailure::kNone};
  double failure_value{0.0};
  bool valid{false};
};
void ikCandidates(const IkModel& model, const Pose& target, IkCandidates& candidates);
/// solveIkNearest with the candidates of the same target and model computed ahead (ikCandidates;
/// null or not valid: computed here): the same result, bit for bit.
bool solveIkNearest(const IkModel& model, const Pose& target, const Vec6& ref,
                    const std::array<double, 6>& weights, const IkCandidates* ahead,
                    IkResult& result, IkSolution& best);

/// Human-readable reason for an empty result.
std::string describeIkFailure(const IkResult& result);

/// Seeded IK for a target near a known solution (per-hole compensation): Newton on the exact chain
/// from the seed (≈ 1–2 µs for targets within a few mm / degrees); when it does not converge, the
/// analytic solution of the seed's branch with the turns nearest the seed.
struct IkNearResult {
  Vec6 q{Vec6::Zero()};
  bool converged{false};
  int iterations{0};
  IkResidual residual;
  bool analytic_fallback{false};
  bool within_limits{true};
};
struct IkNearOptions {
  int max_iterations{8};
  double max_step{0.5};     ///< rad, largest joint step per iteration (scaled down to this)
  double tolerance{1e-10};  ///< stop when both residuals (m, rad) are below (converged: ≤ 1e-9)
};
IkNearResult solveIkNear(const IkModel& model, const Pose& target, const Vec6& seed,
                         const IkNearOptions& options = {});

/// True when every joint is within its limits (with 1e-12 rad slack).
bool withinLimits(const IkModel& model, const Vec6& q);

}  // namespace roprec
