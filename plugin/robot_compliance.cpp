#include "plugin/robot_compliance.hpp"

#include "compensator/error.hpp"

namespace roprec::cli {

nc::JointCompliance complianceOf(const RobotCard& card) {
  nc::JointCompliance c;
  for (int i = 0; i < 6; ++i) {
    const JointCard& j = card.joints[static_cast<size_t>(i)];
    if (!(j.stiffness > 0)) {
      throw InputError(card.file, j.line,
                       "joint '" + j.name + "' has no stiffness: give it in the robot card or with --stiffness \"k1 .. k6\"");
    }
    c.k[i] = j.stiffness;
    if (j.position_gain && j.velocity_gain) c.k_servo[i] = *j.position_gain * *j.velocity_gain;
  }
  return c;
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

}  // namespace roprec::cli
