/// `roprec predict`: per-hole deviation, uncertainty budget, tolerance verdict and capability.
#include <algorithm>
#include <filesystem>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/json.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"

namespace roprec::cli {
namespace {

void printSummary(CommandContext& ctx, const PredictionResult& r) {
  const CapabilitySummary& sum = r.summary;
  ctx.err << "roprec predict: " << sum.holes << " holes: " << sum.conforms << " conform, "
          << sum.conforms_after_compensation << " conform after compensation, " << sum.not_capable
          << " not capable, " << (sum.unreachable + sum.singular + sum.not_converged)
          << " not handled\n";
  ctx.err << "  the robot can take " << sum.robot_can_take
          << " holes = " << formatNumber(sum.mc_time_taken, 0) << " s of machining-center time (of "
          << formatNumber(sum.mc_time_total, 0) << " s)\n";
  double mx = 0;
  double mean = 0;
  int n = 0;
  for (const HolePrediction& h : r.holes) {
    if (!h.nominal_axis_error) continue;
    mx = std::max(mx, *h.nominal_axis_error);
    mean += *h.nominal_axis_error;
    ++n;
  }
  if (n > 0) {
    ctx.err << "  real drill points from the nominal hole axes: mean "
            << formatNumber(mean / n * 1e6, 3) << " µm, max " << formatNumber(mx * 1e6, 3)
            << " µm (" << n << " holes)\n";
  }
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto json_out = args.option("json");
  const auto report_out = args.option("report");
  const auto holes = args.option("holes");
  const auto uncertainty = args.option("uncertainty");
  const auto match_tol = args.option("match-tol");
  JobOptions opt;
  parseFrameTool(args, opt);
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (pos.size() != 1) throw UsageError("give exactly one PROGRAM_OR_HOLES file");
  opt.holes = holes;
  opt.uncertainty = uncertainty.value_or("");
  if (match_tol) opt.match_tol_mm = parseNumberList(*match_tol, 1, "--match-tol (mm)")[0];

  Progress progress(ctx, "predicting holes", 0);
  const PredictionResult r = predictJob(
      *cell, pos[0], opt, [&](size_t done, size_t total) { progress.step(done, total); });
  progress.finish();
  printJobNotes(ctx, r.context.job.notes);
  const std::string json = predictionJson(r).dump();
  if (report_out) writeFileAtomic(*report_out, predictionReport(r));
  emit(ctx, json_out.value_or(""), json);

  for (size_t i = 0; i < r.holes.size(); ++i) {
    const HolePrediction& h = r.holes[i];
    if (h.status == HoleStatus::kOk || ctx.quiet) continue;
    const HoleRequest& q = r.context.job.requests[i];
    ctx.err << "roprec: hole " << h.id;
    if (q.line > 0) ctx.err << " (" << pos[0] << ":" << q.line << ")";
    ctx.err << ": " << verdictName(h.verdict) << ": " << h.reason << "\n";
  }
  if (!ctx.quiet && json_out) printSummary(ctx, r);
  return r.failed() ? 1 : 0;
}

const CommandRegistration reg{
    {"predict", "per-hole deviation, uncertainty, tolerance verdict and capability",
     "usage: roprec predict --cell CELL.xml PROGRAM_OR_HOLES [--json OUT.json] [--report "
     "OUT.html]\n"
     "                      [--holes HOLES.csv] [--uncertainty linear|montecarlo] [--quiet]\n"
     "                      [--frame cell|\"x y z a b c\"|'REF=x y z a b c;...'] [--tool "
     "program|cell]\n\n"
     "For every hole of a drilling program (KUKA .src, ABB .mod/.prg, FANUC .ls, CSV/JSON targets) "
     "or a\n"
     "hole-list CSV: the IK solution the program's configuration selects (hole lists: the "
     "admissible\n"
     "solution nearest the previous hole's), δrobot under gravity, tool weight and the steady "
     "process\n"
     "wrench, δmach, δwork = δrobot + δmach, the position error ⊥ the hole axis and the axis tilt, "
     "the\n"
     "uncertainty budget U_robot, U_mach, U_work (2-D radial 95 %, k = 2.4477) and the ISO "
     "14253-1\n"
     "verdict against the hole's position tolerance (hole list, else the cell's <tolerance>):\n"
     "conforms | conforms-after-compensation | not-capable | unreachable | singular.\n"
     "--holes: a hole list matched to the program's holes (ids, diameters, depths, tolerances) by "
     "id,\n"
     "else by position within --match-tol mm (0.5); the JSON then reports from_nominal_axis, the "
     "real\n"
     "drill point's distance from the nominal hole axis (the residual of a compensated program).\n"
     "JSON to stdout unless --json; --report writes one self-contained HTML file.\n"
     "A base frame only the controller defines (FANUC UFRAME[n], KUKA BASE_DATA[n]) needs --frame\n"
     "(its pose in the robot base frame, mm/deg KUKA A-B-C; REF=... by name; cell = the cell's\n"
     "<workobject>); a program tool that differs from the cell's, or is defined only on the\n"
     "controller (UTOOL[n], TOOL_DATA[n]), needs --tool program|cell. Without them: exit 2.\n"
     "The resolution is printed on stderr and stated in the JSON notes and the report header.\n"
     "Exit 1 if some holes could not be handled (listed on stderr), 2 for bad input.\n",
     40, run}};

}  // namespace
}  // namespace roprec::cli
