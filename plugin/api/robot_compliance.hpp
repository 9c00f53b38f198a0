#pragma once
/// \file robot_compliance.hpp
/// Joint compliance of a loaded robot from its card (k, and the servo's static stiffness
/// k_servo = Kv·Kω when both position_gain and velocity_gain are given; otherwise the servo is
/// ideal/integrating, Δψ = 0), and the ONE decision of how the controller handles gravity for a
/// robot in a cell (docs/model.md §6.3), used by predict, compensate, verify, deflect and
/// simulate alike:
///   * gravity_compensated: the robot card's `<controller gravity_compensated>`, overridden by
///     the cell's `<controller gravity_compensated>`;
///   * calibration load: the card's calibration_load_kg/_com_mm, or the cell's tool when the
///     cell says `<controller calibration_load="tool">` ("card" is the default);
///   * otherwise the mastering reference at the card's calibration pose (robot weight only).
/// Errors: InputError at the cell's <controller> line for a bad calibration_load.
#include <optional>
#include <string>

#include "compensator/precision/cell.hpp"
#include "compensator/robot/deflection.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec::api {

/// Throws InputError (card file and line) when the card has no stiffness.
nc::JointCompliance complianceOf(const RobotCard& card);

/// The controller's gravity handling for `card` in `cell` (nullptr: the card alone).
struct ControllerGravity {
  bool gravity_compensated{false};      ///< absolute-accuracy option
  nc::ToolAttachment calibration_load;  ///< load its compensation was calibrated for
  std::string decided_by;               ///< "robot card" / "cell <controller>"
};
ControllerGravity controllerGravityOf(const RobotCard& card, const CellSpec* cell,
                                      const nc::ToolAttachment& cell_tool);

/// The controller reference (nc::makeControllerReference) of `robot` in `cell` (nullptr: none);
/// kind kNone when `gravity` is false or the card does not model gravity.
nc::ControllerReference controllerReferenceOf(const Robot& robot, const CellSpec* cell,
                                              const nc::ToolAttachment& cell_tool, bool gravity);

}  // namespace roprec::api
