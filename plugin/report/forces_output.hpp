#pragma once
/// \file forces_output.hpp
/// What `roprec forces` writes (plugin/api/forces.hpp computes it): the JSON and the curve CSV.
///
/// Units: mm, µm, N, N·m, deg, N/mm², kW.
/// Frames: drilling tool frame z = drill axis into the material, forces on the TCP; milling frame
/// X = feed, φ clockwise from +Y, Z from the tool tip toward the spindle, forces on the tool.

#include <string>
#include <utility>

#include "compensator/support/atomic_file.hpp"
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

/// The forces JSON of a milling `--program` written as processForces(request, ForcesPathSink)
/// computes it: head() with the ForcesPathSink's head (everything but the path's points; gives
/// the curve CSV), points() with each block, finish() at the end. The bytes handed to `write`
/// are forcesOutput(r).json.dump() of the whole result; the points are never all in memory.
class ForcesJsonStream {
 public:
  explicit ForcesJsonStream(ByteWriter write) : write_(std::move(write)) {}
  /// Writes the JSON up to the path's first point; returns the curve CSV (ForcesOutput).
  std::string head(const ForcesResult& r);
  void points(const MillingCompensationResult& block);
  void finish();

 private:
  ByteWriter write_;
  JsonWriter json_;
  std::string text_;
};

}  // namespace roprec::api
