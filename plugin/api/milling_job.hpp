#pragma once
/// \file milling_job.hpp
/// The milling job of the host-facing API (`roprec compensate` with a milling cell): every linear
/// path point of a program compensated with the coupled force iteration
/// (compensator/compensation/milling_compensation.hpp), the program's targets edited. job.hpp
/// includes it; see there for the drilling jobs.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "compensator/compensation/milling_compensation.hpp"
#include "plugin/api/prediction_setup.hpp"

namespace roprec::api {

/// Milling path compensation (every linear path point, coupled force iteration).
struct MillingCompensationResult {
  PredictionContext context;
  std::vector<int> targets;              ///< program target per point
  std::vector<Pose> points;              ///< nominal TCP, base frame
  std::vector<CuttingDecision> cutting;  ///< per point: cuts or not, and why (§4.5)
  /// Per point: its mill (ProcessSpec::mills index), the one the motion's active tool selects
  /// (docs/process.md §8, tool table); 0 for a single-mill cell.
  std::vector<int> mill;
  /// Path point first + k at k: every point (first = 0), or with a MillingPointsSink the block
  /// being handed over (empty after the job).
  std::vector<PathPointCompensation> points_comp;
  std::size_t first{0};
  std::vector<std::string> failures;  ///< "path point N (FILE:LINE): not compensated: why"
  std::vector<std::string> refused;
  /// Path point i's results (it must be in points_comp: i - first < points_comp.size()).
  [[nodiscard]] const PathPointCompensation& point(std::size_t i) const {
    return points_comp[i - first];
  }
};
/// Receives each block of compensated path points, in path order: r.points_comp holds points
/// [r.first, r.first + r.points_comp.size()), their target edits applied to the program and
/// their failures and refusals recorded; the block is dropped after the call (a CAM-size path's
/// results are never all in memory).
using MillingPointsSink = std::function<void(const MillingCompensationResult& r)>;
/// Each run of path points with one mill is compensated as a path of its own with that mill's
/// process and TCP (a tool change leaves the material), seeded with the joints before it. Throws
/// InputError at a path motion whose tool the cell's mills do not have, at one that selects no
/// tool when the cell has several mills, and at the first motion of a second tool when it has one.
/// `path`: the revolutions resolved by edge angle or not, and the workers (the same results
/// whatever their count; compensateMillingPath).
MillingCompensationResult compensateMillingJob(const std::string& cell_path,
                                               const std::string& program_path, bool force = false,
                                               const MillingPathOptions& path = {});
/// compensateMillingJob handing every block of points to `sink` (points_comp is empty after it).
MillingCompensationResult compensateMillingJob(const std::string& cell_path,
                                               const std::string& program_path, bool force,
                                               const MillingPathOptions& path,
                                               const MillingPointsSink& sink);
/// The mill of path point `i` (MillingCompensationResult::mill).
const MillingSpec& millOf(const MillingCompensationResult& r, std::size_t i);

/// True when the cell's process is milling (compensate then runs compensateMillingJob).
bool cellIsMilling(const std::string& cell_path);

}  // namespace roprec::api
