#pragma once
/// \file robots.hpp
/// The bundled robots (robots/<name>/robot.xml) whose cards `roprec robots` lists
/// (plugin/report/robots_output.hpp), and which numbers of a card are estimates (a source
/// beginning with "estimate:").
///
/// Units: mm (repeatability), kg, N·m/rad, 1/s.
/// Errors: InputError for a broken card.

#include <string>
#include <vector>

#include "compensator/robot/robot_card.hpp"

namespace roprec::api {

/// The card's guesses, one line each ("joint stiffness k1..k6: estimate: ..."): every number
/// whose source starts with `estimate:` (docs/cards.md), for reports to show next to the results.
std::vector<std::string> cardEstimates(const RobotCard& card);

/// Every bundled robot's card (robots/<name>/robot.xml), in name order.
std::vector<RobotCard> bundledRobotCards();

}  // namespace roprec::api
