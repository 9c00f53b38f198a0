/// `roprec plan-test`: a D-optimal drilling test program for re-identifying the robot, in the
/// cell's dialect or as a hole list.
#include <cmath>
#include <sstream>

#include "compensator/support/error.hpp"
#include "plugin/api/plan_test.hpp"
#include "plugin/cli/cli.hpp"

namespace roprec::cli {
namespace {

/// Comma-separated groups of `n` numbers ("0 0 -1, 0 1 0").
std::vector<Eigen::VectorXd> parseGroups(const std::string& text, int n, const std::string& what) {
  std::vector<Eigen::VectorXd> out;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, ',');)
    out.push_back(parseNumberList(part, n, what));
  if (out.empty()) throw UsageError(what + ": nothing given");
  return out;
}

/// Whitespace-separated numbers, any count ≥ 1.
std::vector<double> parseList(const std::string& text, const std::string& what) {
  std::istringstream ss(text);
  std::vector<std::string> words;
  for (std::string w; ss >> w;) words.push_back(w);
  if (words.empty()) throw UsageError(what + ": nothing given");
  const Eigen::VectorXd v = parseNumberList(text, static_cast<int>(words.size()), what);
  return {v.data(), v.data() + v.size()};
}

PlanTestOptions parseOptions(Args& args) {
  PlanTestOptions o;
  if (const auto d = args.option("directions")) {
    o.directions.clear();
    for (const auto& v : parseGroups(*d, 3, "--directions (i j k, ...)"))
      o.directions.emplace_back(v[0], v[1], v[2]);
  }
  if (const auto p = args.option("psi")) o.psi_deg = parseList(*p, "--psi (deg ...)");
  if (const auto n = args.option("per-axis")) {
    const double v = parseNumberList(*n, 1, "--per-axis")[0];
    if (v != std::floor(v)) throw UsageError("--per-axis must be a whole number");
    o.per_axis = static_cast<int>(v);
  }
  if (const auto r = args.option("register")) {
    const auto g = registrationFromName(*r);
    if (!g) throw UsageError("--register must be none, translation or rigid");
    o.registration = *g;
  }
  if (const auto g = args.option("identify")) {
    if (*g != "all" && *g != "stiffness")
      throw UsageError("--identify must be all (geometry and stiffness) or stiffness");
    o.geometry = *g == "all";
  }
  if (const auto s = args.option("sigma")) o.sigma_um = parseNumberList(*s, 1, "--sigma (µm)")[0];
  if (const auto s = args.option("depth")) o.depth_mm = parseNumberList(*s, 1, "--depth (mm)")[0];
  if (const auto s = args.option("diameter"))
    o.diameter_mm = parseNumberList(*s, 1, "--diameter (mm)")[0];
  return o;
}

/// Expected σ per geometry group, the predicted accuracy, unobservable parameters (a warning).
void printGeometryPlan(CommandContext& ctx, const PlanTestResult& r) {
  const std::vector<PlanGroupSigma> groups = geometryGroups(r.plan);
  if (groups.empty()) return;
  ctx.out << "  expected geometry uncertainty (largest component, prior -> expected):\n";
  for (const PlanGroupSigma& g : groups) {
    ctx.out << "    " << g.group << ": " << formatNumber(g.prior_xyz * 1e3, 3) << " -> "
            << formatNumber(g.expected_xyz * 1e3, 3) << " mm, "
            << formatNumber(g.prior_rpy * 1e3, 3) << " -> " << formatNumber(g.expected_rpy * 1e3, 3)
            << " mrad\n";
  }
  ctx.out << "  predicted accuracy of the model over the region (1 σ, in-plane): "
          << formatNumber(r.plan.prior_accuracy * 1e6, 1) << " µm before calibration -> "
          << formatNumber(r.plan.predicted_accuracy * 1e6, 1) << " µm after\n";
  for (const auto& d : r.plan.dependencies)
    ctx.out << "  dependent (not separable by any measurement of this kind): " << d << "\n";
  if (!r.plan.unobservable.empty()) {
    std::string names;
    for (const auto& n : r.plan.unobservable) names += (names.empty() ? "" : ", ") + n;
    ctx.err << "roprec: warning: the region and directions leave " << r.plan.unobservable.size()
            << " robot parameters unobservable (they keep their prior): " << names
            << "; hint: add drilling directions, rotations about the drill axis (--psi) or a "
               "larger region\n";
  }
}

void printPlan(CommandContext& ctx, const PlanTestResult& r, const postproc::DrillProgramText& t) {
  ctx.out << "roprec plan-test: " << r.holes.size() << " holes chosen D-optimally from "
          << r.candidates.size() << " candidates (" << r.plan.rejected.size()
          << " not admissible), " << postproc::dialectName(t.dialect) << ", log det "
          << formatNumber(r.plan.log_det, 3) << "\n";
  ctx.out
      << "  expected joint stiffness uncertainty after measuring them (σ/k, prior -> expected):\n";
  for (int j = 0; j < 6; ++j) {
    ctx.out << "    k" << j + 1 << " = "
            << formatNumber(r.context.robot.card.joints[static_cast<size_t>(j)].stiffness, 0)
            << " N·m/rad: " << formatNumber(100 * r.plan.prior_sigma_rel[j], 1) << " % -> "
            << formatNumber(100 * r.plan.expected_sigma_rel[j], 2) << " % (σ "
            << formatNumber(r.plan.expected_sigma_k[j], 0) << " N·m/rad)\n";
  }
  printGeometryPlan(ctx, r);
  for (const auto& n : t.notes) ctx.out << "  note: " << n << "\n";
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto region = args.option("region");
  const auto count = args.option("count");
  const auto out = args.option("o");
  const PlanTestOptions opt = parseOptions(args);
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (!region) throw UsageError("give --region \"x0 y0 z0 x1 y1 z1\" (mm, workobject frame)");
  if (!count) throw UsageError("give --count N");
  if (!out) throw UsageError("give -o TEST_PROGRAM (or a .csv hole list)");
  if (!pos.empty()) throw UsageError("unexpected argument '" + pos[0] + "'");
  const Eigen::VectorXd b = parseNumberList(*region, 6, "--region (x0 y0 z0 x1 y1 z1, mm)");
  const double n = parseNumberList(*count, 1, "--count")[0];
  if (n != std::floor(n) || n < 1 || n > 10000)
    throw UsageError("--count must be a whole number >= 1");

  const PlanTestResult r = planTestJob(*cell, b.head<3>(), b.tail<3>(), static_cast<int>(n), opt);
  const postproc::DrillProgramText t = planTestProgram(r, *out);
  const std::vector<std::string> written = postproc::saveDrillProgram(t, *out);
  if (!ctx.quiet) {
    printPlan(ctx, r, t);
    for (const auto& p : written) ctx.out << "  wrote " << p << "\n";
  }
  return 0;
}

const CommandRegistration reg{
    {"plan-test", "D-optimal drilling test program for re-identifying the joint stiffness",
     "usage: roprec plan-test --cell CELL.xml --region \"x0 y0 z0 x1 y1 z1\" --count N -o OUT\n"
     "                        [--directions \"i j k, i j k\"] [--psi \"0 90\"] [--per-axis 4]\n"
     "                        [--register none|translation|rigid] [--sigma UM] [--depth MM]\n"
     "                        [--diameter MM] [--identify all|stiffness] [--quiet]\n\n"
     "Candidate drill points (hole bottoms) on a grid of --per-axis points per axis over the "
     "region\n"
     "(workobject frame, mm; an axis with x0 = x1 gets one point), each with every drilling\n"
     "direction (--directions, workobject frame, default \"0 0 -1\") and every rotation about it\n"
     "(--psi, deg, default \"0 90\"). Each candidate is predicted (IK nearest the reference "
     "pose);\n"
     "unreachable or singular ones are dropped. N holes are chosen greedily to maximise the\n"
     "information on the joint compliances (D-optimal: log det of the posterior information, the\n"
     "registration of --register eliminated as nuisance), assuming a residual σ of --sigma µm (5)\n"
     "per axis. Prints the expected σ of each joint stiffness after the test.\n"
     "--identify all (default): the criterion covers the geometry too (per joint origin δxyz and\n"
     "δrpy, the tip; prior 0.3 mm / 0.5 mrad); prints the expected σ per geometry group, the\n"
     "predicted accuracy of the model over the candidates before and after calibration, the exact\n"
     "dependencies, and warns (stderr) about robot parameters the plan leaves unobservable.\n"
     "--identify stiffness: the joint compliances alone (the criterion before geometry).\n"
     "OUT is written in the cell robot's dialect (KUKA .src + .dat, ABB .mod, FANUC .ls), or as a\n"
     "hole list when OUT ends in .csv: holes V01…, the OLP drill cycle of the sample jobs, depth\n"
     "--depth mm (the cell's process depth) with the cell's drill (--diameter), frames and tool\n"
     "from the cell, the planned configuration stated. Exit 2 for bad input.\n",
     56, run}};

}  // namespace
}  // namespace roprec::cli
