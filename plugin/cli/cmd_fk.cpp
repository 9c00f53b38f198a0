/// `roprec fk`: rigid forward kinematics of the natural-coordinate model.
#include "compensator/support/error.hpp"
#include "compensator/robot/model.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "plugin/cli/robot_options.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  RobotSetup s = loadRobotSetup(args);
  const auto joints = args.option("joints");
  const auto out = args.option("o");
  args.finish();
  if (!joints) throw UsageError("give --joints \"j1 .. j6\" (deg, URDF convention)");
  const nc::Vec6 q = parseJointsDeg(*joints);
  const nc::Model model = nc::buildModel(s.robot.chain, s.tool);
  nc::Data data(model);
  const nc::PositionResult pr = nc::forwardKinematics(model, data, q);
  if (!pr.converged) {
    throw InputError("", 0, "position problem did not converge (residual " + std::to_string(pr.residual) + ")");
  }
  Json root = Json::object();
  root.set("robot", Json::str(s.robot.card.name));
  root.set("base_link", Json::str(s.robot.chain.base_link));
  root.set("flange_link", Json::str(s.robot.chain.tip_link));
  root.set("joints_deg", Json::vector(q / kDeg, 6));
  root.set("controller_joints_deg", Json::vector(toControllerJoints(s.robot.card, q) / kDeg, 6));
  const auto viol = limitViolations(s.robot.chain, q);
  root.set("within_limits", Json::boolean(viol.empty()));
  if (!viol.empty()) {
    Json v = Json::array();
    for (const auto& m : viol) v.push(Json::str(m));
    root.set("limit_violations", v);
  }
  root.set("flange", poseJson(data.T_W_flange));
  if (s.cell) root.set("tcp", poseJson(data.T_W_tcp));
  Json pos = Json::object();
  pos.set("converged", Json::boolean(pr.converged));
  pos.set("iterations", Json::integer(pr.iterations));
  pos.set("residual", Json::number(pr.residual));
  root.set("position_problem", pos);
  emit(ctx, out.value_or(""), root.dump());
  return 0;
}

const CommandRegistration reg{
    {"fk", "rigid forward kinematics (flange, and TCP with a cell)",
     "usage: roprec fk --robot NAME|robot.xml|file.urdf --joints \"j1 .. j6\" [--cell CELL.xml]\n"
     "                 [--base LINK --tip LINK] [-o OUT.json]\n\n"
     "Solves the position problem of the mixed-natural-coordinate model (Newton-Raphson) for the\n"
     "joint angles (deg, the robot's URDF joint convention) and prints JSON: `flange` (and `tcp` with a\n"
     "cell) as position_mm and quaternion_wxyz in the robot base frame (plus abc_deg, KUKA Z-Y'-X''),\n"
     "controller_joints_deg (the vendor's joint convention), and within_limits.\n",
     20, run}};

}  // namespace
}  // namespace roprec::cli
