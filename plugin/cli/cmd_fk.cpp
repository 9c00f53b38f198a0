/// `roprec fk`: rigid forward kinematics of the natural-coordinate model.
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/kinematics_json.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  const RobotSetup s = loadRobotFromArgs(args);
  const auto joints = args.option("joints");
  const auto out = args.option("o");
  args.finish();
  if (!joints) throw UsageError("give --joints \"j1 .. j6\" (deg, URDF convention)");
  const FkResult r = forwardKinematicsAt(s, parseJointsDeg(*joints));
  emit(ctx, out.value_or(""), fkJson(s, r).dump());
  return 0;
}

const CommandRegistration reg{
    {"fk", "rigid forward kinematics (flange, and TCP with a cell)",
     "usage: roprec fk --robot NAME|robot.xml|file.urdf --joints \"j1 .. j6\" [--cell CELL.xml]\n"
     "                 [--base LINK --tip LINK] [-o OUT.json]\n\n"
     "Solves the position problem of the mixed-natural-coordinate model (Newton-Raphson) for the\n"
     "joint angles (deg, the robot's URDF joint convention) and prints JSON: `flange` (and `tcp` "
     "with a\n"
     "cell) as position_mm and quaternion_wxyz in the robot base frame (plus abc_deg, KUKA "
     "Z-Y'-X''),\n"
     "controller_joints_deg (the vendor's joint convention), and within_limits.\n",
     20, run}};

}  // namespace
}  // namespace roprec::cli
