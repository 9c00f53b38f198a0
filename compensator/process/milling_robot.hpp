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

}  // namespace roprec
