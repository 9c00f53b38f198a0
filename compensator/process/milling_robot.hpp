#pragma once
/// \file milling_robot.hpp
/// The robot as the milling coupling's compliance (docs/process.md §4.4): at a path
/// point with commanded joints θ_m, the tool deflection under a milling force F is the robot's
/// deviation recomputed with the full nonlinear joint-compliance equilibrium (deflection.hpp):
///
///   δ_mill(F) = S R_W_tcpᵀ [ p_real(θ_m; F_tool = S F) − p_real(θ_m; 0) ],   S = diag(1, −1, −1),
///
/// where the milling frame is X = feed = tool x, Z = tool tip → spindle = −tool z, Y = Z × X =
/// −tool y, and the force on the tool follows the real tool orientation (tool-frame load).
/// Gravity (and the tool weight) is in both terms, so only the process part is returned.

#include "compensator/process/milling.hpp"
#include "compensator/robot/deflection.hpp"

namespace roprec {

/// A ComplianceFunction bound to one path point. The model and compliance are copied into it.
ComplianceFunction robotMillingCompliance(const nc::Model& model, const nc::JointCompliance& c,
                                          const nc::Vec6& theta_m, bool gravity = true);

/// The compliance linearised at a reference force F_ref (what a path's coupling evaluates many
/// times per point, docs/process.md "CAM-size paths"):
///
///   δ(G) ≈ δ(F_ref) + C (G − F_ref),   C_{:,i} = [δ(F_ref + h e_i) − δ(F_ref)] / h,
///
/// four evaluations of the full (nonlinear) compliance instead of one per coupling evaluation.
/// What it leaves out is the compliance's curvature in G (the configuration change under the
/// load, the tool-frame load turning with the tool): second order in |G − F_ref| — on the milling
/// sample's robot ≤ 0.02 µm for |G − F_ref| ≤ 50 N, ≤ 0.3 µm for 200 N (milling_robot_test).
struct LinearCompliance {
  Vec3 F_ref{Vec3::Zero()};      ///< [N], milling frame
  Vec3 delta_ref{Vec3::Zero()};  ///< δ(F_ref) [m]
  Mat3 C{Mat3::Zero()};          ///< ∂δ/∂G at F_ref [m/N]
  [[nodiscard]] Vec3 operator()(const Vec3& G) const { return delta_ref + C * (G - F_ref); }
};
/// Forward differences of `full` at F_ref with the step `step_N` on each axis [N].
LinearCompliance lineariseCompliance(const ComplianceFunction& full, const Vec3& F_ref,
                                     double step_N = 1.0);

}  // namespace roprec
