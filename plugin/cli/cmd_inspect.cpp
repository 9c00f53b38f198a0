/// `roprec inspect PROGRAM`: what a robot program contains (docs/contract.md §11,
/// docs/programs.md).
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/inspect_output.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  const std::optional<std::string> out = args.option("o");
  const bool all = args.flag("all");
  const std::optional<std::string> holes = args.option("holes");
  const std::optional<std::string> tol = args.option("match-tol");
  if (args.option("match-tolerance"))
    throw UsageError("--match-tolerance is called --match-tol (as in predict and compensate)");
  const std::optional<std::string> axis = args.option("tool-axis");
  const std::optional<std::string> frames = args.option("frame");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (pos.size() != 1) throw UsageError("inspect needs exactly one PROGRAM");
  InspectRequest req;
  req.program = pos[0];
  if (frames) req.frames = parseFrames(*frames);
  if (axis) {
    const Eigen::VectorXd a = parseNumberList(*axis, 3, "--tool-axis");
    if (a.norm() < 1e-9) throw UsageError("--tool-axis must not be zero");
    req.tool_axis = a.normalized();
  }
  req.hole_list = holes;
  if (holes && tol) req.match_tolerance_mm = parseNumberList(*tol, 1, "--match-tol (mm)")[0];
  if (all && out) throw UsageError("give --all (the JSON on stdout) or -o OUT.json, not both");
  const InspectedProgram r = inspectProgram(req);
  if (all || out) emit(ctx, all ? "-" : *out, inspectJson(r).dump() + "\n");
  if (!all && !(out && *out == "-")) ctx.out << inspectSummaryText(inspectSummary(r));
  return 0;
}

const CommandRegistration reg{
    {"inspect", "what a robot program contains: targets, frames, configurations, holes",
     "usage: roprec inspect PROGRAM [--all | -o OUT.json] [--holes HOLES.csv [--match-tol MM]]\n"
     "                      [--tool-axis \"x y z\"] [--frame 'REF=x y z a b c[;REF=...]']\n\n"
     "PROGRAM: KUKA .src (+ .dat beside it), ABB .mod/.prg/.sys, FANUC .ls, CSV/JSON target list "
     "or\n"
     "hole list. Prints a summary (targets, motions, drill holes, unresolved references, notes);\n"
     "--all prints the whole JSON instead, -o OUT.json writes it (-o - to stdout). JSON: targets "
     "(pose in their frame and, where the frame resolves, in the robot "
     "base\n"
     "frame: position_mm, quaternion_wxyz; native values; configuration; external axes; "
     "tool/base),\n"
     "motions, recognised drill holes, unresolved references.\n"
     "--frame defines frames the program uses but does not define (e.g. 'UFRAME[1]=1400 0 400 0 0 "
     "0').\n"
     "--tool-axis: drilling axis in the TCP frame (default +z).\n",
     60, run}};

}  // namespace
}  // namespace roprec::cli
