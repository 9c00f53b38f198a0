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
/// Units: SI in the structs (m, N, N·m, m/N); JSON and CSV in mm, µm, N, N·m, deg, N/mm², kW.
/// Frames: drilling tool frame z = drill axis into the material, forces on the TCP; milling frame
/// X = feed, φ clockwise from +Y, Z from the tool tip toward the spindle, forces on the tool.
/// Errors: InputError (cell file and line) for a bad cell, no <process>, a calibration of a
/// non-drilling process or a curve of a wrench process; UsageError for a calibrated cell asked
/// without a calibration. These messages name the CLI's options (--calibrate, -o, --csv).

#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/model.hpp"
#include "plugin/api/json.hpp"

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
};

struct ForcesResult {
  /// cell, process, material; drilling: drill, cut, calibration, coefficients, steady, wrench_tool,
  /// axial_coupling, max_over_depth, machining_deviation; milling: joints_deg, frame, mill, cut,
  /// coefficients, immersion, steady, coupling; wrench: wrench_tool.
  Json json;
  std::string curve_csv;  ///< drilling: over depth (or per revolution); milling: over one
                          ///< revolution (with a coupling: nominal and corrected, TCP movement)
  std::string
      calibrated_cell;   ///< the cell's text with calibrated <coefficients> (calibrated_cell)
  bool converged{true};  ///< every coupled point (axial or milling coupling, program path)
                         ///< converged
  std::vector<std::string> unstable;  ///< milling --program: the points whose ap is above the
                                      ///< chatter limit, one line each
};

/// Computes the forces of the cell's process; the robot is loaded only for `joints`.
ForcesResult processForces(const ForcesRequest& request);

}  // namespace roprec::api
