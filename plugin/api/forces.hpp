#pragma once
/// \file forces.hpp
/// The process forces of a cell alone (`roprec forces`): drilling (steady thrust, torque, runout
/// force, per-lip forces, the wrench on the TCP, the machining-deviation budget, the curve over
/// depth, the axial feed coupling, single-test calibration of kst0/ksa0), milling (immersion,
/// mean and peak forces over a revolution, the coupled force/deflection solve along a path,
/// optionally with the robot's own compliance at a pose, the corrected revolution — nominal vs
/// coupled force and TCP movement — and, with a program, the per-point cutting decision and coupled
/// solve along the program's path; docs/process.md §4.4–4.5) or a given wrench.
///
/// Units: SI in the structs (m, N, N·m, m/N). The JSON and CSV: plugin/report/forces_output.hpp.
/// Frames: drilling tool frame z = drill axis into the material, forces on the TCP; milling frame
/// X = feed, φ clockwise from +Y, Z from the tool tip toward the spindle, forces on the tool.
/// Errors: InputError (cell file and line) for a bad cell, no <process>, a calibration of a
/// non-drilling process or a curve of a wrench process; UsageError for a calibrated cell asked
/// without a calibration. These messages name the CLI's options (--calibrate, -o, --csv).

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compensator/process/process_spec.hpp"
#include "compensator/robot/model.hpp"
#include "plugin/api/job.hpp"

namespace roprec::api {

/// One measured drilling test at the cell's diameter and feed.
struct DrillingMeasurement {
  double thrust{0};  ///< Fa, N
  double torque{0};  ///< M, N·m
};

struct ForcesRequest {
  std::string cell;      ///< CELL.xml with a <process>
  double step{0.05e-3};  ///< drilling: depth step of the curve, m
  int points{10};        ///< milling: path points of the coupled iteration
  std::optional<double>
      axial_compliance;  ///< drilling: axial compliance at the TCP, m/N (curve per revolution)
  std::optional<DrillingMeasurement>
      calibrate;                ///< drilling: identify kst0 and ksa0 from this test
  bool calibrated_cell{false};  ///< also give the cell with the calibrated <coefficients>
  bool curve{false};            ///< the caller wants the curve (a wrench process has none)
  std::optional<nc::Vec6>
      joints;  ///< milling: couple with the cell robot's compliance here (URDF, rad)
  std::optional<std::string>
      program;  ///< milling: every linear point of this program (cutting decision, coupled solve)
  /// The drill or mill of the cell's tool table (its tool number or name; needed when the table
  /// holds several); with `program` the program's active tool selects instead.
  std::optional<std::string> tool;
  /// milling `program`: workers of the path (MillingPathOptions::threads, >= 1; the same results
  /// whatever the count) and points per block handed to a ForcesPathSink (>= 1).
  int threads{1};
  std::size_t block{512};
  /// milling `program` read by windows (a ForcesPathSink and a program millingStreams() accepts):
  /// the windows' size in bytes (0: postproc::ProgramStream::kWindowBytes; tests give small ones).
  std::size_t window_bytes{0};
};

/// Drilling: the spec (after the calibration), the steady forces, the curve over depth and, with
/// an axial compliance, the curve per revolution.
struct DrillingForcesData {
  DrillingSpec spec;  ///< coefficients and their source after the calibration, if any
  std::optional<DrillingMeasurement> measurement;  ///< the calibration test
  std::optional<DrillingCalibration> calibration;  ///< identified from `measurement`
  DrillingCoefficients coeff_before;               ///< the cell's coefficients
  DrillingForces steady;                           ///< at the cell's feed
  std::vector<DepthSample> profile;                ///< over depth, `step` apart
  double step{0};                                  ///< m
  std::optional<double> axial_compliance;          ///< m/N
  std::vector<AxialCouplingSample> axial;          ///< per revolution (axial_compliance)
};

/// Milling: the coupled force/deflection solve over the path points and the corrected revolution
/// of the last point.
struct MillingCouplingData {
  bool robot{false};  ///< the robot's compliance at --joints (else the cell's linear one)
  Mat3 tool_compliance{Mat3::Zero()};  ///< m/N
  std::vector<CouplingResult> points;
  CorrectedRevolution corrected;  ///< of the last point
};

struct MillingForcesData {
  MillingSpec spec;
  std::optional<nc::Vec6> joints;  ///< the robot's pose (rad) with --joints
  ModalModel dynamics;             ///< robot modes at `joints` (if any) and the tool mode
  MillingModel model;
  MillingProfile profile;  ///< one revolution
  std::optional<MillingCouplingData> coupling;
  std::optional<MillingCompensationResult> path;  ///< with a program
  std::string program;                            ///< its path
};

struct ForcesResult {
  std::string cell;  ///< the cell's name
  std::optional<DrillingForcesData> drilling;
  std::optional<MillingForcesData> milling;
  std::optional<WrenchSpec> wrench;
  std::string
      calibrated_cell;   ///< the cell's text with calibrated <coefficients> (calibrated_cell)
  bool converged{true};  ///< every coupled point (axial or milling coupling, program path)
                         ///< converged
  std::vector<std::string> unstable;  ///< milling --program: the points whose ap is above the
                                      ///< chatter limit, one line each
};

/// The ap of path point `i` (the engaged ap of a cutting point with an engagement, else the cut's).
double pathPointAp(const MillingCompensationResult& r, size_t i);

/// Computes the forces of the cell's process; the robot is loaded only for `joints`.
ForcesResult processForces(const ForcesRequest& request);

/// Receives a milling `program`'s path as it is computed: `head` once, with everything but the
/// path's points (milling->path holds the program, its targets and decisions, no points_comp),
/// before the first block; then `points` for each block of path points, in path order
/// (MillingPointsSink: r.points_comp holds points [r.first, r.first + size)).
struct ForcesPathSink {
  std::function<void(const ForcesResult& head)> head;
  MillingPointsSink points;
};
/// processForces handing a milling program's path to `sink` a block at a time: the points'
/// results are never all in memory (milling->path->points_comp is empty in the result). A program
/// compensate reads by windows (millingStreams) is read by windows here too: the program is then
/// never whole in memory either (milling->path is a streamed result: its per-point vectors are
/// empty; read a block's points with its accessors, targetLine() and engagement()). Without a
/// program it is processForces (the sink is not called). `converged` and `unstable` are those of
/// processForces.
ForcesResult processForces(const ForcesRequest& request, const ForcesPathSink& sink);

}  // namespace roprec::api
