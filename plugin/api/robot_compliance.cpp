#include "plugin/api/robot_compliance.hpp"

namespace roprec::api {

nc::JointCompliance complianceOf(const RobotCard& card) {
  return nc::requireComplianceFromCard(card);
}

ControllerGravity controllerGravityOf(const RobotCard& card, const CellSpec* cell,
                                      const nc::ToolAttachment& cell_tool) {
  ControllerGravity g;
  g.gravity_compensated = card.gravity_compensated;
  g.calibration_load.mass = card.calibration_load_kg;
  g.calibration_load.com = card.calibration_load_com;
  g.decided_by = "robot card";
  const XmlNode* e = cell ? cell->root.child("controller") : nullptr;
  if (e == nullptr) return g;
  if (e->has("gravity_compensated")) {
    g.gravity_compensated = e->boolean("gravity_compensated", g.gravity_compensated);
    g.decided_by = "cell <controller>";
  }
  const std::string load = e->str("calibration_load", "card");
  if (load == "tool") {
    g.calibration_load = cell_tool;
  } else if (load != "card") {
    e->fail("<controller> calibration_load must be \"tool\" (the cell's tool) or \"card\"");
  }
  return g;
}

nc::ControllerReference controllerReferenceOf(const Robot& robot, const CellSpec* cell,
                                              const nc::ToolAttachment& cell_tool, bool gravity) {
  const ControllerGravity g = controllerGravityOf(robot.card, cell, cell_tool);
  return nc::makeControllerReference(robot.real_chain, robot.card, gravity, g.gravity_compensated,
                                     g.calibration_load);
}

}  // namespace roprec::api
