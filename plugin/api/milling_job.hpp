#pragma once
/// \file milling_job.hpp
/// The milling job of the host-facing API (`roprec compensate` with a milling cell): every linear
/// path point of a program compensated with the coupled force iteration
/// (compensator/compensation/milling_compensation.hpp), the program's targets edited. job.hpp
/// includes it; see there for the drilling jobs.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compensator/compensation/milling_compensation.hpp"
#include "compensator/support/atomic_file.hpp"
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
  /// A job read by windows (compensateStreamedMillingJob) keeps none of the per-point vectors
  /// above: what the exports read of the points of the block being handed over (point first + k
  /// at k), and the number of path points.
  struct BlockPoint {
    std::string target;  ///< the program target's name
    int line{0};         ///< its line
    Pose nominal{Pose::Identity()};
    std::optional<MillingEngagement> engagement;  ///< its cutting decision's (box stock)
    int mill{0};
  };
  bool streamed{false};
  std::vector<BlockPoint> block;
  std::size_t streamed_points{0};
  /// Read by windows: the first point and the mill of each run of points of one mill.
  std::vector<std::pair<std::size_t, int>> runs;
  /// Read by windows: the lines (first file, sorted) of the targets declared by name that path
  /// points use, each once: the program's bytes from the first of them not compensated yet are
  /// held until it is (a module that declares every point holds its declarations).
  std::vector<int> named_lines;
  /// Path points (compensated or not).
  [[nodiscard]] std::size_t pointCount() const {
    return streamed ? streamed_points : points.size();
  }
  /// Path point i's target name and line (i in the block handed over, or any of a whole job).
  [[nodiscard]] const std::string& targetName(std::size_t i) const;
  [[nodiscard]] int targetLine(std::size_t i) const;
  /// Path point i's nominal TCP (base frame).
  [[nodiscard]] const Pose& nominal(std::size_t i) const;
  /// Path point i's engagement on the programmed path (box stock), none without a box stock.
  [[nodiscard]] const std::optional<MillingEngagement>& engagement(std::size_t i) const;
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
/// Whether compensate reads a milling program by windows (compensateStreamedMillingJob): a KUKA
/// KRL program (compensationStreams), an ABB RAPID module or a FANUC TP program
/// (postproc::ProgramStream with `rapid`) without the "roprec compensated" marker.
bool millingStreams(const std::string& program_path);
/// millingStreams(), and with `force` (compensate --force) also such a program that carries the
/// marker: read by windows as well (loadStreamedMillingJob with `force`).
bool millingStreams(const std::string& program_path, bool force);
/// Whether a job that writes no program (`roprec forces --program`) reads a milling program by
/// windows (loadStreamedMillingJob, computeStreamedMillingPath): a KRL program millingStreams()
/// accepts, or any ABB RAPID module or FANUC TP program (one that carries the compensation marker
/// gets checkNotCompensated's error as the whole-program job does). Other dialects (CSV,
/// JSON) are read whole.
bool millingPathStreams(const std::string& program_path);
/// compensateMillingJob's loading of a program millingStreams() or millingPathStreams() accepts,
/// read by windows: the cell and a first reading that checks every path point (the same errors, in
/// the same order: the program's, then its points' mills, then a program without a path point) and
/// keeps only the runs of points of one mill; context.job.program then holds the program's files
/// (their number style, the `.dat` whole), frames and notes, not its motions. `window_bytes`: the
/// windows' size (0: postproc::ProgramStream::kWindowBytes). A program that carries the
/// compensation marker is refused unless `force` (checkNotCompensated: the same error, or with
/// `force` the same note in context.job.notes, as compensateMillingJob's).
MillingCompensationResult loadStreamedMillingJob(const std::string& cell_path,
                                                 const std::string& program_path,
                                                 std::size_t window_bytes = 0, bool force = false);
/// compensateMillingJob of a job loadStreamedMillingJob loaded, memory constant in the number of
/// points: a second reading hands the path points to the chains block by block
/// (compensateMillingPath's MillingPathSource, the cutting decided point by point) and edits the
/// program as the blocks come back (r.block: what the exports read of them) — `sink` as
/// compensateMillingJob's. The first file's bytes no later edit can change go to `write_src` as
/// they are final (the rest at the end, when nothing failed and no edit was refused), and `dat`
/// receives the edited `.dat` (a program with one). The bytes, the blocks, `failures` and `refused`
/// are those of compensateMillingJob.
void compensateStreamedMillingJob(MillingCompensationResult& r, const MillingPathOptions& path,
                                  const ByteWriter& write_src, std::optional<std::string>& dat,
                                  const MillingPointsSink& sink, std::size_t window_bytes = 0);

/// compensateStreamedMillingJob without the program's edits, for a job that writes no program
/// (`roprec forces --program`): the same blocks, in the same order, and the same `failures`;
/// `refused` stays empty (no edit is made).
void computeStreamedMillingPath(MillingCompensationResult& r, const MillingPathOptions& path,
                                const MillingPointsSink& sink, std::size_t window_bytes = 0);

/// The mill of path point `i` (MillingCompensationResult::mill).
const MillingSpec& millOf(const MillingCompensationResult& r, std::size_t i);

/// True when the cell's process is milling (compensate then runs compensateMillingJob).
bool cellIsMilling(const std::string& cell_path);

}  // namespace roprec::api
