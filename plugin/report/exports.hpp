#pragma once
/// \file exports.hpp
/// The texts a job writes (docs/contract.md): the prediction JSON and HTML report, the
/// corrected-target export (CSV or JSON), the compensation report, the milling path export.
/// Pure functions of a job result; deterministic bytes for identical inputs.

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "plugin/api/job.hpp"
#include "plugin/report/hole_report.hpp"

namespace roprec::api {

/// Receives an export's bytes piece by piece, in order (a staged output file, a string).
using ByteSink = std::function<void(std::string_view)>;

/// Streams the prediction JSON hole by hole in constant memory: the same bytes as
/// predictionJson(r).dump() (docs/contract.md "Prediction output"). The header is written by the
/// constructor, each hole() writes one hole (a hole with a non-finite number is written as
/// "failed", like predictionJson), finish() the summary. Bytes go to `sink` in pieces of about
/// 64 KiB. Throws what `sink` throws.
class PredictionJsonStream {
 public:
  PredictionJsonStream(const PredictionContext& c, ByteSink sink);
  void hole(const HolePrediction& h, const HoleRequest& r);
  /// The next holes, in order (request k of hole k), formatted on `threads` workers: the bytes of
  /// hole() called for each one after the other.
  void holes(std::span<const HolePrediction> h, std::span<const HoleRequest> r, int threads);
  void finish(const CapabilitySummary& s);

 private:
  /// One hole as an item of the "holes" array of `w` (a hole with a non-finite number as
  /// "failed").
  static void item(JsonWriter& w, const HolePrediction& h, const HoleRequest& r,
                   const RobotCard& card);
  void drain(bool all);
  JsonWriter w_;
  std::vector<std::string> texts_;  ///< holes(): each hole's text
  ByteSink sink_;
  RobotCard card_;  ///< for the joints in the controller's convention
};

/// Gathers a prediction's HTML report while its holes stream past (predictJobStreaming's
/// blocks): each hole's δrobot split from its joints, on the workers, and its compact record
/// (PredictedHole, ~0.8 kB); for a large job (more than kReportAggregateAbove holes) instead its
/// table row (RowsAheadRenderer, ~0.5 kB) and what the maps read of it (MappedHole, ~0.16 kB),
/// the budget and the table's totals counted as they go past (StreamedTotals). finish() renders
/// the rest of the document: the same bytes as predictionReport.
class PredictionReportStream {
 public:
  /// `threads`: the most workers holes() is given.
  PredictionReportStream(const PredictionContext& c, int threads);
  /// The next holes, in order (request k of hole k), on `threads` workers.
  void holes(std::span<const HolePrediction> h, std::span<const HoleRequest> r, int threads);
  /// The report of the job `r` (its context, summary and shared frame) with every hole given.
  std::string finish(const PredictionResult& r);
  /// The same bytes given to `sink` piece by piece (no whole-document string).
  void finish(const PredictionResult& r, const ByteSink& sink);

 private:
  ReportInput input(const PredictionResult& r);
  DeviationSplitter splitter_;
  int workers_;
  std::vector<PredictedHole> holes_;       ///< a small job's; a large job's block (reused)
  std::vector<MappedHole> mapped_;         ///< a large job's
  StreamedTotals totals_;                  ///< a large job's
  RobotCard card_;                         ///< the rows' joint convention
  std::optional<RowsAheadRenderer> rows_;  ///< a large job's rows, rendered as they come
  std::vector<RenderedRows> rows_ahead_;
};

/// `item`, or when one of its numbers is not finite (a bug or an input that escaped the range
/// checks) the item reported as failed on its own (id, line, status, reason) instead of poisoning
/// the whole output.
Json finiteOrFailed(Json item, const std::string& id, int line);

/// The prediction JSON of the file contract (docs/contract.md "Prediction output").
Json predictionJson(const PredictionResult& r);
/// The self-contained HTML report of a prediction; the δrobot split of its holes on `threads`
/// workers (the same bytes).
std::string predictionReport(const PredictionResult& r, int threads = 1);

/// The corrected-target export: CSV when `csv`, else JSON (docs/contract.md "Corrected targets").
std::string compensationTargets(const CompensationResult& r, const std::string& program_path,
                                bool csv);
/// The same bytes, written hole by hole to `sink` (no whole-document tree or string). With
/// `threads` > 1 the CSV rows are formatted by blocks on that many workers (the same bytes).
void writeCompensationTargets(const CompensationResult& r, const std::string& program_path,
                              bool csv, const ByteSink& sink, int threads = 1);
/// The corrected-target export written as the holes are compensated (compensateHoles with a
/// CompensationSink): the constructor writes the header, holes() the next holes in order (request
/// q[k] of hole h[k]), finish() the end; the bytes of writeCompensationTargets over the same
/// holes. Holds one JSON chunk (about 64 KiB) or one round of CSV rows at a time.
class CompensationTargetsStream {
 public:
  CompensationTargetsStream(const PredictionContext& c, const std::string& orientation,
                            const std::string& program_path, bool csv, ByteSink sink,
                            int threads = 1);
  void holes(std::span<const HoleCompensation> h, std::span<const HoleRequest> q);
  void finish();

 private:
  bool csv_;
  int threads_;
  ByteSink sink_;
  JsonWriter w_;
  RobotCard card_;  ///< for the joints in the controller's convention
};
/// The compensation report (before/after maps).
std::string compensationReport(const CompensationResult& r, const std::string& program_path);

/// The milling path export: per point the nominal and programmed pose, force, coupling iterations.
std::string millingTargetsJson(const MillingCompensationResult& r, const std::string& program_path);
/// The milling path export as CSV (one row per path point: programmed position in mm, the
/// deviation before and the residual after in µm, the force, the coupling status, the chatter
/// limit and margin; the limit is empty where not cutting or unbounded).
std::string millingTargetsCsv(const MillingCompensationResult& r);
/// The same bytes (CSV when `csv`, else JSON) written point by point to `sink`, in pieces of
/// about 64 KiB: no whole-document tree or string.
void writeMillingTargets(const MillingCompensationResult& r, const std::string& program_path,
                         bool csv, const ByteSink& sink);
/// The same bytes written as the points come (compensateMillingJob's MillingPointsSink): points()
/// for every block (r.points_comp; the first call writes the head), then finish().
class MillingTargetsStream {
 public:
  MillingTargetsStream(bool csv, std::string program_path, ByteSink sink);
  void points(const MillingCompensationResult& r);
  void finish(const MillingCompensationResult& r);

 private:
  void begin(const MillingCompensationResult& r);
  bool csv_;
  std::string program_path_;
  ByteSink sink_;
  JsonWriter w_;
  std::string s_;  ///< CSV text not yet handed to the sink
  bool begun_{false};
};

}  // namespace roprec::api
