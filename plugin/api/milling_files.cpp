#include "plugin/api/milling_files.hpp"

#include <algorithm>
#include <string_view>
#include <utility>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/outputs_together.hpp"
#include "plugin/api/temp_spill.hpp"
#include "plugin/report/exports.hpp"
#include "postproc/program.hpp"

namespace roprec::api {
namespace {

/// Thrown out of a staged output when the job must write nothing (its temporary is removed).
struct NothingWritten {};

bool nothingToWrite(const MillingCompensationResult& r) {
  return !r.failures.empty() || !r.refused.empty();
}

/// The cutting points of the block r.points_comp whose ap is above the chatter limit, one line
/// each into `lines`; returns how many.
int unstablePoints(const MillingCompensationResult& r, std::string& lines) {
  int n = 0;
  for (size_t i = r.first; i < r.first + r.points_comp.size(); ++i) {
    const PathPointCompensation& p = r.point(i);
    const double ap = millOf(r, i).cut.ap;
    if (!p.unstable(ap)) continue;
    ++n;
    if (p.regenerativeUnstable(ap)) {
      lines += "roprec: path point " + std::to_string(i + 1) + ": chatter: ap " +
               formatNumber(ap * 1e3, 3) + " mm > limit " + formatNumber(p.ap_limit * 1e3, 3) +
               " mm (chatter at " + formatNumber(p.chatter_hz, 1) + " Hz)\n";
    }
    if (p.modeCouplingUnstable(ap)) {
      lines += "roprec: path point " + std::to_string(i + 1) + ": mode-coupling chatter: ap " +
               formatNumber(ap * 1e3, 3) + " mm > limit " +
               formatNumber(p.mode_coupling_ap_limit * 1e3, 3) + " mm (at " +
               formatNumber(p.mode_coupling_hz, 1) + " Hz)\n";
    }
  }
  return n;
}

/// The points of the block r.points_comp added to `s`, in order.
void addPointStats(MillingPointStats& s, const MillingCompensationResult& r) {
  for (const PathPointCompensation& p : r.points_comp) {
    ++s.points;
    if (!p.ok) ++s.failed;
    const double before = p.deviation_before.norm() * 1e6;
    const double after = p.residual.norm() * 1e6;
    s.before_sum_um += before;
    s.after_sum_um += after;
    s.before_max_um = s.points == 1 ? before : std::max(s.before_max_um, before);
    s.after_max_um = s.points == 1 ? after : std::max(s.after_max_um, after);
  }
}

/// Whether the outputs of a job read by windows (its program's files, the export, the report)
/// are distinct and none of them is an input file: else the whole-program path says what is
/// wrong, after the job, as it always has.
bool streamedOutputsFine(const MillingCompensationResult& r, const std::vector<std::string>& outs) {
  std::vector<std::string> sorted = outs;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
  try {
    refuseOverwritingInput(*r.context.job.program, outs);
  } catch (const UsageError&) {
    return false;
  }
  return true;
}

bool endsWithCsv(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
}

/// One run of compensateMillingFiles: the job's state while its points stream past.
class MillingFilesRun {
 public:
  explicit MillingFilesRun(const MillingFilesJob& job) : job_(job) {
    path_.resolve_edges = false;  // the compensate outputs report no revolution by edge angle
    path_.threads = job.threads;
    if (job.report) spill_.emplace("the report");
    if (job.targets) extra_.push_back(*job.targets);
    if (job.report) extra_.push_back(*job.report);
  }

  /// The path compensated; the program read by windows is staged as it is written.
  void compute() {
    if (loadStreamed()) {
      computeStreamed();
    } else {
      withTargets([&](MillingTargetsStream* targets_out) {
        result_ = compensateMillingJob(job_.cell, job_.program, job_.force, path_,
                                       blockSink(targets_out));
        if (nothingToWrite(*result_)) throw NothingWritten{};
      });
    }
  }

  /// Every file of the job (none when a point failed or an edit was refused).
  void write() {
    MillingCompensationResult& r = *result_;
    if (nothingToWrite(r)) return;
    refuseOverwritingInput(*r.context.job.program, extra_);
    std::vector<std::string> outs = postproc::outputPaths(*r.context.job.program, job_.out);
    outs.insert(outs.end(), extra_.begin(), extra_.end());
    std::sort(outs.begin(), outs.end());
    const bool distinct = std::adjacent_find(outs.begin(), outs.end()) == outs.end();
    const auto writeReport = [&] {  // the plots from the summary, the rows from the spill
      writeFileAtomicStream(*job_.report, [&](const ByteWriter& write) {
        writeMillingReport(
            out_.summary, r, job_.program,
            [&](const ByteSink& sink) { spill_->replay(sink, std::size_t{64} * 1024); }, write);
      });
    };
    const auto writeProgram = [&] {
      if (!prog_outs_) return writeCompensatedProgram(r.context, job_.out, {});
      if (prog_outs_->size() > 1 && dat_) writeFileAtomic((*prog_outs_)[1], *dat_);
      return *prog_outs_;  // the .src staged as it was written
    };
    out_.written = writeOutputsTogether(job_.threads, distinct, writeProgram, nullptr,
                                        job_.report ? std::function<void()>(writeReport) : nullptr);
    if (job_.targets) out_.written.push_back(*job_.targets);
    if (job_.report) out_.written.push_back(*job_.report);
  }

  const MillingCompensationResult& job() const { return *result_; }

  MillingFilesResult take() {
    out_.job = std::move(*result_);
    return std::move(out_);
  }

 private:
  /// A KRL program or RAPID module read by windows whose outputs are fine: its first reading.
  bool loadStreamed() {
    if (!millingStreams(job_.program, job_.force)) return false;
    result_ = loadStreamedMillingJob(job_.cell, job_.program, 0, job_.force);
    std::vector<std::string> outs = postproc::outputPaths(*result_->context.job.program, job_.out);
    outs.insert(outs.end(), extra_.begin(), extra_.end());
    if (!streamedOutputsFine(*result_, outs)) {
      result_.reset();
      return false;
    }
    prog_outs_ = postproc::outputPaths(*result_->context.job.program, job_.out);
    return true;
  }

  void computeStreamed() {
    try {
      writeFileAtomicStream(job_.out, [&](const ByteWriter& write_src) {
        withTargets([&](MillingTargetsStream* targets_out) {
          compensateStreamedMillingJob(*result_, path_, write_src, dat_, blockSink(targets_out));
          if (nothingToWrite(*result_)) throw NothingWritten{};
        });
        if (nothingToWrite(*result_)) throw NothingWritten{};
      });
    } catch (const NothingWritten&) {
    }
  }

  /// `run` with the export staged as the points come (none without one).
  void withTargets(const std::function<void(MillingTargetsStream*)>& run) {
    try {
      if (job_.targets) {
        writeFileAtomicStream(*job_.targets, [&](const ByteWriter& write) {
          MillingTargetsStream t(endsWithCsv(*job_.targets), job_.program, write);
          run(&t);
          t.finish(*result_);
        });
      } else {
        run(nullptr);
      }
    } catch (const NothingWritten&) {
    }
  }

  /// What each block of points hands on: the summaries, the export's rows, the report's rows.
  MillingPointsSink blockSink(MillingTargetsStream* targets_out) {
    return [this, targets_out](const MillingCompensationResult& blk) {
      addMillingReportPoints(out_.summary, blk);
      if (!spill_) out_.summary.points.clear();  // only the maxima
      addPointStats(out_.stats, blk);
      out_.unstable += unstablePoints(blk, out_.unstable_lines);
      if (nothingToWrite(blk)) return;  // nothing will be written
      if (targets_out != nullptr) targets_out->points(blk);
      if (spill_) writeMillingReportRows(blk, [&](std::string_view v) { spill_->write(v); });
    };
  }

  const MillingFilesJob& job_;
  MillingPathOptions path_;
  std::optional<TempSpill> spill_;  ///< the report's table rows while the path streams past
  std::vector<std::string> extra_;  ///< the export and the report
  std::optional<MillingCompensationResult> result_;
  std::optional<std::vector<std::string>> prog_outs_;  ///< read by windows: the program's files
  std::optional<std::string> dat_;                     ///< read by windows: the edited .dat
  MillingFilesResult out_;
};

}  // namespace

MillingFilesResult compensateMillingFiles(
    const MillingFilesJob& job,
    const std::function<void(const MillingCompensationResult&)>& computed) {
  MillingFilesRun run(job);
  run.compute();
  if (computed) computed(run.job());
  run.write();
  return run.take();
}

}  // namespace roprec::api
