#pragma once
/// \file work_map.hpp
/// Work-area maps (`roprec map`, docs/reports.md §5): where on the table to put the part. For every
/// point of a regular grid over a box of the cell's workobject frame and every feed, the
/// prediction of a hole drilled there along one direction — |δrobot|, the position error e⊥ and
/// U₉₅ (the verdict's U) — with the IK configuration chosen and unreachable points marked, like
/// the deviation and uncertainty maps of Ferreras-Higuero et al. (RCIM 2020) over the robot's
/// working area for two feed rates.
///
/// Each point is predicted exactly as `roprec predict` predicts a one-hole hole list at that point
/// (the same HoleRequest: T_W_tcp = T_W_wobj · [holeFrame(direction), p], the cell's drill,
/// depth and tolerance, IK seeded by the vendor's reference pose, not by a neighbour), with the
/// process re-evaluated at each feed (feed per revolution; spindle speed, drill and material as in
/// the cell). Grid: along each axis lo, lo + step, … ≤ hi (+1e-9 mm); an axis with lo = hi has
/// one point.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {

struct WorkMapRequest {
  std::string cell_path;
  Vec3 lo_mm{Vec3::Zero()};              ///< region corner, workobject frame, mm
  Vec3 hi_mm{Vec3::Zero()};              ///< opposite corner (each component ≥ lo)
  Vec3 direction{-Vec3::UnitZ()};        ///< drilling direction, workobject frame (normalised here)
  std::vector<double> feeds_mm_per_rev;  ///< empty: the cell's feed
  std::optional<double> step_mm;         ///< empty: the largest span / 10 (≥ 1 mm)
  size_t max_predictions{250000};        ///< points × feeds limit
};

struct WorkMapPoint {
  std::array<int, 3> index{};  ///< grid index along x, y, z
  Vec3 p_mm{Vec3::Zero()};     ///< workobject frame
  HolePrediction prediction;
};

struct WorkMapLayer {
  double feed_mm_per_rev{0};
  std::vector<WorkMapPoint> points;  ///< x fastest, then y, then z
};

struct WorkMap {
  PredictionContext context;  ///< the cell (its job is empty)
  WorkMapRequest request;     ///< normalised (direction unit, step set, feeds set)
  std::array<int, 3> counts{1, 1, 1};
  std::vector<WorkMapLayer> layers;  ///< one per feed
};

/// Validates and predicts. Throws UsageError for a bad region (a component hi < lo, non-finite),
/// a zero or non-finite direction, step ≤ 0, feeds ≤ 0 or above 5 mm/rev, a cell without a
/// drilling process, or more than `max_predictions` predictions (the message gives the count and
/// the step that fits); InputError for a bad cell. `progress` (may be empty) after each point.
WorkMap computeWorkMap(const WorkMapRequest& request,
                       const std::function<void(size_t, size_t)>& progress = {});

// Its CSV and HTML: plugin/report/work_map_report.hpp.

}  // namespace roprec::api
