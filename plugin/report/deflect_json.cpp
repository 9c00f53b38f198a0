/// The JSON of `roprec deflect` and of the controller's gravity handling
/// (plugin/report/deflect_json.hpp).
#include "plugin/report/deflect_json.hpp"

#include "plugin/report/pose_json.hpp"

namespace roprec::api {

Json gravityHandlingJson(const Robot& robot, const nc::ControllerReference& ref) {
  Json j = Json::object();
  j.set("gravity_model", Json::str(robot.card.gravity_modelled ? "links" : "none"));
  j.set("controller_reference", Json::str(ref.description()));
  j.set("calibration_pose_deg",
        Json::vector(toControllerJoints(robot.card, robot.card.calibration_pose) / kDeg, 6));
  const Counterbalance& cb = robot.card.counterbalance;
  j.set("counterbalance",
        Json::str(!cb.present() ? "none"
                                : robot.chain.joints[static_cast<size_t>(cb.joint)].name + " " +
                                      (cb.law == Counterbalance::Law::kGas ? "gas" : "spring")));
  const std::string note = gravityNotModelledNote(robot.card);
  if (!note.empty()) j.set("note", Json::str(note));
  return j;
}

namespace {

Json loadsJson(const RobotSetup& setup, const DeflectResult& r) {
  Json lj = Json::object();
  lj.set("gravity", Json::boolean(r.loads.gravity));
  lj.set("gravity_compensated_by_controller",
         Json::boolean(r.controller.kind == nc::ControllerReference::Kind::kGravityCompensated));
  lj.set("gravity_handling", gravityHandlingJson(setup.robot, r.controller));
  lj.set("tool_mass_kg", Json::number(setup.tool.mass, 3));
  lj.set("wrench_source", Json::str(r.load_source));
  lj.set("force_N", Json::vector(r.force(), 3));
  lj.set("moment_Nm", Json::vector(r.moment(), 4));
  return lj;
}

}  // namespace

Json deflectJson(const RobotSetup& setup, const DeflectResult& r) {
  const nc::Deflection& d = r.deflection;
  Json root = Json::object();
  root.set("robot", Json::str(setup.robot.card.name));
  root.set("joints_deg", Json::vector(r.joints / kDeg, 6));
  root.set("loads", loadsJson(setup, r));
  root.set("torques_Nm", Json::vector(d.tau, 3));
  root.set("joint_deflection_urad", Json::vector((d.theta - r.joints) * 1e6, 3));
  root.set("joint_deformation_urad", Json::vector(d.phi * 1e6, 3));
  root.set("servo_correction_urad", Json::vector(d.dpsi * 1e6, 3));
  Json dev = Json::object();
  dev.set("translation_um", Json::vector(d.dp * 1e6, 3));
  dev.set("rotation_urad", Json::vector(d.drot * 1e6, 3));
  dev.set("translation_norm_um", Json::number(d.dp.norm() * 1e6, 3));
  root.set("deviation", dev);
  root.set("nominal_tcp", poseJson(d.T_nominal));
  root.set("real_tcp", poseJson(d.T_real));
  Json conv = Json::object();
  conv.set("converged", Json::boolean(d.converged));
  conv.set("iterations", Json::integer(d.iterations));
  conv.set("residual_rad", Json::number(d.residual));
  root.set("equilibrium", conv);
  return root;
}

}  // namespace roprec::api
