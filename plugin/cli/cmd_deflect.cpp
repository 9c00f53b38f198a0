/// `roprec deflect`: static deviation of the TCP at one pose under gravity, tool weight and a
/// process wrench (flexible joints + servo gain, deformed-configuration equilibrium).
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/deflect_json.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  const RobotSetup s = loadRobotFromArgs(args);
  const auto joints = args.option("joints");
  const auto wrench = args.option("wrench");
  const bool no_gravity = args.flag("no-gravity");
  const bool no_process = args.flag("no-process");
  const auto out = args.option("o");
  args.finish();
  if (!joints) throw UsageError("give --joints \"j1 .. j6\" (deg, URDF convention)");
  DeflectRequest req;
  req.joints = parseJointsDeg(*joints);
  req.joints_name = "--joints";
  req.gravity = !no_gravity;
  req.process = !no_process;
  if (wrench) {
    const Eigen::VectorXd w =
        parseNumberList(*wrench, 6, "--wrench (fx fy fz mx my mz, N and N m, base frame)");
    req.wrench = nc::Wrench{w.head<3>(), w.tail<3>()};
    req.wrench_source = "--wrench (base frame, on the TCP)";
  }
  const DeflectResult r = deflectAt(s, req);
  emit(ctx, out.value_or(""), deflectJson(s, r).dump());
  if (!r.deflection.converged) {
    ctx.err << "roprec: the compliance equilibrium did not converge (residual "
            << r.deflection.residual << " rad)\n";
    return 1;
  }
  return 0;
}

const CommandRegistration reg{
    {"deflect", "static TCP deviation under gravity, tool weight and a process wrench",
     "usage: roprec deflect --robot R --joints \"j1 .. j6\" [--wrench \"fx fy fz mx my mz\"]\n"
     "                      [--no-gravity] [--stiffness \"k1 .. k6\"] [--cell CELL.xml] "
     "[--no-process]\n"
     "                      [-o OUT.json]\n\n"
     "Commanded joints θ_m (deg, URDF convention). The real link angles solve\n"
     "  θ = θ_m − τ(θ)/k − τ(θ)/k_servo   (flexible joints + servo gain, τ at the deflected pose)\n"
     "and the deviation δrobot = FK(θ) − FK(θ_m) is printed in the base frame (µm, µrad).\n"
     "--wrench: force (N) and moment (N m) that the environment exerts ON the TCP, base frame.\n"
     "With --cell: the cell's tool (TCP, mass, centre of mass) and, unless --wrench or "
     "--no-process,\n"
     "its process (drilling: steady thrust and torque; milling: mean force; wrench: as given, tool "
     "frame).\n"
     "JSON: torques_Nm, joint_deflection_urad, deviation {translation_um, rotation_urad}.\n"
     "Exit 1 if the equilibrium does not converge, 2 for bad input (e.g. joints outside limits).\n",
     30, run}};

}  // namespace
}  // namespace roprec::cli
