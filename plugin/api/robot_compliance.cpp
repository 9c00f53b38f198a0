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

Json gravityHandlingJson(const Robot& robot, const nc::ControllerReference& ref) {
  Json j = Json::object();
  j.set("gravity_model", Json::str(robot.card.gravity_modelled ? "links" : "none"));
  j.set("controller_reference", Json::str(ref.description()));
  j.set("calibration_pose_deg",
        Json::vector(toControllerJoints(robot.card, robot.card.calibration_pose) / kDeg, 6));
  const Counterbalance& cb = robot.card.counterbalance;
  j.set("counterbalance",
        Json::str(!cb.present() ? "none"
                                : robot.chain.joints[static_cast<size_t>(cb.joint)].name + " " +
                                      (cb.law == Counterbalance::Law::kGas ? "gas" : "spring")));
  const std::string note = gravityNotModelledNote(robot.card);
  if (!note.empty()) j.set("note", Json::str(note));
  return j;
}

}  // namespace roprec::api
