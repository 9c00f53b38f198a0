/// `roprec milling-stability`: the robot's modes at a pose, the spindle/tool mode and the
/// zero-order stability lobes of the cell's milling cut (plugin/api/milling_stability.hpp).
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/report/milling_output.hpp"

namespace roprec::cli {
namespace {

/// `--rpm "LO HI"` and `--steps N` into the request.
void parseRange(MillingStabilityRequest& req, const std::optional<std::string>& rpm,
                const std::optional<std::string>& steps) {
  if (rpm) {
    const Eigen::VectorXd v = parseNumberList(*rpm, 2, "--rpm (LO HI, 1/min)");
    if (!(v[0] > 0 && v[1] > v[0] && v[1] <= 200000))
      throw UsageError("--rpm: give \"LO HI\" with 0 < LO < HI <= 200000");
    req.rpm_lo = v[0];
    req.rpm_hi = v[1];
  }
  if (steps) {
    const auto v = parseNumber(*steps);
    if (!v || !(*v >= 2 && *v <= 20000) || *v != std::floor(*v))
      throw UsageError("--steps must be an integer 2..20000");
    req.steps = static_cast<int>(*v);
  }
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto joints = args.option("joints");
  const auto csv = args.option("csv");
  const auto report = args.option("report");
  const auto json = args.option("json");
  const auto rpm = args.option("rpm");
  const auto steps = args.option("steps");
  const auto tool = args.option("tool");
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  MillingStabilityRequest req;
  req.cell = *cell;
  req.tool = tool;
  if (joints) req.joints = parseJointsDeg(*joints);
  parseRange(req, rpm, steps);
  const MillingStabilityResult r = millingStability(req);
  const MillingStabilityOutput o = millingStabilityOutput(r);
  const std::string text = o.json.dump() + "\n";
  if (csv) emit(ctx, *csv, o.csv);
  if (report) emit(ctx, *report, o.report);
  if (json) {
    emit(ctx, *json, text);
  } else {
    ctx.out << text;
  }
  return r.stable ? 0 : 1;
}

const CommandRegistration reg{
    {"milling-stability", "robot and tool modes at a pose; chatter stability lobes of the cut",
     "usage: roprec milling-stability --cell CELL.xml [--joints \"j1 .. j6\"] [--csv F.csv]\n"
     "                                [--report F.html] [--json F.json] [--rpm \"LO HI\"] "
     "[--steps N]\n"
     "                                [--tool N]\n\n"
     "The linearised dynamics at the tool of the cell's milling process: with --joints (deg) the\n"
     "robot's modes at that pose (multibody mass matrix, joint stiffness in series with the "
     "servo,\n"
     "<dynamics robot_damping_ratio>), always the spindle/tool mode of <dynamics> (defaults are\n"
     "stated estimates). JSON: the modes (frequency, damping, TCP direction and stiffness, joint\n"
     "shape), the static compliance, the zero-order chatter limit at the cut's spindle speed\n"
     "(ap_limit_mm, chatter_frequency_Hz, margin = limit/ap).\n"
     "--csv writes the lobe diagram: spindle_rpm,ap_limit_mm,chatter_Hz,lobe over --rpm (default\n"
     "0.2-2 x the cut's speed, --steps speeds, default 400); --report an HTML plot of it.\n"
     "--tool N: the mill of the cell's tool table (<mill tool=\"N\">, its cut and TCP); needed\n"
     "when the cell has several mills.\n"
     "Exit 0 the cut is stable; 1 the cut's ap is above the limit (chatter); 2 bad input.\n",
     41, run}};

}  // namespace
}  // namespace roprec::cli
