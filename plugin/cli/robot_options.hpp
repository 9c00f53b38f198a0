#pragma once
/// \file robot_options.hpp
/// The options every robot command shares: `--robot NAME|robot.xml|file.urdf`, `--base LINK`,
/// `--tip LINK`, `--cell CELL.xml` (the cell's robot and tool are used; `--robot` overrides the
/// cell's robot), `--stiffness "k1 .. k6"` (N m/rad, overrides the card).

#include <optional>
#include <string>

#include "compensator/precision/cell.hpp"
#include "compensator/robot/model.hpp"
#include "compensator/robot/robot_card.hpp"
#include "plugin/api/json.hpp"
#include "plugin/cli/cli.hpp"

namespace roprec::cli {

struct RobotSetup {
  Robot robot;
  std::optional<CellSpec> cell;
  nc::ToolAttachment tool;  ///< from the cell (identity/no mass without a cell)
};

/// Reads --robot/--base/--tip/--cell/--stiffness from args and loads everything.
RobotSetup loadRobotSetup(Args& args);

/// Joint values outside the URDF limits, as "joint_a2 = -170.000° (limits -155.000° .. 35.000°)".
std::vector<std::string> limitViolations(const ChainDescription& chain, const nc::Vec6& q);

/// JSON of a pose: position_mm (6 decimals), quaternion_wxyz (w >= 0, 9 decimals) and the
/// KUKA-style A,B,C (deg) for convenience.
Json poseJson(const Pose& T);

}  // namespace roprec::cli
