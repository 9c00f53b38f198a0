#pragma once
/// \file milling_dynamics.hpp
/// Linear structural dynamics at the milling tool (docs/process.md §4.6): the robot's modes at a
/// pose, the spindle/tool mode, the tool-tip receptance H(ω) and the periodic forced response to
/// the cutting force over a revolution.
///
/// ## Robot modes at a pose θ (linearised about the static pose, small vibration)
///   M(θ) δθ̈ + D δθ̇ + K δθ = J_v(θ)ᵀ F,   x_tcp = J_v(θ) δθ
/// M(θ) = RᵀMR, the joint-space inertia of the multibody model (inverse_dynamics.hpp
/// `jointSpaceInertia`: links, tool and spindle mass; no rotor inertia: the motors are held by the
/// servo); K = diag(k_eff,j), 1/k_eff = 1/k + 1/k_servo (the joint and the servo's static stiffness
/// in series, deflection.hpp). The geometric stiffness of gravity and of the axis-2 balancer is
/// neglected (it is ≲ 1 % of K on the bundled cards). Joints without stiffness (rigid,
/// k_eff ≥ 1e15 N m/rad) are locked: the problem is reduced to the flexible joints.
/// Modes: the generalized symmetric eigenproblem K φ = ω² M φ with φᵀMφ = 1; damping is modal,
/// ζ_r = `damping_ratio` for every robot mode (stated; 0.02–0.08 is typical of robot arms).
/// The TCP modal vector of mode r is u_r = S R_W_tcpᵀ J_v φ_r (milling frame, S = diag(1, −1, −1):
/// X = tool x, Y = −tool y, Z = −tool z, as milling_robot.hpp); with φ mass-normalised
///   H(ω) = Σ_r u_r u_rᵀ / (ω_r² − ω² + 2i ζ_r ω_r ω)   [m/N], milling frame;
/// H(0) = J_v K⁻¹ J_vᵀ is the robot's linear static compliance at the TCP.
///
/// ## Spindle/tool mode (cell `<dynamics tool_frequency_hz tool_stiffness_N_per_um
/// tool_damping_ratio>`)
/// One mode of the tool tip relative to the spindle in each of X and Y (isotropic, axially rigid):
/// modal mass m_t = k_t/ω_t², u = e_X/√m_t and e_Y/√m_t, so that its receptance is
/// 1/(k_t − m_t ω² + 2i ζ_t √(k_t m_t) ω). It acts in series with the robot: the receptances add.
///
/// ## Periodic forced response
/// A force sampled over one revolution at φ_n = 2πn/N (cutter angle, ϕ = Ωt, Ω = 2π rpm/60) has
/// the harmonics F̂_k = (1/N) Σ_n F(φ_n) e^{−ikφ_n}; the steady-state displacement is
///   x(φ) = Σ_{k=1}^{⌊(N−1)/2⌋} 2 Re[H(kΩ) F̂_k e^{ikφ}]   (the dynamic part; the mean k = 0 is
///   the static deflection, which the coupling solves with the full nonlinear compliance).

#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "compensator/robot/deflection.hpp"
#include "compensator/robot/model.hpp"
#include "compensator/support/rotation.hpp"

namespace roprec {

using Mat3c = Eigen::Matrix3cd;

struct VibrationMode {
  double omega{0};         ///< undamped natural frequency ω_r [rad/s]
  double zeta{0};          ///< modal damping ratio
  Vec3 tcp{Vec3::Zero()};  ///< u_r: TCP displacement of the mass-normalised mode, milling frame
  nc::Vec6 joints{
      nc::Vec6::Zero()};  ///< joint shape normalised to max |φ_j| = 1 (zero for the tool mode)
  bool robot{true};       ///< a robot mode (false: the spindle/tool mode)
  /// Modal stiffness seen at the TCP along the mode's own TCP direction: ω_r²/|u_r|² [N/m]
  /// (infinite when the mode does not move the TCP).
  [[nodiscard]] double tcpStiffness() const;
};

struct ModalModel {
  std::vector<VibrationMode> modes;  ///< robot modes by ascending frequency, then the tool's
};

/// Receptance of the modal model at ω [rad/s] (milling frame, m/N).
Mat3c receptance(const ModalModel& model, double omega);

struct ToolModeSpec {
  double frequency_hz{2000};  ///< f_t [Hz]
  double stiffness{20e6};     ///< k_t [N/m]
  double damping_ratio{0.03};
};
/// The tool mode's static compliance diag(1/k_t, 1/k_t, 0) [m/N], milling frame.
Mat3 toolStaticCompliance(const ToolModeSpec& tool);
/// Adds the spindle/tool mode in X and in Y (two modes, tool == false).
void addToolMode(ModalModel& model, const ToolModeSpec& tool);

/// Robot modes at the joint values θ (rad) with modal damping `damping_ratio`, TCP shapes in the
/// milling frame of the nominal TCP orientation at θ. Throws std::runtime_error when the position
/// problem does not converge or M is not positive definite.
ModalModel robotModes(const nc::Model& model, const nc::JointCompliance& compliance,
                      const nc::Vec6& theta, double damping_ratio);

/// Dynamic part of the steady periodic displacement (see the file comment) at the samples of
/// `force` (one revolution, equally spaced in the cutter angle) for a spindle at `spindle_rpm`:
/// the harmonic sum term by term, O(N·K) — the plain form of what milling.cpp's resolved
/// revolution takes by FFT at every iteration, and the tests' reference for it.
std::vector<Vec3> periodicResponse(const ModalModel& model, const std::vector<Vec3>& force,
                                   double spindle_rpm);

}  // namespace roprec
