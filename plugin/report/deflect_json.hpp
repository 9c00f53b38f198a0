#pragma once
/// \file deflect_json.hpp
/// The JSON `roprec deflect` prints (plugin/api/deflect.hpp computes it), and the controller's
/// gravity handling (plugin/api/robot_compliance.hpp) as deflect and simulate print it.
///
/// Units: µm, µrad, mm, deg, N, N·m. Frames: the base frame (deflect.hpp).

#include "plugin/api/deflect.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// {"gravity_model": "links" | "none", "controller_reference": description, "calibration_pose_deg"
/// (controller convention), "counterbalance": law or "none", "note": gravityNotModelledNote}.
Json gravityHandlingJson(const Robot& robot, const nc::ControllerReference& ref);

/// robot, joints_deg, loads (with gravity_handling: gravityHandlingJson),
/// torques_Nm, joint_deflection_urad, joint_deformation_urad,
/// servo_correction_urad, deviation {translation_um, rotation_urad, translation_norm_um},
/// nominal_tcp, real_tcp, equilibrium.
Json deflectJson(const RobotSetup& setup, const DeflectResult& r);

}  // namespace roprec::api
