/// `roprec compensate`: pre-offset the drill targets so the predicted real holes land on the
/// nominal ones; optionally choose the rotation about each drill axis; write the corrected
/// program in its own dialect (only the compensated targets' bytes change), the corrected-target
/// export and the report.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/milling_files.hpp"
#include "plugin/api/outputs_together.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/cli/robot_options.hpp"
#include "plugin/report/milling_report.hpp"
#include "postproc/edited_file_writer.hpp"
#include "postproc/program.hpp"

namespace roprec::cli {
namespace {

CompensationOptions parseCompensationOptions(Args& args) {
  CompensationOptions opt;
  const std::string mode = args.option("orientation").value_or("keep");
  if (mode == "keep") {
    opt.mode = OrientationMode::kKeep;
  } else if (mode == "flip-free") {
    opt.mode = OrientationMode::kFlipFree;
  } else if (mode == "stiffest") {
    opt.mode = OrientationMode::kStiffest;
  } else {
    throw UsageError("--orientation must be keep, flip-free or stiffest");
  }
  if (const auto w = args.option("wrist-margin"))
    opt.wrist_margin = parseNumberList(*w, 1, "--wrist-margin (deg)")[0] * kDeg;
  if (const auto j = args.option("jump-threshold")) {
    opt.jump_threshold = parseNumberList(*j, 1, "--jump-threshold (deg)")[0] * kDeg;
  }
  if (const auto grid = args.option("grid")) {
    const double g = parseNumberList(*grid, 1, "--grid")[0];
    if (g < 4 || g > 720) throw UsageError("--grid must lie in [4, 720]");
    opt.grid = static_cast<int>(g);
  }
  if (!(opt.wrist_margin >= 0) || !(opt.jump_threshold > 0))
    throw UsageError("--wrist-margin >= 0, --jump-threshold > 0");
  opt.allow_branch_change = args.flag("allow-branch-change");
  return opt;
}

std::optional<std::array<int, 3>> parseTurnAxes(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  const Eigen::VectorXd ax = parseNumberList(*text, 3, "--turn-axes (three joint numbers)");
  std::array<int, 3> a{};
  for (int i = 0; i < 3; ++i) {
    if (ax[i] < 1 || ax[i] > 6 || ax[i] != std::floor(ax[i]))
      throw UsageError("--turn-axes: joint numbers 1..6");
    a[static_cast<size_t>(i)] = static_cast<int>(ax[i]);
  }
  return a;
}

/// Milling: compensateMillingFiles (plugin/api/milling_files.hpp), its notes, failures,
/// summary and chatter lines printed.
int runMillingPath(CommandContext& ctx, const MillingFilesJob& job) {
  const MillingFilesResult res = compensateMillingFiles(
      job, [&](const MillingCompensationResult& r) { printJobNotes(ctx, r.context.job.notes); });
  const MillingCompensationResult& r = res.job;
  const size_t points = r.pointCount();
  for (const auto& f : r.failures) ctx.err << "roprec: " << f << "\n";
  if (!r.failures.empty()) {
    ctx.err << "roprec: " << r.failures.size() << " of " << points
            << " path points could not be compensated; nothing written\n";
    return 1;
  }
  if (!r.refused.empty()) {
    for (const auto& x : r.refused) ctx.err << "roprec: " << x << "\n";
    ctx.err << "roprec: the writer refused " << r.refused.size()
            << " target edits; nothing written\n";
    return 1;
  }
  const MillingReportSummary& sum = res.summary;
  if (!ctx.quiet) {
    ctx.out << "roprec compensate (milling path): " << points << " path points compensated\n";
    ctx.out << "  deviation before (coupled force) max " << formatNumber(sum.before * 1e6, 3)
            << " µm; predicted residual max " << formatNumber(sum.after * 1e6, 4) << " µm\n";
    ctx.out << "  surface error normal to the wall max " << formatNumber(sum.wall_before * 1e6, 3)
            << " µm before; " << formatNumber(sum.wall_after * 1e6, 4) << " µm compensated\n";
    for (const auto& pth : res.written) ctx.out << "  wrote " << pth << "\n";
  }
  ctx.err << res.unstable_lines;
  if (res.unstable > 0)
    ctx.err << "roprec: " << res.unstable
            << " cutting path points are above the chatter limit (outputs "
            << "written; the static compensation does not remove chatter)\n";
  return res.unstable > 0 ? 1 : 0;
}

std::string stat(std::vector<double> v) {
  if (v.empty()) return "n/a";
  std::sort(v.begin(), v.end());
  double mean = 0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  return "mean " + cFixed(mean, 3) + ", max " + cFixed(v.back(), 3);
}

void printSummary(CommandContext& ctx, const CompensationResult& r, const CompensationOptions& opt,
                  const std::vector<std::string>& written) {
  const CompensationResult::Stats& s = r.summary;
  ctx.out << "roprec compensate (" << r.orientation << "): " << r.hole_count << " holes, "
          << (r.hole_count - static_cast<size_t>(r.failed)) << " compensated\n";
  ctx.out << "  position error ⊥ axis before [µm]: " << stat(s.error_before_um) << "\n";
  ctx.out << "  predicted residual after    [µm]: " << stat(s.residual_after_um) << "\n";
  ctx.out << "  holes conforming (ISO 14253-1): before " << s.conform_before << ", after "
          << s.conform_after << "\n";
  ctx.out << "  axis-4/6 jumps > " << formatNumber(opt.jump_threshold / kDeg, 0)
          << " deg between holes of a face: before " << s.jumps_before << ", after "
          << s.jumps_after << "\n";
  ctx.out << "  rotation about the drill axis changed at " << r.stats.psi_changed << " holes";
  if (r.stats.psi_changed > 0) {
    ctx.out << " (joint limits " << r.stats.psi_for_limits << ", wrist margin "
            << r.stats.psi_for_wrist << ", jumps " << r.stats.psi_for_jumps << ", stiffness "
            << r.stats.psi_for_stiffness << "; reasons in the export)";
  }
  ctx.out << "\n  configuration flags changed at " << r.stats.config_changed
          << " holes (reasons in the export)\n";
  if (r.stats.stiffness_compared > 0) {
    const double n = r.stats.stiffness_compared;
    ctx.out << "  U_work [µm]: mean " << cFixed(r.stats.U_work_sum / n * 1e6, 3) << " (keep "
            << cFixed(r.stats.U_work_keep_sum / n * 1e6, 3) << "), largest gain at a hole "
            << cFixed(r.stats.U_work_gain_max * 1e6, 3) << "\n";
  }
  if (r.stats.relaxed_jumps)
    ctx.out << "  note: no orientation sequence met the jump threshold; it was relaxed\n";
  if (r.stats.relaxed_wrist > 0) {
    ctx.out << "  note: at " << r.stats.relaxed_wrist
            << " holes no rotation about the drill axis meets |θ5| ≥ "
            << formatNumber(opt.wrist_margin / kDeg, 0) << "° (flagged in the export)\n";
  }
  for (const auto& p : written) ctx.out << "  wrote " << p << "\n";
}

/// A hole that was not compensated, for the messages after the job.
struct NotCompensated {
  std::string id;
  int line{0};
  std::string reason;
};

void printNotCompensated(CommandContext& ctx, const std::string& program,
                         const std::vector<NotCompensated>& failed) {
  for (const NotCompensated& f : failed) {
    ctx.err << "roprec: hole " << f.id;
    if (f.line > 0) ctx.err << " (" << program << ":" << f.line << ")";
    ctx.err << ": not compensated: " << f.reason << "\n";
  }
}

/// Stages `path` into `set` with the bytes `produce` writes, or runs produce with no writer
/// (nullptr) when there is no such output.
void stageOptional(OutputSet& set, const std::optional<std::string>& path,
                   const std::function<void(const ByteWriter*)>& produce) {
  if (!path) {
    produce(nullptr);
    return;
  }
  set.stageStream(*path, [&](const ByteWriter& write) { produce(&write); });
}

/// The end of a streamed compensate: the job's messages, then the staged outputs `sets` handed
/// to the command's set (or committed) when the program may be written.
int finishStreaming(CommandContext& ctx, const CompensationResult& r, const CompensationJob& job,
                    const std::string& program, const std::vector<std::string>& prog_outs,
                    const std::optional<std::string>& targets,
                    const std::vector<NotCompensated>& failed,
                    std::initializer_list<OutputSet*> sets) {
  printJobNotes(ctx, r.context.job.notes);
  printNotCompensated(ctx, program, failed);
  for (const auto& x : r.refused) ctx.err << "roprec: " << x << "\n";
  if (!r.writable) {
    ctx.err << "roprec: " << r.why_not_writable << "\n";
    return 1;  // the sets' temporaries are removed with them
  }
  std::vector<std::string> written = prog_outs;
  for (OutputSet* set : sets) {
    if (OutputSet* active = activeOutputSet()) {
      active->adopt(std::move(*set));
    } else {
      set->commit();
    }
  }
  if (targets) written.push_back(*targets);
  if (!ctx.quiet) printSummary(ctx, r, job.options, written);
  return r.failed ? 1 : 0;
}

/// compensate without a report, in bounded memory for the per-hole results: the holes are
/// compensated a block at a time and each block goes to its outputs at once — the program's first
/// file written up to the bytes no later edit changes (EditedFileWriter), the targets export's
/// rows — into temporaries of sets of its own, handed to the command's set (the same files, bytes
/// and commit order as the whole-result path) only when the program may be written.
int runStreaming(CommandContext& ctx, CompensationResult& r, const CompensationJob& job,
                 const std::string& program, const std::string& out,
                 const std::optional<std::string>& targets, bool csv, int threads) {
  postproc::Program& prog = *r.context.job.program;
  const std::vector<std::string> prog_outs = postproc::outputPaths(prog, out);
  std::vector<NotCompensated> failed;
  OutputSet program_set;
  OutputSet targets_set;
  program_set.stageStream(out, [&](const ByteWriter& write_src) {
    postproc::EditedFileWriter src(prog, 0, write_src);
    stageOptional(targets_set, targets, [&](const ByteWriter* write_targets) {
      std::optional<CompensationTargetsStream> export_rows;
      if (write_targets)
        export_rows.emplace(r.context, r.orientation, program, csv, *write_targets, threads);
      compensateLoadedStreaming(
          r, job,
          [&](CompensationResult& res, size_t first, std::span<const HoleCompensation> holes,
              size_t stable) {
            const std::span<const HoleRequest> req =
                std::span<const HoleRequest>(res.context.job.requests).subspan(first, holes.size());
            for (size_t k = 0; k < holes.size(); ++k) {
              if (!holes[k].ok) failed.push_back({holes[k].id, req[k].line, holes[k].reason});
            }
            src.flushBefore(stable);
            if (export_rows) export_rows->holes(holes, req);
          });
      if (export_rows && r.writable) export_rows->finish();
    });
    if (r.writable) src.finish();
  });
  if (r.writable && prog_outs.size() > 1) {  // the .dat (KRL), whole: its edits are all made
    std::string dat;
    postproc::EditedFileWriter w(prog, 1, [&](std::string_view b) { dat.append(b); });
    w.finish();
    program_set.stage(prog_outs[1], dat);
  }
  return finishStreaming(ctx, r, job, program, prog_outs, targets, failed,
                         {&program_set, &targets_set});
}

/// compensate of a KRL program read by windows (compensationStreams), without a report: the
/// holes' requests are set up first (the sequence is chosen over the whole program), then each
/// block of compensated holes goes to its outputs at once, as runStreaming does, while the
/// program is read again and edited window by window: the program is never held whole.
int runStreamedProgram(CommandContext& ctx, CompensationResult& r, const CompensationJob& job,
                       const std::string& program, const std::string& out,
                       const std::optional<std::string>& targets, bool csv, int threads) {
  const std::vector<std::string> prog_outs = postproc::outputPaths(*r.context.job.program, out);
  std::vector<NotCompensated> failed;
  OutputSet program_set;
  OutputSet targets_set;
  std::optional<std::string> dat;
  program_set.stageStream(out, [&](const ByteWriter& write_src) {
    stageOptional(targets_set, targets, [&](const ByteWriter* write_targets) {
      std::optional<CompensationTargetsStream> export_rows;
      if (write_targets)
        export_rows.emplace(r.context, r.orientation, program, csv, *write_targets, threads);
      compensateStreamedProgram(
          r, job, write_src, dat,
          [&](size_t, std::span<const HoleCompensation> holes, std::span<const HoleRequest> req) {
            for (size_t k = 0; k < holes.size(); ++k) {
              if (!holes[k].ok) failed.push_back({holes[k].id, req[k].line, holes[k].reason});
            }
            if (export_rows) export_rows->holes(holes, req);
          });
      if (export_rows && r.writable) export_rows->finish();
    });
  });
  if (r.writable && prog_outs.size() > 1 && dat) program_set.stage(prog_outs[1], *dat);
  return finishStreaming(ctx, r, job, program, prog_outs, targets, failed,
                         {&program_set, &targets_set});
}

/// Whether a file of the compensated program (OUT, its .dat) is one of the program's input files.
bool overwritesInput(const CompensationResult& r, const std::string& out) {
  try {
    refuseOverwritingInput(*r.context.job.program,
                           postproc::outputPaths(*r.context.job.program, out));
  } catch (const UsageError&) {
    return true;
  }
  return false;
}

/// runStreamedProgram when the outputs are distinct and none is an input file, else -1 (the
/// whole-program path then says what is wrong, after the job, as it always has).
int streamedRun(CommandContext& ctx, CompensationResult& r, const CompensationJob& job,
                const std::string& program, const std::string& out,
                const std::optional<std::string>& targets, bool csv, int threads) {
  std::vector<std::string> outs = postproc::outputPaths(*r.context.job.program, out);
  if (targets) outs.push_back(*targets);
  std::sort(outs.begin(), outs.end());
  if (std::adjacent_find(outs.begin(), outs.end()) != outs.end()) return -1;
  if (overwritesInput(r, out)) return -1;
  if (targets) {
    try {
      refuseOverwritingInput(*r.context.job.program, {*targets});
    } catch (const UsageError&) {
      return -1;
    }
  }
  return runStreamedProgram(ctx, r, job, program, out, targets, csv, threads);
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto out = args.option("o");
  const auto targets = args.option("targets");
  const auto report = args.option("report");
  CompensationJob job;
  job.job.holes = args.option("holes");
  job.job.fanuc_turn_axes = parseTurnAxes(args.option("turn-axes"));
  parseFrameTool(args, job.job);
  job.options = parseCompensationOptions(args);
  job.allow_partial = args.flag("allow-partial");
  job.force = args.flag("force");
  job.job.threads = parseThreadsOption(args);
  const std::vector<std::string> pos = args.positionals();
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (!out) throw UsageError("give -o OUT (the corrected program)");
  if (pos.size() != 1) throw UsageError("give exactly one PROGRAM file");
  {  // cheap early check (writeCompensatedProgram checks every output against every input file)
    std::error_code ec;
    if (std::filesystem::exists(*out, ec) && std::filesystem::equivalent(*out, pos[0], ec))
      throw UsageError("output " + *out + " is the input file " + pos[0] +
                       ": write the compensated program to another file (nothing written)");
  }
  if (cellIsMilling(*cell)) {
    MillingFilesJob milling;
    milling.cell = *cell;
    milling.program = pos[0];
    milling.out = *out;
    milling.targets = targets;
    milling.report = report;
    milling.force = job.force;
    milling.threads = resolvedThreads(job.job.threads);
    return runMillingPath(ctx, milling);
  }

  const int threads = resolvedThreads(job.job.threads);
  const bool csv = targets && targets->size() > 4 && targets->substr(targets->size() - 4) == ".csv";
  if (!report && compensationStreams(pos[0], job)) {
    CompensationResult r = loadStreamedCompensationJob(*cell, pos[0], job);
    if (const int rc = streamedRun(ctx, r, job, pos[0], *out, targets, csv, threads); rc >= 0) {
      keepUntilExit(std::move(r));
      return rc;
    }
  }
  CompensationResult r = loadCompensationJob(*cell, pos[0], job);
  std::vector<std::string> extra;  // checked against the inputs before anything is staged
  if (targets) extra.push_back(*targets);
  if (report) extra.push_back(*report);
  auto writeTargets = [&] {  // written hole by hole into its staged file
    writeFileAtomicStream(*targets, [&](const ByteWriter& write) {
      writeCompensationTargets(r, pos[0], csv, write, threads);
    });
  };
  std::vector<std::string> outs = postproc::outputPaths(*r.context.job.program, *out);
  outs.insert(outs.end(), extra.begin(), extra.end());
  std::sort(outs.begin(), outs.end());
  const bool distinct = std::adjacent_find(outs.begin(), outs.end()) == outs.end();
  // With more than one thread the targets export (the holes' results alone) is written while
  // the program is edited, into a set of its own taken over only when the program may be written
  // (the same files, bytes and commit order).
  std::exception_ptr overwrites_input;  // thrown where it was before: after the job's messages
  try {
    refuseOverwritingInput(*r.context.job.program, extra);
  } catch (const UsageError&) {
    overwrites_input = std::current_exception();
  }
  // without a report (which draws every hole at once) the results are not kept: streamed out
  if (!report && distinct && !overwrites_input && !overwritesInput(r, *out)) {
    const int rc = runStreaming(ctx, r, job, pos[0], *out, targets, csv, threads);
    keepUntilExit(std::move(r));
    return rc;
  }
  compensateLoadedHoles(r, job);
  StagedOutputs targets_started;  // dropped with its set (no file) unless taken over below
  if (threads > 1 && targets && distinct && !overwrites_input)
    targets_started = stagedApart(writeTargets);
  editCompensatedProgram(r, job);
  printJobNotes(ctx, r.context.job.notes);
  for (size_t i = 0; i < r.holes.size(); ++i) {
    if (r.holes[i].ok) continue;
    const HoleRequest& q = r.context.job.requests[i];
    ctx.err << "roprec: hole " << r.holes[i].id;
    if (q.line > 0) ctx.err << " (" << pos[0] << ":" << q.line << ")";
    ctx.err << ": not compensated: " << r.holes[i].reason << "\n";
  }
  for (const auto& x : r.refused) ctx.err << "roprec: " << x << "\n";
  if (!r.writable) {
    ctx.err << "roprec: " << r.why_not_writable << "\n";
    return 1;
  }
  if (overwrites_input) std::rethrow_exception(overwrites_input);
  auto writeReport = [&] { writeFileAtomic(*report, compensationReport(r, pos[0])); };
  std::vector<std::string> written = writeOutputsTogether(
      threads, distinct, [&] { return writeCompensatedProgram(r.context, *out, {}); },
      targets ? std::function<void()>(writeTargets) : nullptr,
      report ? std::function<void()>(writeReport) : nullptr, std::move(targets_started));
  if (targets) written.push_back(*targets);
  if (report) written.push_back(*report);
  if (!ctx.quiet) printSummary(ctx, r, job.options, written);
  const int rc = r.failed ? 1 : 0;
  keepUntilExit(std::move(r));
  return rc;
}

const CommandRegistration reg{
    {"compensate", "pre-offset drill targets; corrected program, target export and report",
     "usage: roprec compensate --cell CELL.xml PROGRAM -o OUT [--orientation "
     "keep|flip-free|stiffest]\n"
     "                         [--targets F.csv|F.json] [--report F.html] [--holes HOLES.csv]\n"
     "                         [--allow-partial] [--allow-branch-change] [--wrist-margin DEG]\n"
     "                         [--jump-threshold DEG] [--grid N] [--turn-axes \"1 4 6\"] "
     "[--force]\n"
     "                         [--frame cell|\"x y z a b c\"|'REF=x y z a b c;...'] [--tool "
     "program|cell]\n"
     "                         [--threads N]\n\n"
     "For every hole: the motor-side command θ_m = θ_d + K⁻¹τ(θ_d) (+ servo term) that makes the\n"
     "predicted real TCP land on the nominal hole, and the programmed target = the controller's\n"
     "rigid FK of θ_m with its configuration flags. Every target of a drill cycle moves with it.\n"
     "--orientation: keep (positions only), flip-free (keeps the programmed rotation about the\n"
     "drill axis unless it breaks a constraint: no axis-4/6 jump > --jump-threshold (60°),\n"
     "|θ5| ≥ --wrist-margin (10°), joint limits, same IK branch unless --allow-branch-change;\n"
     "then the fewest holes and the smallest angles turned, each with its reason in the export),\n"
     "stiffest (least predicted U_work under the same constraints; a hole turns only for ≥ 1 %\n"
     "of its U_work). The program's configuration flags are kept unless the compensated target\n"
     "cannot be reached with them (each change and its reason in the export).\n"
     "OUT is written in the program's dialect; only the compensated targets' bytes change.\n"
     "FANUC: turn digits 1 and 2 are changed only when $SCR_GRP[1].$TURN_AXIS is known "
     "(--turn-axes or\n"
     "the cell's <controller fanuc_turn_axes>); otherwise such edits are refused.\n"
     "With a milling cell every linear path point is compensated instead, with the coupled force\n"
     "iteration (the force depends on the deviation; the tool's bending is pre-offset too); the "
     "export\n"
     "(CSV or JSON by its extension) lists points, forces, iterations and the chatter limit at "
     "each\n"
     "cutting point (robot modes at the pose + tool mode, zero-order lobes); the report draws the\n"
     "deviation before, the residual after and the chatter margin along the path. Points above "
     "the\n"
     "chatter limit (regenerative, or mode coupling of the robot's modes) are listed and the exit "
     "code\n"
     "is 1 (outputs written). The summary gives the surface error normal to the wall before and "
     "after.\n"
     "Unreachable, singular or non-converging holes are listed; without --allow-partial nothing "
     "is\n"
     "written and the exit code is 1; with it they keep their original targets and are flagged.\n"
     "A hole that is singular or unreachable at its programmed target is never compensated (it\n"
     "would change the arm posture). OUT gets a comment line \"roprec compensated: cell ...\";\n"
     "a program carrying it is refused (exit 2) unless --force. OUT (or its .dat) equal to the\n"
     "input is refused. --frame and --tool: as for roprec predict (controller-only frames and a\n"
     "program tool that differs from the cell's are errors unless resolved).\n"
     "--threads N: worker threads for the per-hole work, or a milling path's two pipelined\n"
     "chains (0 = every core; default 1); the outputs are byte-identical for any N. Without\n"
     "--report the holes are compensated and written out a block at a time (the program's bytes\n"
     "up to the next hole's targets, the --targets rows): memory does not grow with the per-hole\n"
     "results; --report keeps them all (it draws them). Without --report or --holes a KUKA KRL\n"
     "program is read by windows, twice (the holes, then the edits), and never held whole. A\n"
     "milling path's --targets export is written point by point, and its KRL program, RAPID\n"
     "module or TP program read by windows twice and written as the points come (a TP\n"
     "program's /MN is read again behind its /POS).\n",
     50, run}};

}  // namespace
}  // namespace roprec::cli
