#pragma once
/// \file milling_files.hpp
/// `roprec compensate` of a milling path with its files (the CLI, roprec_compensate_file and the
/// Python module's compensate): every linear path point compensated (milling_job.hpp), the
/// corrected program, the corrected-target export (CSV when its name ends in ".csv", else JSON)
/// and the HTML report written all together or not at all. The points stream past block by
/// block: the export is written as they come, the report's rows are spilled to a temporary file
/// and only its plots' few numbers per point are kept. A KRL program or a RAPID module is read by
/// windows (millingStreams; one carrying the compensation marker too with `force`) and its
/// program written as the blocks come: memory is then constant in the number of points but for
/// the report's few numbers per point; a TP program is read whole.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plugin/api/milling_job.hpp"
#include "plugin/report/milling_report.hpp"

namespace roprec::api {

struct MillingFilesJob {
  std::string cell;
  std::string program;
  std::string out;                     ///< the corrected program (KRL: its .src; the .dat beside)
  std::optional<std::string> targets;  ///< the export: CSV when it ends in ".csv", else JSON
  std::optional<std::string> report;   ///< the HTML report
  bool force{false};                   ///< a program carrying the compensation marker too
  int threads{1};                      ///< the chains' workers (the same bytes for any count)
};

/// The figures of every path point, accumulated in path order as the blocks pass.
struct MillingPointStats {
  std::size_t points{0};
  std::size_t failed{0};
  double before_sum_um{0};  ///< Σ |deviation before| [µm]
  double before_max_um{0};
  double after_sum_um{0};  ///< Σ |residual| [µm]
  double after_max_um{0};
};

struct MillingFilesResult {
  /// The job: its notes (context.job.notes), failures and refused edits (then nothing is
  /// written), streamed or not (its per-point vectors are empty either way).
  MillingCompensationResult job;
  MillingReportSummary summary;  ///< the maxima (and, with a report, its plots' points)
  MillingPointStats stats;
  std::vector<std::string> written;  ///< every file written, in order; empty when none was
  /// The cutting points above the chatter limit (written all the same), one line each:
  /// "roprec: path point N: chatter: ..." / "...: mode-coupling chatter: ...".
  int unstable{0};
  std::string unstable_lines;
};

/// Compensates the path of `job.program` and writes its files (see the file comment): nothing
/// when a point failed or the writer refused an edit (job.failures / job.refused say which).
/// `computed` (may be empty) is called once the path is done, before any file is written (a
/// caller's notes come before a writing error). Throws InputError / UsageError as the CLI's
/// compensate reports them (an output that is an input, two outputs on one path).
MillingFilesResult compensateMillingFiles(
    const MillingFilesJob& job,
    const std::function<void(const MillingCompensationResult&)>& computed = nullptr);

}  // namespace roprec::api
