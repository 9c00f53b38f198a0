/// `roprec predict`: per-hole deviation, uncertainty budget, tolerance verdict and capability.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/platform.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/verify.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/json.hpp"

namespace roprec::cli {
namespace {

/// What the summary and the failure list need of the holes, gathered while they stream past.
struct HoleDigest {
  double axis_max{0};
  double axis_sum{0};
  int axis_n{0};
  size_t failed{0};
  bool list{true};                    ///< keep the failures' lines (not with --quiet)
  std::vector<std::string> failures;  ///< "hole ID (FILE:LINE): verdict: reason"

  void add(const HolePrediction& h, const HoleRequest& q, const std::string& program) {
    if (h.nominal_axis_error) {
      axis_max = std::max(axis_max, *h.nominal_axis_error);
      axis_sum += *h.nominal_axis_error;
      ++axis_n;
    }
    if (h.status == HoleStatus::kOk) return;
    ++failed;
    if (!list) return;
    failures.push_back(api::holeWhere(h.id, q.line, program) + ": " +
                       verdictAndReason(h.verdict, h.reason));
  }
};

void printSummary(CommandContext& ctx, const CapabilitySummary& sum, const HoleDigest& d) {
  ctx.err << "roprec predict: " << sum.holes << " holes: " << sum.conforms << " conform, "
          << sum.conforms_after_compensation << " conform after compensation, " << sum.not_capable
          << " not capable, " << (sum.unreachable + sum.singular + sum.not_converged)
          << " not handled\n";
  ctx.err << "  the robot can take " << sum.robot_can_take
          << " holes = " << formatNumber(sum.mc_time_taken, 0) << " s of machining-center time (of "
          << formatNumber(sum.mc_time_total, 0) << " s)\n";
  if (d.axis_n > 0) {
    ctx.err << "  real drill points from the nominal hole axes: mean "
            << formatNumber(d.axis_sum / d.axis_n * 1e6, 3) << " µm, max "
            << formatNumber(d.axis_max * 1e6, 3) << " µm (" << d.axis_n << " holes)\n";
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
  opt.threads = parseThreadsOption(args);
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (pos.size() != 1) throw UsageError("give exactly one PROGRAM_OR_HOLES file");
  if (json_out && report_out && *json_out == *report_out)
    throw UsageError("--json and --report name the same file " + *json_out);
  opt.holes = holes;
  opt.uncertainty = uncertainty.value_or("");
  if (match_tol) opt.match_tol_mm = parseNumberList(*match_tol, 1, "--match-tol (mm)")[0];

  Progress progress(ctx, "predicting holes", 0);
  const ProgressFn step = [&](size_t done, size_t total) { progress.step(done, total); };
  HoleDigest digest;
  digest.list = !ctx.quiet;  // printed only without --quiet: not kept with it
  std::vector<std::string> notes;
  CapabilitySummary summary;
  const bool to_file = json_out && *json_out != "-";
  // The JSON is written hole by hole, its text not kept: to the staged output file (committed
  // when complete) or, with --json -, straight to stdout as it is made.
  auto produce = [&](const ByteWriter& write) {
    std::optional<PredictionJsonStream> js;
    // the report keeps a compact record of each hole (and its δrobot split) as they stream past
    std::optional<PredictionReportStream> report;
    PredictionResult r = predictJobStreaming(
        *cell, pos[0], opt,
        [&](size_t, std::span<const HolePrediction> block, std::span<const HoleRequest> reqs,
            int threads) {
          if (json_out) js->holes(block, reqs, threads);  // formatted on the workers
          if (report) report->holes(block, reqs, threads);
          for (size_t k = 0; k < block.size(); ++k) digest.add(block[k], reqs[k], pos[0]);
        },
        [&](const PredictionContext& c) {
          js.emplace(c, write);
          if (report_out) report.emplace(c, resolvedThreads(opt.threads));
        },
        step);
    js->finish(r.summary);
    if (report) {  // written as it is rendered: no whole-document string
      writeFileAtomicStream(*report_out, [&](const ByteWriter& w) { report->finish(r, w); });
    }
    notes = r.context.job.notes;
    summary = r.summary;
    keepUntilExit(std::move(r));
  };
  if (to_file) {
    writeFileAtomicStream(*json_out, produce);
  } else if (json_out) {
    produce([](std::string_view b) {
      if (const int e = writeStdout(b); e != 0)
        throw std::runtime_error(std::string("cannot write to standard output: ") +
                                 platform::errorText(e));
    });
  } else {
    produce([](std::string_view) {});  // no JSON asked for: the summary only
  }
  progress.finish();
  printJobNotes(ctx, notes);

  if (!ctx.quiet) {
    for (const std::string& f : digest.failures) ctx.err << "roprec: " << f << "\n";
  }
  if (!ctx.quiet) printSummary(ctx, summary, digest);
  return digest.failed == 0 ? 0 : 1;
}

const CommandRegistration reg{
    {"predict", "per-hole deviation, uncertainty, tolerance verdict and capability",
     "usage: roprec predict --cell CELL.xml PROGRAM_OR_HOLES [--json OUT.json|-] [--report "
     "OUT.html]\n"
     "                      [--holes HOLES.csv] [--uncertainty linear|montecarlo] [--quiet]\n"
     "                      [--frame cell|\"x y z a b c\"|'REF=x y z a b c;...'] [--tool "
     "program|cell]\n"
     "                      [--threads N]\n\n"
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
     "Prints a summary; --json OUT.json writes the JSON (--json - to stdout); --report writes one\n"
     "self-contained HTML file. The JSON (file or stdout) is written a block of holes at a time,\n"
     "its text not kept. A KUKA KRL program is read twice by windows of whole lines (every hole\n"
     "checked first, then set up, predicted and written): memory does not grow with the number of\n"
     "holes (a 1,000,000-hole .src: ~100 MB peak; its .dat is read whole), except for the lines "
     "of\n"
     "the holes that cannot be handled, kept for the list on stderr (not with --quiet). Other\n"
     "dialects, hole lists and --holes keep the holes read and their set-up, about 1.5 kB a hole;\n"
     "--report keeps what the report shows of each hole, about 0.8 kB a hole; beyond 2,000 holes\n"
     "its table row and what the maps show of it (about 0.7 kB a hole in all).\n"
     "--threads N: worker threads for the per-hole work (0 = every core; default 1); the output "
     "is\n"
     "byte-identical for any N.\n"
     "A base frame only the controller defines (FANUC UFRAME[n], KUKA BASE_DATA[n]) needs --frame\n"
     "(its pose in the robot base frame, mm/deg KUKA A-B-C; REF=... by name; cell = the cell's\n"
     "<workobject>); a program tool that differs from the cell's, or is defined only on the\n"
     "controller (UTOOL[n], TOOL_DATA[n]), needs --tool program|cell. Without them: exit 2.\n"
     "The resolution is printed on stderr and stated in the JSON notes and the report header.\n"
     "A cell with <part_registration> (verify --write-cell): every hole is aimed where the\n"
     "registration found the part, as compensate aims it; the nominal positions are the\n"
     "registered holes and the deviations those of compensate's \"before\".\n"
     "Exit 1 if some holes could not be handled (listed on stderr), 2 for bad input.\n",
     40, run}};

}  // namespace
}  // namespace roprec::cli
