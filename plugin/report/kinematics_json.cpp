/// The JSON `roprec fk` and `roprec ik` print (plugin/report/kinematics_json.hpp).
#include "plugin/report/kinematics_json.hpp"

#include <algorithm>
#include <cmath>

#include "plugin/report/pose_json.hpp"

namespace roprec::api {

namespace {
/// What fk/ik answer for a calibrated robot (robot card <calibration>).
std::string geometryText(const RobotCard& card) {
  return "calibrated (" + card.calibration->source +
         "): the real robot, FK_real; the controller's targets follow the card's URDF";
}
}  // namespace

Json fkJson(const RobotSetup& setup, const FkResult& r) {
  Json root = Json::object();
  root.set("robot", Json::str(setup.robot.card.name));
  if (setup.robot.card.calibration) root.set("geometry", Json::str(geometryText(setup.robot.card)));
  root.set("base_link", Json::str(setup.robot.chain.base_link));
  root.set("flange_link", Json::str(setup.robot.chain.tip_link));
  root.set("joints_deg", Json::vector(r.joints / kDeg, 6));
  root.set("controller_joints_deg",
           Json::vector(toControllerJoints(setup.robot.card, r.joints) / kDeg, 6));
  root.set("within_limits", Json::boolean(r.limit_violations.empty()));
  if (!r.limit_violations.empty()) {
    Json v = Json::array();
    for (const auto& m : r.limit_violations) v.push(Json::str(m));
    root.set("limit_violations", v);
  }
  root.set("flange", poseJson(r.T_flange));
  if (setup.cell) root.set("tcp", poseJson(r.T_tcp));
  Json pos = Json::object();
  pos.set("converged", Json::boolean(r.position.converged));
  pos.set("iterations", Json::integer(r.position.iterations));
  pos.set("residual", Json::number(r.position.residual));
  root.set("position_problem", pos);
  return root;
}

namespace {

Json opwJson(const IkModel& model) {
  Json opw = Json::object();
  opw.set("a1_mm", Json::number(model.opw.a1 * 1e3, 6));
  opw.set("a2_mm", Json::number(model.opw.a2 * 1e3, 6));
  opw.set("b_mm", Json::number(model.opw.b * 1e3, 6));
  opw.set("c1_mm", Json::number(model.opw.c1 * 1e3, 6));
  opw.set("c2_mm", Json::number(model.opw.c2 * 1e3, 6));
  opw.set("c3_mm", Json::number(model.opw.c3 * 1e3, 6));
  opw.set("c4_mm", Json::number(model.opw.c4 * 1e3, 6));
  opw.set("ideal_geometry", Json::boolean(model.deviation.exact));
  return opw;
}

Json branchJson(const IkBranch& b) {
  Json br = Json::object();
  br.set("shoulder", Json::str(b.shoulder == 0 ? "front" : "back"));
  br.set("elbow", Json::str(b.elbow == 0 ? "up" : "down"));
  br.set("wrist", Json::str(b.wrist == 0 ? "theta5_nonnegative" : "theta5_negative"));
  return br;
}

Json singularJson(const IkSolution& sol) {
  Json sing = Json::object();
  sing.set("wrist", Json::boolean(sol.singular_wrist));
  sing.set("shoulder", Json::boolean(sol.singular_shoulder));
  sing.set("elbow", Json::boolean(sol.singular_elbow));
  sing.set("wrist_margin_deg",
           Json::number(std::asin(std::min(1.0, sol.branch.wrist_margin_rad)) / kDeg, 6));
  sing.set("elbow_margin_deg",
           Json::number(std::asin(std::min(1.0, sol.branch.elbow_margin_rad)) / kDeg, 6));
  sing.set("shoulder_margin_mm", Json::number(sol.branch.shoulder_margin_m * 1e3, 6));
  return sing;
}

Json solutionJson(const RobotSetup& setup, const IkAnswer& a, const IkSolution& sol) {
  Json j = Json::object();
  j.set("branch_index", Json::integer(sol.branch.index()));
  j.set("branch", branchJson(sol.branch));
  j.set("joints_deg", Json::vector(sol.q / kDeg, 6));
  j.set("controller_joints_deg",
        Json::vector(toControllerJoints(setup.robot.card, sol.q) / kDeg, 6));
  j.set(
      "config",
      Json::str(formatConfig(configurationOf(a.model, setup.robot.card, sol.q, a.config_options))));
  j.set("within_limits", Json::boolean(sol.within_limits));
  j.set("converged", Json::boolean(sol.converged));
  j.set("singular", singularJson(sol));
  Json res = Json::object();
  res.set("position_um", Json::number(sol.residual.position * 1e6, 6));
  res.set("rotation_urad", Json::number(sol.residual.rotation * 1e6, 6));
  res.set("refinement_iterations", Json::integer(sol.iterations));
  j.set("residual", res);
  return j;
}

}  // namespace

Json ikJson(const RobotSetup& setup, const IkAnswer& a) {
  Json root = Json::object();
  root.set("robot", Json::str(setup.robot.card.name));
  if (setup.robot.card.calibration) root.set("geometry", Json::str(geometryText(setup.robot.card)));
  root.set("vendor", Json::str(vendorName(setup.robot.card.vendor)));
  root.set("base_link", Json::str(setup.robot.chain.base_link));
  root.set("flange_link", Json::str(setup.robot.chain.tip_link));
  root.set("flange", poseJson(a.T_flange));
  if (setup.cell) root.set("tcp", poseJson(a.T_target));
  root.set("opw", opwJson(a.model));
  if (setup.robot.card.vendor == Vendor::kFanuc) {
    Json axes = Json::array();
    for (int ax : a.config_options.fanuc_turn_axes) axes.push(Json::integer(ax));
    root.set("fanuc_turn_axes", axes);
  }
  Json list = Json::array();
  for (int k = 0; k < a.result->count; ++k)
    list.push(solutionJson(setup, a, a.result->solutions[static_cast<size_t>(k)]));
  root.set("count", Json::integer(a.result->count));
  root.set("solutions", list);
  if (a.result->truncated) root.set("turns_truncated", Json::boolean(true));
  if (!a.unreachable.empty()) root.set("unreachable", Json::str(a.unreachable));
  return root;
}

}  // namespace roprec::api
