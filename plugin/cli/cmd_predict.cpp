/// `roprec predict`: per-hole deviation, uncertainty budget, tolerance verdict and capability.
#include <algorithm>
#include <filesystem>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/json.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "plugin/api/report.hpp"

namespace roprec::cli {
namespace {

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto json_out = args.option("json");
  const auto report_out = args.option("report");
  const auto holes = args.option("holes");
  const auto uncertainty = args.option("uncertainty");
  const auto match_tol = args.option("match-tol");
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (pos.size() != 1) throw UsageError("give exactly one PROGRAM_OR_HOLES file");
  const double tol = match_tol ? parseNumberList(*match_tol, 1, "--match-tol (mm)")[0] : 0.5;
  const PredictionContext c = loadPredictionContext(*cell, pos[0], holes, uncertainty.value_or(""), tol);

  PredictionData data(c.model);
  std::vector<HolePrediction> preds;
  preds.reserve(c.job.requests.size());
  Progress progress(ctx, "predicting holes", c.job.requests.size());
  std::optional<nc::Vec6> prev;
  for (size_t i = 0; i < c.job.requests.size(); ++i) {
    preds.push_back(predictHole(c.model, data, c.job.requests[i], prev ? &*prev : nullptr));
    if (preds.back().status == HoleStatus::kOk) prev = preds.back().joints;
    progress.step(i + 1);
  }
  progress.finish();
  const CapabilitySummary sum = summarize(preds);

  Json root = Json::object();
  root.set("robot", Json::str(c.robot.card.name));
  root.set("cell", Json::str(c.cell.name));
  root.set("program", Json::str(std::filesystem::path(pos[0]).filename().string()));
  root.set("process", Json::str(c.process_description));
  Json u = Json::object();
  u.set("method", Json::str(uncertaintyMethodText(c.model.uncertainty)));
  u.set("stiffness_rel", Json::number(c.model.uncertainty.stiffness_rel, 4));
  u.set("position_gain_rel", Json::number(c.model.uncertainty.position_gain_rel, 4));
  u.set("process_halfwidth", Json::number(c.model.uncertainty.process_halfwidth, 4));
  u.set("coverage", Json::str("2-D radial 95 % (Rayleigh), k = 2.4477"));
  u.set("source", Json::str(c.model.uncertainty.source));
  root.set("uncertainty_inputs", u);
  Json notes = Json::array();
  for (const auto& n : c.job.notes) notes.push(Json::str(n));
  root.set("notes", notes);
  Json hs = Json::array();
  for (size_t i = 0; i < preds.size(); ++i) hs.push(holeJson(preds[i], c.job.requests[i]));
  root.set("holes", hs);
  root.set("summary", summaryJson(sum));

  if (report_out) {
    ReportInput in;
    in.title = "roprec prediction — " + std::filesystem::path(pos[0]).filename().string();
    in.robot = c.robot.card.name + (c.robot.card.model.empty() ? "" : " (" + vendorName(c.robot.card.vendor) + " " + c.robot.card.model + ")");
    in.cell = c.cell.name + " (" + c.cell.file + ")";
    in.program = pos[0];
    in.process = c.process_description;
    in.uncertainty_method = uncertaintyMethodText(c.model.uncertainty);
    in.uncertainty_source = c.model.uncertainty.source;
    in.default_tolerance_mm = c.cell.tolerance_mm;
    in.summary = sum;
    for (size_t i = 0; i < preds.size(); ++i) {
      ReportHole rh;
      rh.prediction = &preds[i];
      rh.T_W_tcp = c.job.requests[i].T_W_tcp;
      in.holes.push_back(rh);
    }
    writeFileAtomic(*report_out, renderReport(in));
  }
  emit(ctx, json_out.value_or(""), root.dump());

  int failed = 0;
  for (size_t i = 0; i < preds.size(); ++i) {
    const HolePrediction& h = preds[i];
    if (h.status == HoleStatus::kOk) continue;
    ++failed;
    if (!ctx.quiet) {
      const HoleRequest& r = c.job.requests[i];
      ctx.err << "roprec: hole " << h.id;
      if (r.line > 0) ctx.err << " (" << pos[0] << ":" << r.line << ")";
      ctx.err << ": " << verdictName(h.verdict) << ": " << h.reason << "\n";
    }
  }
  if (!ctx.quiet && json_out) {
    ctx.err << "roprec predict: " << sum.holes << " holes: " << sum.conforms << " conform, "
            << sum.conforms_after_compensation << " conform after compensation, " << sum.does_not_conform
            << " do not conform, " << (sum.unreachable + sum.singular + sum.not_converged) << " not handled\n";
    ctx.err << "  the robot can take " << sum.robot_can_take << " holes = " << formatNumber(sum.mc_time_taken, 0)
            << " s of machining-center time (of " << formatNumber(sum.mc_time_total, 0) << " s)\n";
    double mx = 0;
    double mean = 0;
    int n = 0;
    for (const HolePrediction& h : preds) {
      if (!h.nominal_axis_error) continue;
      mx = std::max(mx, *h.nominal_axis_error);
      mean += *h.nominal_axis_error;
      ++n;
    }
    if (n > 0) {
      ctx.err << "  real drill points from the nominal hole axes: mean " << formatNumber(mean / n * 1e6, 3)
              << " µm, max " << formatNumber(mx * 1e6, 3) << " µm (" << n << " holes)\n";
    }
  }
  return failed ? 1 : 0;
}

const CommandRegistration reg{
    {"predict", "per-hole deviation, uncertainty, tolerance verdict and capability",
     "usage: roprec predict --cell CELL.xml PROGRAM_OR_HOLES [--json OUT.json] [--report OUT.html]\n"
     "                      [--holes HOLES.csv] [--uncertainty linear|montecarlo] [--quiet]\n\n"
     "For every hole of a drilling program (KUKA .src, ABB .mod/.prg, FANUC .ls, CSV/JSON targets) or a\n"
     "hole-list CSV: the IK solution the program's configuration selects (hole lists: the admissible\n"
     "solution nearest the previous hole's), δrobot under gravity, tool weight and the steady process\n"
     "wrench, δmach, δwork = δrobot + δmach, the position error ⊥ the hole axis and the axis tilt, the\n"
     "uncertainty budget U_robot, U_mach, U_work (2-D radial 95 %, k = 2.4477) and the ISO 14253-1\n"
     "verdict against the hole's position tolerance (hole list, else the cell's <tolerance>):\n"
     "conforms | conforms-after-compensation | does-not-conform | unreachable | singular.\n"
     "--holes: a hole list matched to the program's holes (ids, diameters, depths, tolerances) by id,\n"
     "else by position within --match-tol mm (0.5); the JSON then reports from_nominal_axis, the real\n"
     "drill point's distance from the nominal hole axis (the residual of a compensated program).\n"
     "JSON to stdout unless --json; --report writes one self-contained HTML file.\n"
     "Exit 1 if some holes could not be handled (listed on stderr), 2 for bad input.\n",
     40, run}};

}  // namespace
}  // namespace roprec::cli
