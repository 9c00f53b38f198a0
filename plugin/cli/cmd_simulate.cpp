/// `roprec simulate`: transient of one drilling cycle at one hole (CVODE,
/// compensator/process/transient.hpp): CSV time history of the process forces and the TCP
/// deviation, JSON summary.
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/simulate_output.hpp"

namespace roprec::cli {
namespace {

double positive(const std::optional<std::string>& text, const char* what, double def) {
  if (!text) return def;
  const double v = parseNumberList(*text, 1, what)[0];
  if (!(v > 0)) throw UsageError(std::string(what) + " must be > 0");
  return v;
}

int run(Args& args, CommandContext& ctx) {
  const RobotSetup s = loadRobotFromArgs(args);
  const auto joints = args.option("joints");
  const auto hole = args.option("hole");
  const auto out = args.option("o");
  const auto summary_path = args.option("summary");
  const auto duration = args.option("duration");
  const auto sample = args.option("sample-ms");
  const auto rtol = args.option("rtol");
  SimulateOptions opt;
  const auto method = args.option("method");
  opt.runout = args.flag("runout");
  opt.integral = !args.flag("no-integral");
  opt.gravity = !args.flag("no-gravity");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!s.cell) throw UsageError("simulate needs --cell CELL.xml (robot, tool and process)");
  if (joints && hole) throw UsageError("give either --joints or --hole ID PROGRAM, not both");
  if (!joints && !hole) throw UsageError("give --hole ID PROGRAM or --joints \"j1 .. j6\"");
  if (hole && pos.size() != 1) throw UsageError("--hole ID needs exactly one PROGRAM");
  if (joints && !pos.empty())
    throw UsageError("unexpected argument '" + pos.front() + "' with --joints");
  opt.duration = positive(duration, "--duration (s)", -1.0);
  opt.sample = positive(sample, "--sample-ms", 1.0) * 1e-3;
  opt.rtol = positive(rtol, "--rtol", -1.0);
  if (method && *method != "bdf" && *method != "adams")
    throw UsageError("--method must be 'bdf' (default) or 'adams', not '" + *method + "'");
  opt.adams = method && *method == "adams";

  HoleJoints at;
  if (joints) {
    at = {parseJointsDeg(*joints), "--joints", {}};
  } else {
    try {
      at = holeJoints(s, pos[0], *hole);
    } catch (const HoleUnreachable& e) {
      ctx.err << "roprec: " << formatInputError(e) << "\n";
      return 1;
    }
  }
  const SimulationResult r = simulateAt(s, at, opt);
  emit(ctx, out.value_or("-"), transientHistoryCsv(r.transient));
  if (summary_path) {
    emit(ctx, *summary_path, simulationSummaryJson(s, at, r).dump());
  } else {
    ctx.err << simulationSummaryJson(s, at, r).dump();
  }
  if (!r.transient.ok) {
    const std::string where =
        hole ? "hole " + *hole + " of " + pos[0] + ", " + at.source : at.source;
    ctx.err << "roprec: " << where << ": the transient stopped at t = " << r.transient.t_reached
            << " s: " << r.transient.message << "\n";
    return 1;
  }
  return 0;
}

const CommandRegistration reg{
    {"simulate",
     "transient drilling cycle at one hole (flexible joints + servo + real penetration)",
     "usage: roprec simulate --cell CELL.xml (--hole ID PROGRAM | --joints \"j1 .. j6\")\n"
     "                       [-o OUT.csv] [--summary F.json] [--duration S] [--method bdf|adams] "
     "[--runout]\n"
     "                       [--no-integral] [--no-gravity] [--sample-ms MS] [--rtol R] "
     "[--stiffness \"k1 .. k6\"]\n\n"
     "Integrates the flexible-joint robot under its cascade servo (position gain from the card,\n"
     "velocity PI estimated when absent) along the cell's process cycle: approach, progressive "
     "entry,\n"
     "full engagement, breakthrough, dwell, retract (drilling); a ramped step (wrench, milling).\n"
     "The arm holds the hole pose and the spindle feeds along the drill axis; the drill cuts at "
     "the "
     "tip's\n"
     "real advance (commanded feed + axial deflection of the arm): cut depth D and real feed per "
     "rev\n"
     "h = dD/dt·60/n set the forces; in the dwell the recovering arm keeps cutting until h < 1 % "
     "of "
     "f.\n"
     "CVODE BDF of order <= 3 at rtol 1e-4 (the convergence study of docs/transient.md: <= 0.5 um "
     "at\n"
     "the hole bottom against a tight reference); --method adams: Adams-Moulton; --rtol R: "
     "another\n"
     "relative tolerance. Without --duration the run ends with the retract.\n"
     "CSV (default stdout): t_s, depth_mm (commanded), Fa_N, Ft_N, M_Nm, Fr_N, dx_um, dy_um, dz_um "
     "(TCP\n"
     "deviation from the nominal rigid TCP, base frame), rx/ry/rz_urad, dq1..dq6_urad (link angle "
     "−\n"
     "command), tip_mm, cut_depth_mm, feed_per_rev_mm, axial_um, phase.\n"
     "JSON summary (stderr or --summary): static deviation (as deflect), deviation at the end of "
     "full\n"
     "engagement, maximum during entry, first contact, end of cut, maximum thrust, settling time "
     "to "
     "0.1 um\n"
     "and the equivalent damping ratio (the joint damping is an estimate), CVODE statistics.\n"
     "docs/transient.md has the model.\n"
     "--runout: apply the rotating residual force Fr at spindle frequency. --no-integral: velocity "
     "loop\n"
     "without integral action (steady state = static model with k_servo = Kv·Kω).\n"
     "Exit 1 if the hole is unreachable or the integration fails, 2 for bad input.\n",
     35, run}};

}  // namespace
}  // namespace roprec::cli
