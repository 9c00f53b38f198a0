#include "plugin/api/robot_compliance.hpp"

#include "compensator/support/error.hpp"

namespace roprec::api {

nc::JointCompliance complianceOf(const RobotCard& card) {
  for (const JointCard& j : card.joints) {
    if (!(j.stiffness > 0)) {
      throw InputError(card.file, j.line,
                       "joint '" + j.name + "' has no stiffness: give it in the robot card or with --stiffness \"k1 .. k6\"");
    }
  }
  return nc::complianceFromCard(card);
}

nc::Vec6 controllerGravityOffset(const Robot& robot, const nc::JointCompliance& c, const nc::Vec6& theta_m) {
  if (!robot.card.gravity_compensated) return nc::Vec6::Zero();
  nc::ToolAttachment cal;
  cal.mass = robot.card.calibration_load_kg;
  cal.com = robot.card.calibration_load_com;
  const nc::Model m = nc::buildModel(robot.chain, cal);
  nc::Data d(m);
  nc::solvePosition(m, d, theta_m);
  nc::Loads g;
  const nc::Vec6 tau = nc::staticTorques(m, d, g);
  return tau.cwiseQuotient(c.effective());
}

}  // namespace roprec::api
