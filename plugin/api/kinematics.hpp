#pragma once
/// \file kinematics.hpp
/// Rigid forward kinematics of the natural-coordinate model and the analytic inverse kinematics
/// (all OPW solutions with the vendor's configuration flags). Their JSON: plugin/report/
/// kinematics_json.hpp.
///
/// Units: SI in the structs (m, rad); JSON in mm and degrees. Joints are in the URDF convention
/// unless named `controller` (the vendor's convention, toControllerJoints).
/// Frames: base = the robot's base link; TCP = flange × the setup's tool.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/configuration.hpp"
#include "compensator/robot/ik.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

// ---------------------------------------------------------------- forward kinematics

struct FkResult {
  Vec6 joints{Vec6::Zero()};                  ///< URDF convention, rad
  Pose T_flange{Pose::Identity()};            ///< base frame, m
  Pose T_tcp{Pose::Identity()};               ///< base frame, m
  nc::PositionResult position;                ///< the Newton solve of the position problem
  std::vector<std::string> limit_violations;  ///< limitViolations(joints)
};

/// Solves the position problem at `joints` (URDF, rad; outside the limits is allowed and
/// reported). Throws InputError "position problem did not converge (residual ...)".
FkResult forwardKinematicsAt(const RobotSetup& setup, const Vec6& joints);

// ---------------------------------------------------------------- inverse kinematics

struct IkRequest {
  Pose target{Pose::Identity()};  ///< base frame, m: the TCP with a cell, else the flange
  std::optional<Vec6> seed;  ///< URDF, rad: primary turns, q4 at a wrist singularity, q1 on axis 1
  bool all_turns{false};     ///< every in-limit ±360° variant instead of one per branch
  std::optional<std::array<int, 3>> fanuc_turn_axes;  ///< joints (1..6) of the FANUC turn digits
};

struct IkAnswer {
  Pose T_target{Pose::Identity()};  ///< as requested
  Pose T_flange{Pose::Identity()};  ///< target · tool⁻¹ with a cell, else the target
  IkModel model;
  std::unique_ptr<IkResult> result;  ///< solutions ordered by branch, then turns
  ConfigurationOptions config_options;
  int usable{0};            ///< solutions converged and within the limits
  std::string unreachable;  ///< why there is no usable solution; empty when usable > 0
};

/// All analytic IK solutions of the target. No solution is not an error: see `unreachable`.
IkAnswer inverseKinematicsFor(const RobotSetup& setup, const IkRequest& request);

}  // namespace roprec::api
