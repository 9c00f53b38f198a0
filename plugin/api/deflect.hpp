#pragma once
/// \file deflect.hpp
/// The static deviation of the TCP at one commanded pose under gravity, the tool's weight and a
/// process wrench: flexible joints + servo stiffness, equilibrium in the deformed configuration
/// (θ = θ_m − τ(θ)/k − τ(θ)/k_servo), and the controller's gravity handling exactly as predict
/// sees it: the card's and the cell's <controller gravity_compensated>, else the mastering
/// reference at the calibration pose (plugin/api/robot_compliance.hpp, docs/model.md §6.3).
///
/// Units: SI in the structs (rad, N, N·m, m). The JSON: plugin/report/deflect_json.hpp.
/// Frames: the deviation δrobot = FK(θ) − FK(θ_m) is in the base frame; a given wrench is in the
/// base frame, the cell's process load in the tool frame (it follows the real tool orientation).

#include <optional>
#include <string>

#include "compensator/robot/deflection.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

struct DeflectRequest {
  nc::Vec6 joints{nc::Vec6::Zero()};  ///< commanded θ_m, URDF convention, rad
  bool gravity{true};                 ///< link and tool weight (and the controller's compensation)
  std::optional<nc::Wrench> wrench;   ///< on the TCP, base frame; replaces the cell's process
  bool process{true};                 ///< without `wrench`: the cell's steady process load, if any
  std::string joints_name{"joints"};  ///< names the joints in errors
  std::string wrench_source{
      "given wrench (base frame, on the TCP)"};  ///< loads.wrench_source with `wrench`
};

struct DeflectResult {
  nc::Vec6 joints{nc::Vec6::Zero()};  ///< θ_m, URDF, rad
  nc::Loads loads;
  std::string load_source;         ///< "none", the request's wrench_source or the cell process
  Mat3 R_W_tcp{Mat3::Identity()};  ///< nominal (rigid) TCP orientation, base frame
  nc::Deflection deflection;
  /// The controller's gravity handling (robot_compliance.hpp: card + cell <controller>; the
  /// mastering reference otherwise; none without gravity).
  nc::ControllerReference controller;
  /// The force (N) and moment (N·m) on the TCP in the base frame (tool-frame loads rotated by
  /// R_W_tcp).
  [[nodiscard]] Vec3 force() const;
  [[nodiscard]] Vec3 moment() const;
};

/// Solves the equilibrium. Throws InputError when the joints are outside the limits, when gravity
/// is on and a chain link has no mass (requireGravityModel)
/// ("<joints_name> outside the joint limits: ..."), when the card has no stiffness, and when the
/// position problem does not converge at this pose. A non-converged compliance equilibrium is
/// not an error: see deflection.converged and deflection.residual.
DeflectResult deflectAt(const RobotSetup& setup, const DeflectRequest& request);

}  // namespace roprec::api
