#pragma once
/// \file deflection.hpp
/// Static deviation of a robot with flexible joints and a finite servo gain, and its exact
/// inverse (the explicit compensation primitive). docs/model.md §6, docs/contract.md §2.
///
/// Joint i is a torsional spring between the motor-side angle θ_m,i (what the controller
/// commands, link side) and the link-side angle θ_i the geometry sees:
///
///   θ = θ_m + φ + Δψ_Kpos,   φ = −τ(θ)/k,   Δψ_Kpos = −τ(θ)/k_servo,
///
/// with τ(θ) the static drive torques at the **deflected** configuration (inverse_dynamics.hpp:
/// link and tool weight + TCP wrench), k the joint stiffness (N m/rad) and k_servo = Kv·Kω the
/// static stiffness of a position loop without integral action (position gain Kv in 1/s times
/// velocity gain Kω in N m s/rad, both from the robot card; absent → ideal servo, Δψ = 0).
/// The two act in series: θ = θ_m − τ(θ)/k_eff, 1/k_eff = 1/k + 1/k_servo.
///
/// Prediction solves G(θ) = θ − θ_m + τ(θ)/k_eff = 0 by Newton's method with the analytic
/// ∂G/∂θ = I + K_eff⁻¹ ∂τ/∂θ (fast_equilibrium.hpp: link frames by the forward recursion, one
/// sin/cos pair per joint and iterate, the torque sensitivity in closed form; it agrees with the
/// natural-coordinate model of record to 1e-9 relative), from θ = θ_cmd, to ‖G‖∞ ≤ tol (default
/// 1e-12 rad). ∂G/∂θ is factorised once and reused while each step contracts the residual by
/// 1000 or more (simplified Newton; it changes by O(Δθ) ≈ 1e-3 relative), re-formed otherwise:
/// two or three iterations on industrial robots. Convergence is reported as a value.
/// On return `data` is the natural-coordinate state at the deflected θ (as after solvePosition:
/// tcpJacobian, staticTorques work on it) with data.tau = τ(θ) and data.frames at θ; with
/// DeflectionOptions::natural_state false only data.frames and data.tau.
/// δrobot = FK(θ) − FK(θ_m): translation (m) and rotation vector of R_real R_nomᵀ (rad), base
/// frame; it includes the configuration-change ("complementary stiffness") effect.
///
/// Compensation is explicit: for a desired link-side θ_d and load, θ_m = θ_d + τ(θ_d)/k_eff.

#include "compensator/robot/inverse_dynamics.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec::nc {

struct JointCompliance {
  Vec6 k{Vec6::Constant(1e300)};        ///< joint stiffness, N m/rad
  Vec6 k_servo{Vec6::Constant(1e300)};  ///< servo static stiffness, N m/rad (1e300 = ideal)
  /// 1/k_eff = 1/k + 1/k_servo
  [[nodiscard]] Vec6 effective() const;
};

/// k from the card (joints without stiffness: rigid), k_servo = Kv·Kω where both gains are given
/// (otherwise an ideal, integrating servo).
JointCompliance complianceFromCard(const RobotCard& card);

struct DeflectionOptions {
  double tol{1e-12};  ///< rad, ‖Δθ‖∞
  int max_iterations{60};
  /// Leave `data` the natural-coordinate state at the deflected θ (see predictDeflection). When
  /// false only data.frames (and data.tau) are made to hold it — what the per-hole paths read
  /// (tcpJacobianFromFrames) — and the rest of `data` is stale: cheaper by the 72-coordinate sync.
  bool natural_state{true};
};

struct Deflection {
  bool converged{false};
  int iterations{0};
  double residual{0.0};  ///< ‖θ − θ_m + τ(θ)/k_eff‖∞ at exit, rad
  bool position_converged{true};
  Vec6 theta_m{Vec6::Zero()};        ///< command (rad)
  Vec6 theta{Vec6::Zero()};          ///< real link angles (rad)
  Vec6 tau{Vec6::Zero()};            ///< drive torques at θ (N m)
  Vec6 phi{Vec6::Zero()};            ///< joint deformation −τ/k (rad)
  Vec6 dpsi{Vec6::Zero()};           ///< servo correction −τ/k_servo (rad)
  Pose T_nominal{Pose::Identity()};  ///< rigid FK(θ_m) of the TCP
  Pose T_real{Pose::Identity()};     ///< FK(θ) of the TCP
  Vec3 dp{Vec3::Zero()};             ///< translation deviation, m, base frame
  Vec3 drot{Vec3::Zero()};           ///< rotation deviation (rotation vector), rad, base frame
};

/// Predicts the real TCP for the command θ_m under `loads`. `command_offset` is added to the
/// command inside the controller (e.g. its own gravity compensation) but not to the nominal.
Deflection predictDeflection(const Model& model, Data& data, const JointCompliance& c,
                             const Vec6& theta_m, const Loads& loads,
                             const DeflectionOptions& opt = {},
                             const Vec6& command_offset = Vec6::Zero());

/// A calibrated robot (geometry_calibration.hpp) is predicted on its real model, while the pose
/// the controller means by the command is its nominal FK: d.T_nominal becomes `T_controller`
/// (FK_nom(θ_m) of the TCP) and δrobot = FK_real(θ) − FK_nom(θ_m) (dp, drot as above), so the
/// deviation holds the geometric error as well as the deflection.
void referToControllerPose(Deflection& d, const Pose& T_controller);

/// Explicit inverse: the command θ_m = θ_d + τ(θ_d)/k_eff that makes the link side reach θ_d.
Vec6 compensateCommand(const Model& model, Data& data, const JointCompliance& c,
                       const Vec6& theta_d, const Loads& loads);

/// The command offset a gravity-compensating controller adds (robot card / cell <controller
/// gravity_compensated>): Δθ = K_eff⁻¹ τ_g,cal(θ), with τ_g,cal the static gravity torques of
/// `calibration_model` (the links + the load the controller was calibrated for) at θ (rad).
/// `data` may be the scratch of any model of the same chain. Non-convergence of the position
/// problem is not expected here (closed form); the torques are then those of the last iterate.
Vec6 gravityCommandOffset(const Model& calibration_model, Data& data, const JointCompliance& c,
                          const Vec6& theta);

/// What the controller's joint values mean under the arm's own weight — the "controller
/// reference" every prediction, identification, compensation, deflect and simulate uses
/// (docs/model.md §6.3). Exactly one of:
///   * absolute-accuracy option (gravity_compensated): the controller adds
///     Δθ_c = K_eff⁻¹ τ_g,cal(θ_cmd) with τ_g,cal the gravity torques (links, balancer and the
///     calibration load) at the command; its identified kinematics is the zero-gravity one, so
///     its own mastering is part of that model and no other reference applies;
///   * standard controller (mastering): the kinematics is exact at the mastering pose θ_cal under
///     the robot's own weight (no tool): the mastering offsets absorb the joint deflection there,
///     Δθ_c = K_eff⁻¹ τ_g,robot(θ_cal) (constant), so the predicted deflection is
///     θ − θ_cmd = K_eff⁻¹ (τ_g,robot(θ_cal) − τ(θ)) and vanishes at θ_cal without a tool;
///   * none (gravity not modelled, or gravity switched off for the call): Δθ_c = 0.
/// In every case the controller adds Δθ_c to the command; the nominal TCP stays FK(θ_cmd).
struct ControllerReference {
  enum class Kind { kNone, kMastering, kGravityCompensated };
  Kind kind{Kind::kNone};
  Model calibration_model;  ///< kGravityCompensated: links + balancer + calibration load
  Vec6 calibration_pose{Vec6::Zero()};         ///< kMastering: θ_cal (URDF, rad)
  Vec6 calibration_pose_torque{Vec6::Zero()};  ///< kMastering: τ_g,robot(θ_cal), N m
  /// One line for outputs (JSON "controller_reference", notes).
  [[nodiscard]] std::string description() const;
};

/// The reference of a robot: gravity_compensated → the absolute-accuracy offset with
/// `calibration_load` (tool attachment; its TCP is irrelevant); else the mastering reference at
/// card.calibration_pose with the chain's own weight; kind kNone when `gravity` is false or the
/// chain does not model gravity.
ControllerReference makeControllerReference(const ChainDescription& chain, const RobotCard& card,
                                            bool gravity, bool gravity_compensated,
                                            const ToolAttachment& calibration_load);

/// Δθ_c (rad) the controller adds to the command θ_cmd (rad), with the compliance c the offsets
/// were set up with (identification and Monte Carlo vary it). `data` may be the scratch of any
/// model of the same chain.
Vec6 controllerReferenceOffset(const ControllerReference& ref, Data& data, const JointCompliance& c,
                               const Vec6& theta_cmd);

/// complianceFromCard, but every joint must have a stiffness: throws InputError naming the card
/// line of the first joint without one.
JointCompliance requireComplianceFromCard(const RobotCard& card);

/// Joint-space stiffness term ∂τ/∂θ (N m/rad) at θ, analytic (fast_equilibrium.hpp); data is
/// left the natural-coordinate state at θ.
Mat6 torqueSensitivity(const Model& model, Data& data, const Vec6& theta, const Loads& loads);

}  // namespace roprec::nc
