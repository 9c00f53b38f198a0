/// Static TCP deviation at one pose (plugin/api/deflect.hpp).
#include "plugin/api/deflect.hpp"

#include "compensator/process/process_load.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/robot_compliance.hpp"

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

}  // namespace roprec::api
