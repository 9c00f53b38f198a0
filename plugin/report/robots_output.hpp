#pragma once
/// \file robots_output.hpp
/// What `roprec robots` prints of the robot cards (plugin/api/robots.hpp loads them): vendor,
/// model, ISO 9283 repeatability, joint stiffness and position gain, and the source of every
/// number, estimates marked.
///
/// Units: mm (repeatability), kg, N·m/rad, 1/s.

#include <string>
#include <vector>

#include "compensator/robot/robot_card.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {

/// JSON of one card: name, vendor, model, urdf, rated payload, repeatability and sources, joints[]
/// (stiffness, estimate, source, position gain), gravity_compensated.
Json robotCardJson(const RobotCard& card);

/// The text block of one card: name, repeatability, stiffness k1..k6 and whether it is estimated,
/// the inertial and dimension sources; ends with a blank line.
std::string robotCardText(const RobotCard& card);

/// One line of one card: name, vendor and model, payload, repeatability RP and whether the joint
/// stiffness is published or estimated.
std::string robotCardLine(const RobotCard& card);

struct RobotList {
  Json json;            ///< {"robots": [robotCardJson, ...]}
  std::string text;     ///< robotCardText of each, in name order
  std::string summary;  ///< robotCardLine of each, in name order
};

/// The listing of `cards` (bundledRobotCards: every bundled robot, in name order).
RobotList robotList(const std::vector<RobotCard>& cards);

}  // namespace roprec::api
