#include "plugin/api/robot_compliance.hpp"

namespace roprec::api {

nc::JointCompliance complianceOf(const RobotCard& card) {
  return nc::requireComplianceFromCard(card);
}

nc::Vec6 controllerGravityOffset(const Robot& robot, const nc::JointCompliance& c,
                                 const nc::Vec6& theta_m) {
  if (!robot.card.gravity_compensated) return nc::Vec6::Zero();
  nc::ToolAttachment cal;
  cal.mass = robot.card.calibration_load_kg;
  cal.com = robot.card.calibration_load_com;
  const nc::Model m = nc::buildModel(robot.chain, cal);
  nc::Data d(m);
  return nc::gravityCommandOffset(m, d, c, theta_m);
}

}  // namespace roprec::api
