#pragma once
/// \file urdf_writer.hpp
/// The calibrated robot as a URDF for other tools (`roprec card export-urdf`): the card's URDF
/// text with the joint origins of the chain base_link → flange_link rewritten so that the URDF's
/// chain is calibratedChain(nominal, cal) (geometry_calibration.hpp):
///   * chain joint i:             origin' = origin · E_i
///   * the first joint on the path from base_link (joint 1 or a fixed joint before it):
///                                origin' = E_base · origin
///   * the last joint on the path to flange_link (a fixed joint after joint 6):
///                                origin' = origin · E_tool
/// Values are written as `xyz` (m) and `rpy` (rad, URDF fixed-axis roll-pitch-yaw) in the
/// shortest text that reads back to the same double; every other byte of the URDF is unchanged
/// (comments, meshes, side branches, other attributes).

#include <string>

#include "compensator/robot/geometry_calibration.hpp"

namespace roprec {

/// Throws InputError(urdf_path, line, …) when a joint on the chain is not found, when a tool
/// error is stated but flange_link is joint 6's own link (no fixed joint to carry it), or for
/// malformed XML.
std::string calibratedUrdf(const std::string& urdf_path, const ChainDescription& nominal,
                           const GeometryCalibration& cal);

}  // namespace roprec
