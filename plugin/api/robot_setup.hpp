#pragma once
/// \file robot_setup.hpp
/// A robot loaded for the per-pose calls (forward and inverse kinematics, deflection, transient
/// simulation): the robot card or bare URDF, optionally a cell (its robot, tool and process) and
/// a joint-stiffness override; plus what those calls share: the joint-limit check (the JSON of a
/// pose: plugin/report/pose_json.hpp).
///
/// Units: SI in every struct (m, rad, N·m/rad); JSON in mm and degrees.
/// Frames: base = the robot's base link; the TCP is flange × the cell's tool (the flange itself
/// without a cell).
/// Errors: InputError (`FILE:LINE: what`) for bad files or values, UsageError when no robot is
/// named. Thread safety: no shared state.

#include <optional>
#include <string>
#include <vector>

#include "compensator/precision/cell.hpp"
#include "compensator/robot/model.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec::api {

/// Which robot to load, as plain values (the CLI's --robot/--cell/--base/--tip/--stiffness).
struct RobotSetupRequest {
  std::optional<std::string> robot;  ///< bundled NAME, robot.xml or file.urdf; overrides the cell's
  std::optional<std::string> cell;   ///< CELL.xml: its robot (unless `robot`) and its tool
  std::optional<std::string> base_link;  ///< overrides the base link (bare URDF)
  std::optional<std::string> tip_link;   ///< overrides the flange link
  std::optional<nc::Vec6> stiffness;  ///< k1..k6 (N·m/rad), replaces the card's (overrideStiffness)
};

struct RobotSetup {
  Robot robot;
  std::optional<CellSpec> cell;
  nc::ToolAttachment tool;  ///< the cell's tool (identity TCP and no mass without a cell)
};

/// Loads the cell (if any), then the robot (`robot` wins over the cell's <robot>; base/tip links
/// override), then applies the stiffness override. Throws UsageError "give --robot ... (or --cell)"
/// when no robot is named; InputError for bad files (an error of the cell's robot reference is
/// reported at the cell's <robot> line) and for a stiffness ≤ 0.
RobotSetup loadRobotSetup(const RobotSetupRequest& request);

/// Replaces the card's joint stiffness by `k` (N·m/rad) and marks each joint's source `source`.
/// Throws InputError "`name`: k3 must be > 0 N m/rad, got ..." unless every k_i > 0.
void overrideStiffness(RobotSetup& setup, const nc::Vec6& k, const std::string& name = "stiffness",
                       const std::string& source = "stiffness override");

/// The cell's tool as the model's attachment: TCP in the flange frame (m), mass (kg), centre of
/// mass (m, flange frame) and inertia (kg·m²).
nc::ToolAttachment toolOf(const CellSpec& cell);

/// Joint values (URDF convention, rad) outside the URDF limits, one text per joint:
/// "joint_a2 = -170.000 deg (limits -155.000 .. 35.000 deg)".
std::vector<std::string> limitViolations(const ChainDescription& chain, const nc::Vec6& q);

/// Throws InputError "`what` outside the joint limits: <first violation>" when q (URDF, rad) is
/// outside the limits.
void requireWithinLimits(const ChainDescription& chain, const nc::Vec6& q, const std::string& what);

}  // namespace roprec::api
