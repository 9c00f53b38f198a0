#pragma once
/// \file forces_output.hpp
/// What `roprec forces` writes (plugin/api/forces.hpp computes it): the JSON and the curve CSV.
///
/// Units: mm, µm, N, N·m, deg, N/mm², kW.
/// Frames: drilling tool frame z = drill axis into the material, forces on the TCP; milling frame
/// X = feed, φ clockwise from +Y, Z from the tool tip toward the spindle, forces on the tool.

#include <string>

#include "plugin/api/forces.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

struct ForcesOutput {
  /// cell, process, material; drilling: drill, cut, calibration, coefficients, steady, wrench_tool,
  /// axial_coupling, max_over_depth, machining_deviation; milling: joints_deg, frame, mill, cut,
  /// coefficients, immersion, steady, dynamics, stability, coupling, path; wrench: wrench_tool.
  Json json;
  std::string curve_csv;  ///< drilling: over depth (or per revolution); milling: over one
                          ///< revolution (with a coupling: nominal and corrected, TCP movement)
};

ForcesOutput forcesOutput(const ForcesResult& r);

}  // namespace roprec::api
