/// `roprec ik`: all analytic inverse-kinematics solutions with the vendor's configuration flags.
#include <cmath>
#include <memory>

#include "compensator/robot/configuration.hpp"
#include "compensator/support/error.hpp"
#include "compensator/robot/ik.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "plugin/cli/robot_options.hpp"

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
  RobotSetup s = loadRobotSetup(args);
  const auto pose = args.option("pose");
  const auto xyzabc = args.option("xyzabc");
  const auto seed_text = args.option("seed");
  const auto turn_axes = args.option("turn-axes");
  const bool all_turns = args.flag("all-turns");
  const auto out = args.option("o");
  args.finish();
  if (pose.has_value() == xyzabc.has_value()) {
    throw UsageError("give exactly one of --pose \"x y z qw qx qy qz\" or --xyzabc \"x y z a b c\" (mm, deg)");
  }
  const Pose target = pose ? parsePoseQuat(*pose) : parsePoseXyzAbc(*xyzabc);
  Vec6 seed = Vec6::Zero();
  if (seed_text) seed = parseJointsDeg(*seed_text);
  ConfigurationOptions copt;
  if (turn_axes) copt.fanuc_turn_axes = parseTurnAxes(*turn_axes);

  const Pose T_flange = s.cell ? Pose(target * s.cell->tool.T_flange_tcp.inverse()) : target;
  const IkModel model = buildIkModel(s.robot);
  auto result = std::make_unique<IkResult>();
  IkOptions opt;
  opt.turns = all_turns ? IkTurns::kAll : IkTurns::kPrimary;
  if (seed_text) opt.seed = &seed;
  solveIk(model, T_flange, opt, *result);

  Json root = Json::object();
  root.set("robot", Json::str(s.robot.card.name));
  root.set("vendor", Json::str(vendorName(s.robot.card.vendor)));
  root.set("base_link", Json::str(s.robot.chain.base_link));
  root.set("flange_link", Json::str(s.robot.chain.tip_link));
  root.set("flange", poseJson(T_flange));
  if (s.cell) root.set("tcp", poseJson(target));
  Json opw = Json::object();
  opw.set("a1_mm", Json::number(model.opw.a1 * 1e3, 6));
  opw.set("a2_mm", Json::number(model.opw.a2 * 1e3, 6));
  opw.set("b_mm", Json::number(model.opw.b * 1e3, 6));
  opw.set("c1_mm", Json::number(model.opw.c1 * 1e3, 6));
  opw.set("c2_mm", Json::number(model.opw.c2 * 1e3, 6));
  opw.set("c3_mm", Json::number(model.opw.c3 * 1e3, 6));
  opw.set("c4_mm", Json::number(model.opw.c4 * 1e3, 6));
  opw.set("ideal_geometry", Json::boolean(model.deviation.exact));
  root.set("opw", opw);
  if (s.robot.card.vendor == Vendor::kFanuc) {
    Json axes = Json::array();
    for (int a : copt.fanuc_turn_axes) axes.push(Json::integer(a));
    root.set("fanuc_turn_axes", axes);
  }

  Json list = Json::array();
  int usable = 0;
  for (int k = 0; k < result->count; ++k) {
    const IkSolution& sol = result->solutions[static_cast<size_t>(k)];
    Json j = Json::object();
    j.set("branch_index", Json::integer(sol.branch.index()));
    Json br = Json::object();
    br.set("shoulder", Json::str(sol.branch.shoulder == 0 ? "front" : "back"));
    br.set("elbow", Json::str(sol.branch.elbow == 0 ? "up" : "down"));
    br.set("wrist", Json::str(sol.branch.wrist == 0 ? "theta5_nonnegative" : "theta5_negative"));
    j.set("branch", br);
    j.set("joints_deg", Json::vector(sol.q / kDeg, 6));
    j.set("controller_joints_deg", Json::vector(toControllerJoints(s.robot.card, sol.q) / kDeg, 6));
    j.set("config", Json::str(formatConfig(configurationOf(model, s.robot.card, sol.q, copt))));
    j.set("within_limits", Json::boolean(sol.within_limits));
    j.set("converged", Json::boolean(sol.converged));
    Json sing = Json::object();
    sing.set("wrist", Json::boolean(sol.singular_wrist));
    sing.set("shoulder", Json::boolean(sol.singular_shoulder));
    sing.set("elbow", Json::boolean(sol.singular_elbow));
    sing.set("wrist_margin_deg", Json::number(std::asin(std::min(1.0, sol.branch.wrist_margin_rad)) / kDeg, 6));
    sing.set("elbow_margin_deg", Json::number(std::asin(std::min(1.0, sol.branch.elbow_margin_rad)) / kDeg, 6));
    sing.set("shoulder_margin_mm", Json::number(sol.branch.shoulder_margin_m * 1e3, 6));
    j.set("singular", sing);
    Json res = Json::object();
    res.set("position_um", Json::number(sol.residual.position * 1e6, 6));
    res.set("rotation_urad", Json::number(sol.residual.rotation * 1e6, 6));
    res.set("refinement_iterations", Json::integer(sol.iterations));
    j.set("residual", res);
    list.push(j);
    usable += (sol.within_limits && sol.converged) ? 1 : 0;
  }
  root.set("count", Json::integer(result->count));
  root.set("solutions", list);
  if (result->truncated) root.set("turns_truncated", Json::boolean(true));
  std::string reason;
  if (result->count == 0) {
    reason = describeIkFailure(*result);
  } else if (usable == 0) {
    reason = "no converged solution within the joint limits";
  }
  if (!reason.empty()) root.set("unreachable", Json::str(reason));
  emit(ctx, out.value_or(""), root.dump());
  if (!reason.empty()) {
    ctx.err << "roprec: ik: " << reason << "\n";
    return 1;
  }
  return 0;
}

const CommandRegistration reg{
    {"ik", "all inverse-kinematics solutions with vendor configuration flags",
     "usage: roprec ik --robot NAME|robot.xml|file.urdf (--pose \"x y z qw qx qy qz\" | --xyzabc \"x y z a b c\")\n"
     "                 [--cell CELL.xml] [--seed \"j1 .. j6\"] [--all-turns] [--turn-axes \"1 4 6\"]\n"
     "                 [--base LINK --tip LINK] [-o OUT.json]\n\n"
     "Analytic IK of a spherical-wrist 6R robot (OPW geometry, Brandstötter et al. 2014) for the flange\n"
     "pose in the robot base frame (mm, unit quaternion; or KUKA X Y Z A B C). With --cell the pose is the\n"
     "TCP and the flange is TCP · tool⁻¹. Prints JSON `solutions[]` ordered by branch (4·shoulder + 2·elbow\n"
     "+ wrist) then turns: joints_deg (URDF convention), controller_joints_deg, config (KUKA \"S 2 T 34\",\n"
     "ABB \"[cf1,cf4,cf6,cfx]\", FANUC \"N U T, t1, t2, t3\" with the turn digits of --turn-axes, default\n"
     "J1 J4 J6 as RoboDK writes), branch, within_limits, singularity flags and margins, residuals.\n"
     "One solution per branch (turns nearest the seed, or 0) unless --all-turns lists every ±360° variant\n"
     "inside the joint limits. --seed (deg) also fixes q4 at a wrist singularity and q1 on axis 1.\n"
     "Exit 1 when no solution is reachable within the limits (the reason is printed), 2 on bad input.\n"
     "Conventions and their uncertainties: docs/configuration.md.\n",
     25, run}};

}  // namespace
}  // namespace roprec::cli
