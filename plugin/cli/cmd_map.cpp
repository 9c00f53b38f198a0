/// `roprec map`: work-area maps of |δrobot|, e⊥ and U over a grid of a region (work_map.hpp).
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/support/error.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/report/work_map_report.hpp"

namespace roprec::cli {
namespace {

/// Whitespace- or comma-separated finite numbers (at least one).
std::vector<double> parseList(std::string text, const std::string& what) {
  for (char& ch : text) {
    if (ch == ',') ch = ' ';
  }
  std::istringstream s(text);
  int n = 0;
  for (std::string tok; s >> tok;) ++n;
  if (n == 0) throw UsageError(what + ": at least one number expected");
  const Eigen::VectorXd v = parseNumberList(text, n, what);
  return {v.data(), v.data() + v.size()};
}

int run(Args& args, CommandContext& ctx) {
  const auto cell = args.option("cell");
  const auto region = args.option("region");
  const auto direction = args.option("direction");
  const auto feeds = args.option("feeds");
  const auto step = args.option("step");
  const auto report = args.option("report");
  const auto csv = args.option("csv");
  args.finish();
  if (!cell) throw UsageError("give --cell CELL.xml");
  if (!region) throw UsageError("give --region \"x0 y0 z0 x1 y1 z1\" (mm, workobject frame)");
  if (!direction)
    throw UsageError("give --direction \"i j k\" (the drilling direction, workobject frame)");
  if (!report && !csv) throw UsageError("give --report OUT.html and/or --csv OUT.csv");

  WorkMapRequest q;
  q.cell_path = *cell;
  const Eigen::VectorXd r = parseNumberList(*region, 6, "--region (x0 y0 z0 x1 y1 z1, mm)");
  q.lo_mm = r.head<3>();
  q.hi_mm = r.tail<3>();
  q.direction = parseNumberList(*direction, 3, "--direction (i j k)");
  if (feeds) q.feeds_mm_per_rev = parseList(*feeds, "--feeds (mm/rev)");
  if (step) q.step_mm = parseNumberList(*step, 1, "--step (mm)")[0];

  Progress progress(ctx, "predicting map points", 0);
  const WorkMap map =
      computeWorkMap(q, [&](size_t done, size_t total) { progress.step(done, total); });
  progress.finish();
  if (report) writeFileAtomic(*report, workMapReport(map));
  if (csv) writeFileAtomic(*csv, workMapCsv(map));
  if (!ctx.quiet) {
    size_t n = 0, failed = 0;
    for (const WorkMapLayer& l : map.layers) {
      for (const WorkMapPoint& p : l.points) {
        ++n;
        failed += p.prediction.status == HoleStatus::kOk ? 0 : 1;
      }
    }
    ctx.err << "roprec map: " << map.counts[0] << " x " << map.counts[1] << " x " << map.counts[2]
            << " points x " << map.layers.size() << " feeds = " << n << " predictions, " << failed
            << " unreachable or singular\n";
  }
  return 0;
}

const CommandRegistration reg{
    {"map", "work-area maps of the predicted deviation and uncertainty over a region",
     "usage: roprec map --cell CELL.xml --region \"x0 y0 z0 x1 y1 z1\" --direction \"i j k\"\n"
     "                  [--feeds \"0.1 0.2\"] [--step MM] [--report OUT.html] [--csv OUT.csv] "
     "[--quiet]\n\n"
     "Where on the table to put the part: for every point of a grid over the box (mm, the cell's\n"
     "<workobject> frame, like a hole list) and every feed (mm/rev; default the cell's), predicts "
     "a\n"
     "hole drilled there along --direction (workobject frame) exactly as `roprec predict` "
     "predicts\n"
     "a one-hole hole list at that point: |δrobot|, the position error e⊥ and U95 (the verdict's\n"
     "U), the IK configuration and the verdict. --step: grid spacing in mm (default the largest\n"
     "span / 10, at least 1 mm); an axis with x0 = x1 has one point. At most 250000 predictions\n"
     "(points × feeds); a progress line on a terminal.\n"
     "--report: one HTML heat map per feed and quantity (per slice along the third axis for a 3-D\n"
     "region), colour scales shared across feeds, t/2 marked, configuration changes outlined in\n"
     "red, unreachable points crossed. --csv: one row per point × feed (docs/reports.md §5).\n"
     "Exit 2 for a bad region (x1 < x0), a zero direction, --step ≤ 0, too many points or a cell\n"
     "without a drilling process.\n",
     42, run}};

}  // namespace
}  // namespace roprec::cli
