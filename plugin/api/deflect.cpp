/// Static TCP deviation at one pose (plugin/api/deflect.hpp).
#include "plugin/api/deflect.hpp"

#include "compensator/process/process_load.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/report/pose_json.hpp"

namespace roprec::api {

namespace {

/// The loads of the request: the given wrench (base frame), else the cell's process (tool frame).
nc::Loads loadsOf(const RobotSetup& setup, const DeflectRequest& request, std::string& source) {
  nc::Loads loads;
  loads.gravity = request.gravity;
  source = "none";
  if (request.wrench) {
    loads.tcp = *request.wrench;
    source = request.wrench_source;
  } else if (setup.cell && setup.cell->has_process && request.process) {
    const SteadyProcessLoad pl = steadyProcessLoad(parseProcess(setup.cell->process));
    loads.tcp_tool.force = pl.wrench.force;  // tool frame, follows the real tool orientation
    loads.tcp_tool.moment = pl.wrench.torque;
    source = "cell process (tool frame): " + pl.description;
  }
  return loads;
}

}  // namespace

Vec3 DeflectResult::force() const { return loads.tcp.force + R_W_tcp * loads.tcp_tool.force; }
Vec3 DeflectResult::moment() const { return loads.tcp.moment + R_W_tcp * loads.tcp_tool.moment; }

DeflectResult deflectAt(const RobotSetup& setup, const DeflectRequest& request) {
  DeflectResult r;
  r.joints = request.joints;
  requireWithinLimits(setup.robot.chain, r.joints, request.joints_name);
  const nc::JointCompliance c = complianceOf(setup.robot.card);
  const nc::Model model = nc::buildModel(setup.robot.real_chain, setup.tool);
  nc::Data data(model);
  nc::forwardKinematics(model, data, r.joints);
  r.R_W_tcp = data.T_W_tcp.linear();
  r.loads = loadsOf(setup, request, r.load_source);
  if (request.gravity) requireGravityModel(setup.robot);
  r.controller = controllerReferenceOf(setup.robot, setup.cell ? &*setup.cell : nullptr, setup.tool,
                                       request.gravity);
  const nc::Vec6 offset = nc::controllerReferenceOffset(r.controller, data, c, r.joints);
  r.deflection = nc::predictDeflection(model, data, c, r.joints, r.loads, {}, offset);
  if (!r.deflection.position_converged)
    throw InputError("", 0, "the position problem did not converge at this pose");
  if (setup.robot.card.calibration) {  // deviation from the pose the controller means (FK_nom)
    nc::referToControllerPose(r.deflection, chainForwardKinematics(setup.robot.chain, r.joints) *
                                                setup.tool.T_flange_tcp);
  }
  return r;
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
