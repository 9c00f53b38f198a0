#pragma once
/// \file kinematics_json.hpp
/// The JSON `roprec fk` and `roprec ik` print (plugin/api/kinematics.hpp computes it).
///
/// Units: mm and degrees. Joints are in the URDF convention unless named `controller` (the
/// vendor's convention, toControllerJoints).
/// Frames: base = the robot's base link; TCP = flange × the setup's tool.

#include "plugin/api/kinematics.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// robot, base_link, flange_link, joints_deg, controller_joints_deg, within_limits
/// (+ limit_violations), flange, tcp (with a cell), position_problem.
Json fkJson(const RobotSetup& setup, const FkResult& r);

/// robot, vendor, links, flange (+ tcp), opw geometry, fanuc_turn_axes (FANUC), solutions[] with
/// branch, joints, controller joints, config, limits, singularity flags and margins, residuals;
/// count, turns_truncated, unreachable.
Json ikJson(const RobotSetup& setup, const IkAnswer& a);

}  // namespace roprec::api
