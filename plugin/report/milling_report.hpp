#pragma once
/// The report of a compensated milling path (`roprec compensate --report` with a milling cell):
/// one self-contained HTML page (no external resources) with the deviation of every linear path
/// point before compensation (the coupled force, docs/process.md) and the predicted residual
/// after it, in µm, drawn along the path, and a table per point: program target and line,
/// whether it cuts and why, the converged force, the before/after deviation, the coupled
/// solver's status, iterations and loop gain, the configuration written.
#include <functional>
#include <string>
#include <vector>

#include "plugin/api/job.hpp"

namespace roprec::api {

/// What the report draws and sums over the whole path, gathered block by block (a few doubles
/// per point: the path plot's two values and the margin plot's).
struct MillingReportSummary {
  struct Point {
    double before_um{0};    ///< |deviation before| [µm]
    double residual_um{0};  ///< |residual| [µm]
    double margin{0};       ///< chatter margin ap_limit/ap (5 when unbounded), when `checked`
    bool checked{false};    ///< cutting and its stability checked (a margin-plot point)
    bool unstable{false};
  };
  std::vector<Point> points;
  double before{0}, after{0}, wall_before{0}, wall_after{0};  ///< maxima [m]
  int cutting{0};
};
/// Adds the points of r.points_comp (a block, or the whole path) to `s`.
void addMillingReportPoints(MillingReportSummary& s, const MillingCompensationResult& r);
/// The table rows of the points of r.points_comp, in order, to `sink`.
void writeMillingReportRows(const MillingCompensationResult& r, const ByteSink& sink);
/// The whole report from the summary of every point and their rows (`rows`: called once with
/// the sink, writes every row in order, e.g. from a spill file): the same bytes as
/// writeMillingCompensationReport.
void writeMillingReport(const MillingReportSummary& s, const MillingCompensationResult& r,
                        const std::string& program_path,
                        const std::function<void(const ByteSink&)>& rows, const ByteSink& sink);

/// Throws InputError when a number to be shown is not finite (nothing is written then).
std::string millingCompensationReport(const MillingCompensationResult& r,
                                      const std::string& program_path);
/// The same bytes handed to `sink` in pieces of about 64 KiB (no whole-document string).
void writeMillingCompensationReport(const MillingCompensationResult& r,
                                    const std::string& program_path, const ByteSink& sink);

}  // namespace roprec::api
