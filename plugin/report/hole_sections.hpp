#pragma once
/// \file hole_sections.hpp
/// The sections of the hole report (renderReport, hole_report.hpp), one file each: the header and
/// verdicts (hole_report.cpp), the deviation maps (hole_maps.cpp), the uncertainty budget
/// (hole_budget.cpp) and the per-hole table (hole_table.cpp). Internal to plugin/report.

#include <algorithm>
#include <atomic>
#include <exception>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "plugin/report/hole_report.hpp"
#include "plugin/report/html.hpp"

namespace roprec::report {

using api::ReportHole;
using api::ReportInput;

/// One hole as the sections show it: its prediction (and after compensation), its δrobot split,
/// its position and drilling axis in the part frame (mm), and whether the robot changed its IK
/// branch since the previous predicted hole.
struct HoleView {
  /// null for a streamed prediction's hole (ReportInput::predicted)
  const ReportHole* rh{nullptr};
  /// null for a large streamed prediction's hole (ReportInput::mapped: the maps only read it)
  const api::ReportPrediction* p{nullptr};
  const api::MapFacts* f{nullptr};              ///< what the maps read: p, or the mapped hole's
  const api::ReportPrediction* after{nullptr};  ///< compensate: the prediction after
  const std::optional<api::DeviationSplit>* split{nullptr};
  Vec3 pos_mm{Vec3::Zero()};  ///< part frame
  Vec3 axis{Vec3::UnitZ()};   ///< part frame
  bool ok{false};
  bool config_change{false};
  int prev_branch{-1};
};

/// The views of a report's holes, in order, and the predictions they point to (ReportHole's
/// converted by reportPrediction). Throws std::invalid_argument for a hole without a prediction.
struct HoleViews {
  std::vector<api::ReportPrediction> own;
  std::vector<HoleView> views;
};
HoleViews holeViews(const ReportInput& in);
/// The views of streamed holes (ReportInput::predicted) appended to `out`, in order (positions
/// and axes into the part frame by T_part_W); `prev_branch`: the IK branch of the last predicted
/// hole before them (-1: none), carried on.
void appendPredictedViews(std::vector<HoleView>& out, std::span<const api::PredictedHole> holes,
                          const Pose& T_part_W, int& prev_branch);
/// The same for the holes of a large streamed prediction (ReportInput::mapped).
void appendMappedViews(std::vector<HoleView>& out, std::span<const api::MappedHole> holes,
                       const Pose& T_part_W, int& prev_branch);
/// The budget terms of the predicted holes of `hv` not in `names` yet appended to it, in the
/// order first seen (the table's budget columns).
void addBudgetNames(std::vector<std::string>& names, std::span<const HoleView> hv);

/// `branch` with `config` appended to `branches` unless it is there (first seen first).
void addBranch(std::vector<std::pair<int, std::string>>& branches, int branch,
               const std::string& config);
/// The budget over the predicted holes of `hv`.
api::BudgetSums budgetSums(const std::vector<HoleView>& hv);

/// The verdict a hole ends with: after compensation when it was compensated, else as predicted.
Verdict finalVerdict(const HoleView& h);
/// The hole conforms in the end (the table's "pass" rows).
bool passes(const HoleView& h);
/// "1 hole", "2 holes".
std::string plural(long n, const char* one, const char* many);
/// part / whole in %, 0 when whole ≤ 0.
double pct(double part, double whole);

void renderMaps(Html& h, const ReportInput& in, const std::vector<HoleView>& hv);
/// The budget section of the budget summed over the predicted holes.
void renderBudget(Html& h, const api::BudgetSums& sums);
void renderTable(Html& h, const ReportInput& in, const std::vector<HoleView>& hv);

/// Runs work(k) for every k in [0, n) on min(threads, n) threads, the calling thread one of
/// them, one k at a time (each k writes only its own slot); the first exception is rethrown after
/// every thread joined.
template <class Work>
void eachOnThreads(size_t n, int threads, const Work& work) {
  const size_t t = std::min(n, static_cast<size_t>(std::max(1, threads)));
  std::atomic<size_t> next{0};
  std::vector<std::exception_ptr> errors(t);
  auto run = [&](size_t w) {
    try {
      for (size_t k = next++; k < n; k = next++) work(k);
    } catch (...) {
      errors[w] = std::current_exception();
      next.store(n);
    }
  };
  std::vector<std::thread> pool;
  for (size_t w = 1; w < t; ++w) pool.emplace_back(run, w);
  run(0);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

/// The reports' stylesheet and table scripts (report_assets.cpp).
extern const char* const kReportCss;
extern const char* const kTableScript;
extern const char* const kPagedTableScript;

}  // namespace roprec::report
