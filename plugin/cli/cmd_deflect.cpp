/// `roprec deflect`: static deviation of the TCP at one pose under gravity, tool weight and a
/// process wrench (flexible joints + servo gain, deformed-configuration equilibrium).
#include <cstdio>

#include "compensator/support/error.hpp"
#include "compensator/process/process_load.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/cli/robot_options.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  RobotSetup s = loadRobotSetup(args);
  const auto joints = args.option("joints");
  const auto wrench = args.option("wrench");
  const bool no_gravity = args.flag("no-gravity");
  const bool no_process = args.flag("no-process");
  const auto out = args.option("o");
  args.finish();
  if (!joints) throw UsageError("give --joints \"j1 .. j6\" (deg, URDF convention)");
  const nc::Vec6 q = parseJointsDeg(*joints);
  const auto viol = limitViolations(s.robot.chain, q);
  if (!viol.empty()) throw InputError("", 0, "--joints outside the joint limits: " + viol.front());
  const nc::JointCompliance c = complianceOf(s.robot.card);
  const nc::Model model = nc::buildModel(s.robot.chain, s.tool);
  nc::Data data(model);
  nc::forwardKinematics(model, data, q);
  const Mat3 R_W_tcp = data.T_W_tcp.linear();

  nc::Loads loads;
  loads.gravity = !no_gravity;
  std::string load_source = "none";
  if (wrench) {
    const Eigen::VectorXd w = parseNumberList(*wrench, 6, "--wrench (fx fy fz mx my mz, N and N m, base frame)");
    loads.tcp.force = w.head<3>();
    loads.tcp.moment = w.tail<3>();
    load_source = "--wrench (base frame, on the TCP)";
  } else if (s.cell && s.cell->has_process && !no_process) {
    const SteadyProcessLoad pl = steadyProcessLoad(parseProcess(s.cell->process));
    loads.tcp_tool.force = pl.wrench.force;  // tool frame, follows the real tool orientation
    loads.tcp_tool.moment = pl.wrench.torque;
    load_source = "cell process (tool frame): " + pl.description;
  }
  const nc::Vec6 offset = no_gravity ? nc::Vec6::Zero() : controllerGravityOffset(s.robot, c, q);
  const nc::Deflection d = nc::predictDeflection(model, data, c, q, loads, {}, offset);
  if (!d.position_converged) throw InputError("", 0, "the position problem did not converge at this pose");

  Json root = Json::object();
  root.set("robot", Json::str(s.robot.card.name));
  root.set("joints_deg", Json::vector(q / kDeg, 6));
  Json lj = Json::object();
  lj.set("gravity", Json::boolean(loads.gravity));
  lj.set("gravity_compensated_by_controller", Json::boolean(s.robot.card.gravity_compensated && loads.gravity));
  lj.set("tool_mass_kg", Json::number(s.tool.mass, 3));
  lj.set("wrench_source", Json::str(load_source));
  lj.set("force_N", Json::vector(loads.tcp.force + R_W_tcp * loads.tcp_tool.force, 3));
  lj.set("moment_Nm", Json::vector(loads.tcp.moment + R_W_tcp * loads.tcp_tool.moment, 4));
  root.set("loads", lj);
  root.set("torques_Nm", Json::vector(d.tau, 3));
  root.set("joint_deflection_urad", Json::vector((d.theta - q) * 1e6, 3));
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
  emit(ctx, out.value_or(""), root.dump());
  if (!d.converged) {
    ctx.err << "roprec: the compliance equilibrium did not converge (residual " << d.residual << " rad)\n";
    return 1;
  }
  return 0;
}

const CommandRegistration reg{
    {"deflect", "static TCP deviation under gravity, tool weight and a process wrench",
     "usage: roprec deflect --robot R --joints \"j1 .. j6\" [--wrench \"fx fy fz mx my mz\"]\n"
     "                      [--no-gravity] [--stiffness \"k1 .. k6\"] [--cell CELL.xml] [--no-process]\n"
     "                      [-o OUT.json]\n\n"
     "Commanded joints θ_m (deg, URDF convention). The real link angles solve\n"
     "  θ = θ_m − τ(θ)/k − τ(θ)/k_servo   (flexible joints + servo gain, τ at the deflected pose)\n"
     "and the deviation δrobot = FK(θ) − FK(θ_m) is printed in the base frame (µm, µrad).\n"
     "--wrench: force (N) and moment (N m) that the environment exerts ON the TCP, base frame.\n"
     "With --cell: the cell's tool (TCP, mass, centre of mass) and, unless --wrench or --no-process,\n"
     "its process (drilling: steady thrust and torque; milling: mean force; wrench: as given, tool frame).\n"
     "JSON: torques_Nm, joint_deflection_urad, deviation {translation_um, rotation_urad}.\n"
     "Exit 1 if the equilibrium does not converge, 2 for bad input (e.g. joints outside limits).\n",
     30, run}};

}  // namespace
}  // namespace roprec::cli
