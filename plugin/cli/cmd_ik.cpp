/// `roprec ik`: all analytic inverse-kinematics solutions with the vendor's configuration flags.
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/kinematics_json.hpp"

namespace roprec::cli {
namespace {

std::array<int, 3> parseTurnAxes(const std::string& text) {
  const Eigen::VectorXd v = parseNumberList(text, 3, "--turn-axes");
  std::array<int, 3> axes{};
  for (int i = 0; i < 3; ++i) {
    const double a = v[i];
    if (a != static_cast<int>(a) || a < 1 || a > 6) {
      throw InputError("", 0, "--turn-axes: joint numbers 1..6 expected, got '" + text + "'");
    }
    axes[static_cast<size_t>(i)] = static_cast<int>(a);
  }
  return axes;
}

int run(Args& args, CommandContext& ctx) {
  const RobotSetup s = loadRobotFromArgs(args);
  const auto pose = args.option("pose");
  const auto xyzabc = args.option("xyzabc");
  const auto seed = args.option("seed");
  const auto turn_axes = args.option("turn-axes");
  const bool all_turns = args.flag("all-turns");
  const auto out = args.option("o");
  args.finish();
  if (pose.has_value() == xyzabc.has_value()) {
    throw UsageError(
        "give exactly one of --pose \"x y z qw qx qy qz\" or --xyzabc \"x y z a b c\" (mm, deg)");
  }
  IkRequest req;
  req.target = pose ? parsePoseQuat(*pose) : parsePoseXyzAbc(*xyzabc);
  if (seed) req.seed = parseJointsDeg(*seed);
  if (turn_axes) req.fanuc_turn_axes = parseTurnAxes(*turn_axes);
  req.all_turns = all_turns;

  const IkAnswer a = inverseKinematicsFor(s, req);
  emit(ctx, out.value_or(""), ikJson(s, a).dump());
  if (!a.unreachable.empty()) {
    ctx.err << "roprec: ik: " << a.unreachable << "\n";
    return 1;
  }
  return 0;
}

const CommandRegistration reg{{"ik",
                               "all inverse-kinematics solutions with vendor configuration flags",
                               "usage: roprec ik --robot NAME|robot.xml|file.urdf (--pose \"x y z "
                               "qw qx qy qz\" | --xyzabc \"x y z a b c\")\n"
                               "                 [--cell CELL.xml] [--seed \"j1 .. j6\"] "
                               "[--all-turns] [--turn-axes \"1 4 6\"]\n"
                               "                 [--base LINK --tip LINK] [-o OUT.json]\n\n"
                               "Analytic IK of a spherical-wrist 6R robot (OPW geometry, "
                               "Brandstötter et al. 2014) for the flange\n"
                               "pose in the robot base frame (mm, unit quaternion; or KUKA X Y Z A "
                               "B C). With --cell the pose is the\n"
                               "TCP and the flange is TCP · tool⁻¹. Prints JSON `solutions[]` "
                               "ordered by branch (4·shoulder + 2·elbow\n"
                               "+ wrist) then turns: joints_deg (URDF convention), "
                               "controller_joints_deg, config (KUKA \"S 2 T 34\",\n"
                               "ABB \"[cf1,cf4,cf6,cfx]\", FANUC \"N U T, t1, t2, t3\" with the "
                               "turn digits of --turn-axes, default\n"
                               "J1 J4 J6 as RoboDK writes), branch, within_limits, singularity "
                               "flags and margins, residuals.\n"
                               "One solution per branch (turns nearest the seed, or 0) unless "
                               "--all-turns lists every ±360° variant\n"
                               "inside the joint limits. --seed (deg) also fixes q4 at a wrist "
                               "singularity and q1 on axis 1.\n"
                               "Exit 1 when no solution is reachable within the limits (the reason "
                               "is printed), 2 on bad input.\n"
                               "Conventions and their uncertainties: docs/configuration.md.\n",
                               25, run}};

}  // namespace
}  // namespace roprec::cli
