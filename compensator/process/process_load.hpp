#pragma once
/// \file process_load.hpp
/// The process as a load on the robot: the steady wrench that the workpiece exerts on the TCP
/// (tool frame; tool +z = drilling direction into the material) for a cell's <process>, and
/// its expression in the base frame at a TCP pose. Drilling: maximum steady values of the
/// quaternion edge model (thrust Fz pushes the drill back, −z; the cutting torque opposes the
/// spindle); the runout force Fr rotates at spindle frequency and has zero mean, so it enters
/// the uncertainty, not the steady load. Milling: the revolution-averaged force of the nominal
/// cut (the coupled iteration refines it per path point). Wrench: as given.

#include "compensator/process/process_spec.hpp"
#include "compensator/robot/inverse_dynamics.hpp"

namespace roprec {

struct SteadyProcessLoad {
  ToolWrench wrench;         ///< on the TCP, tool frame
  double rotating_force{0};  ///< amplitude of the rotating residual force Fr [N] (drilling)
  std::string description;   ///< e.g. "drilling Dc 10 mm f 0.20 mm/rev Al 6061-T6"
};

SteadyProcessLoad steadyProcessLoad(const ProcessSpec& spec);

/// The tool-frame wrench in the base frame at the TCP orientation R_W_tcp.
nc::Wrench toBaseFrame(const ToolWrench& w, const Mat3& R_W_tcp);

}  // namespace roprec
