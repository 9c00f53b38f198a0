#pragma once
/// \file cell.hpp
/// The cell file (docs/contract.md §6): robot reference, tool (TCP in the flange frame, mass,
/// centre of mass), work object (hole frame in the base frame), process element and default
/// position tolerance. Files use mm and degrees; everything here is SI.

#include <optional>
#include <string>
#include <vector>

#include "compensator/robot/robot_card.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec {

struct ToolSpec {
  std::string name;
  Pose T_flange_tcp{Pose::Identity()};  ///< TCP in the flange frame
  double mass{0.0};                     ///< kg (tool + spindle)
  Vec3 com{Vec3::Zero()};               ///< m, in the flange frame
  Mat3 inertia{Mat3::Zero()};           ///< kg m^2 about the com, flange axes (optional)
};

struct CellSpec {
  std::string file;
  std::string name;
  RobotRequest robot;  ///< resolved relative to the cell file's folder
  int robot_line{0};
  ToolSpec tool;
  /// The TCP of each <drill> (drilling) or <mill> (milling) of the process's tool table (document
  /// order): its own <tcp xyz rpy [mass_kg com_mm inertia_kgm2]> (without mass_kg the cell's
  /// tool's mass data), nullopt for a tool without one (it sits at the cell's <tool>). Empty
  /// without a drilling or milling process.
  std::vector<std::optional<ToolSpec>> drill_tools;
  Pose T_base_wobj{Pose::Identity()};  ///< work object frame in the robot base frame
  /// <part_registration xyz_mm rpy_mrad source>: where the part was found (roprec verify
  /// --register, written by --write-cell) as the rigid transform F = [R, t] of verify's model
  /// (identification.hpp): a point p of the nominal part (workobject coordinates) is measured at
  /// R p + t, so the real part is the nominal one moved by F⁻¹. Absent: the part is nominal.
  std::optional<Pose> part_registration;
  bool has_process{false};
  XmlNode process;           ///< the <process> element (type="drilling|milling|wrench")
  double tolerance_mm{0.2};  ///< default ⌀ position tolerance (ISO 1101)
  XmlNode root;              ///< the whole cell, for extensions (uncertainty, ...)
};

/// Pose from `xyz` (mm) and `rpy` (deg, URDF order) attributes of an element. Throws InputError
/// at the element's line when a value is not finite or beyond ±1e5 mm (100 m) / ±3600 deg.
Pose poseFromXyzRpyMm(const XmlNode& e);

/// The motion of the part in the robot base frame the cell's <part_registration> states:
/// G = T_W_wobj · F⁻¹ · T_W_wobj⁻¹, so a nominal hole pose T (base frame, whatever frame its
/// program uses) is at G · T on the real part. Identity without a registration.
Pose partMotion(const CellSpec& cell);

/// Loads and validates a cell file. Throws InputError `FILE:LINE: what` for malformed XML, an
/// unknown element or attribute anywhere (with a "did you mean" hint for a near-miss name, e.g.
/// `unknown attribute 'mas_kg' on <tool> (did you mean 'mass_kg'?)`), an element given twice, a
/// tool mass outside [0, 5000] kg or a non-physical tool inertia, a tolerance <= 0, and any error
/// of the <process> element (parseProcess).
CellSpec loadCell(const std::string& path);

}  // namespace roprec
