/// Forward and inverse kinematics (plugin/api/kinematics.hpp).
#include "plugin/api/kinematics.hpp"

#include "compensator/support/error.hpp"

namespace roprec::api {

FkResult forwardKinematicsAt(const RobotSetup& setup, const Vec6& joints) {
  // the real robot: its calibrated geometry (robot card <calibration>), else the URDF
  const nc::Model model = nc::buildModel(setup.robot.real_chain, setup.tool);
  nc::Data data(model);
  FkResult r;
  r.joints = joints;
  r.position = nc::forwardKinematics(model, data, joints);
  if (!r.position.converged) {
    throw InputError(
        "", 0,
        "position problem did not converge (residual " + numberText(r.position.residual) + ")");
  }
  r.T_flange = data.T_W_flange;
  r.T_tcp = data.T_W_tcp;
  r.limit_violations = limitViolations(setup.robot.chain, joints);
  return r;
}

IkAnswer inverseKinematicsFor(const RobotSetup& setup, const IkRequest& request) {
  IkAnswer a;
  a.T_target = request.target;
  a.T_flange =
      setup.cell ? Pose(request.target * setup.cell->tool.T_flange_tcp.inverse()) : request.target;
  if (request.fanuc_turn_axes) a.config_options.fanuc_turn_axes = *request.fanuc_turn_axes;
  a.model = buildRealIkModel(setup.robot);  // the real robot reaches the target
  a.result = std::make_unique<IkResult>();
  IkOptions opt;
  opt.turns = request.all_turns ? IkTurns::kAll : IkTurns::kPrimary;
  const Vec6 seed = request.seed.value_or(Vec6::Zero());
  if (request.seed) opt.seed = &seed;
  solveIk(a.model, a.T_flange, opt, *a.result);
  for (int k = 0; k < a.result->count; ++k) {
    const IkSolution& sol = a.result->solutions[static_cast<size_t>(k)];
    a.usable += (sol.within_limits && sol.converged) ? 1 : 0;
  }
  if (a.result->count == 0) {
    a.unreachable = describeIkFailure(*a.result);
  } else if (a.usable == 0) {
    a.unreachable = "no converged solution within the joint limits";
  }
  return a;
}

}  // namespace roprec::api
