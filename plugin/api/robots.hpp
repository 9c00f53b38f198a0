#pragma once
/// \file robots.hpp
/// The bundled robots (robots/<name>/robot.xml) with the source of every number their cards
/// carry (`roprec robots`): vendor, model, ISO 9283 repeatability, joint stiffness and position
/// gain, and which numbers are estimates (a source beginning with "estimate:").
///
/// Units: mm (repeatability), kg, N·m/rad, 1/s.
/// Errors: InputError for a broken card.

#include <string>
#include <vector>

#include "compensator/robot/robot_card.hpp"
#include "plugin/api/json.hpp"

namespace roprec::api {

/// JSON of one card: name, vendor, model, urdf, rated payload, repeatability and sources, joints[]
/// (stiffness, estimate, source, position gain), gravity_compensated.
Json robotCardJson(const RobotCard& card);

/// The text block of one card: name, repeatability, stiffness k1..k6 and whether it is estimated,
/// the inertial and dimension sources; ends with a blank line.
std::string robotCardText(const RobotCard& card);

/// The card's guesses, one line each ("joint stiffness k1..k6: estimate: ..."): every number
/// whose source starts with `estimate:` (docs/cards.md), for reports to show next to the results.
std::vector<std::string> cardEstimates(const RobotCard& card);

/// One line of one card: name, vendor and model, payload, repeatability RP and whether the joint
/// stiffness is published or estimated.
std::string robotCardLine(const RobotCard& card);

struct RobotList {
  Json json;            ///< {"robots": [robotCardJson, ...]}
  std::string text;     ///< robotCardText of each, in name order
  std::string summary;  ///< robotCardLine of each, in name order
};

/// Every bundled robot, in name order.
RobotList bundledRobotList();

}  // namespace roprec::api
