#include "plugin/report/prediction_json.hpp"

namespace roprec::api {

Json holeJson(const HolePrediction& h, const HoleRequest& r, const RobotCard* card) {
  Json j = Json::object();
  j.set("id", Json::str(h.id));
  if (r.line > 0) j.set("line", Json::integer(r.line));
  if (!r.evidence.empty()) j.set("evidence", Json::str(r.evidence));
  j.set("nominal", [&] {
    Json n = Json::object();
    n.set("position_mm", Json::vector(r.T_W_tcp.translation() * 1e3, 6));
    // where the hole starts (the feed's first point on the axis) and where it ends
    if (r.surface_W) n.set("surface_mm", Json::vector(*r.surface_W * 1e3, 6));
    n.set("bottom_mm", Json::vector(r.T_W_tcp.translation() * 1e3, 6));
    const Eigen::Quaterniond q = quaternionFromRotation(r.T_W_tcp.linear());
    n.set("quaternion_wxyz", Json::vector(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()), 9));
    n.set("axis", Json::vector(r.T_W_tcp.linear().col(2), 9));
    return n;
  }());
  j.set("diameter_mm", Json::number(h.diameter * 1e3, 3));
  j.set("depth_mm", Json::number(h.depth * 1e3, 3));
  if (statesOwnProcess(r)) {
    Json d = Json::object();
    if (!r.tool.empty()) d.set("tool", Json::str(r.tool));
    d.set("feed_mm_per_rev", Json::number(h.feed * 1e3, 4));
    d.set("spindle_rpm", Json::number(h.spindle_rpm, 1));
    j.set("drill", d);
  }
  if (h.status == HoleStatus::kOk || h.status == HoleStatus::kNotConverged ||
      h.status == HoleStatus::kSingular) {
    j.set("joints_deg", Json::vector(h.joints / kDeg, 6));
    if (card != nullptr)
      j.set("controller_joints_deg", Json::vector(toControllerJoints(*card, h.joints) / kDeg, 6));
    if (!h.config.empty()) j.set("config", Json::str(h.config));
    j.set("branch", Json::integer(h.branch));
  }
  if (h.status == HoleStatus::kOk) {
    Json d = Json::object();
    d.set("robot", Json::vector(h.d_robot * 1e6, 3));
    d.set("mach", Json::vector(h.d_mach * 1e6, 3));
    d.set("work", Json::vector(h.d_work * 1e6, 3));
    d.set("robot_rotation_urad", Json::vector(h.d_rot * 1e6, 3));
    d.set("work_tool_xy", Json::vector(h.e_tool * 1e6, 3));
    d.set("position_error", Json::number(h.position_error * 1e6, 3));
    d.set("axis_tilt_urad", Json::number(h.axis_tilt * 1e6, 3));
    if (h.nominal_axis_error)
      d.set("from_nominal_axis", Json::number(*h.nominal_axis_error * 1e6, 4));
    j.set("deviation_um", d);
    Json u = Json::object();
    u.set("U_robot", Json::number(h.U_robot * 1e6, 3));
    u.set("U_mach", Json::number(h.U_mach * 1e6, 3));
    u.set("U_work", Json::number(h.U_work * 1e6, 3));
    u.set("k", Json::number(h.k, 4));
    u.set("coverage", Json::str("2-D radial 95 % (Rayleigh)"));
    u.set("U_work_anisotropic", Json::number(h.U_work_exact * 1e6, 3));
    Json b = Json::object();
    Json sources = Json::object();
    bool any_source = false;
    for (const BudgetTerm& t : h.budget) {
      b.set(t.name, Json::number(t.u * 1e6, 3));
      if (t.source != nullptr) sources.set(t.name, Json::str(t.source));
      any_source |= t.source != nullptr;
    }
    u.set("standard_per_axis", b);
    if (any_source) u.set("term_sources", sources);
    u.set("process_share", Json::number(h.process_share, 4));
    u.set("process_force_share", Json::number(h.process_force_share, 4));
    j.set("uncertainty_um", u);
    j.set("process_force_N", Json::vector(h.force_base, 2));
    Json eq = Json::object();
    eq.set("converged", Json::boolean(h.deflection.converged));
    eq.set("iterations", Json::integer(h.deflection.iterations));
    j.set("equilibrium", eq);
  }
  j.set("tolerance_mm", Json::number(h.tolerance * 1e3, 4));
  j.set("verdict", Json::str(verdictName(h.verdict)));
  if (!h.reason.empty()) j.set("reason", Json::str(h.reason));
  j.set("mc_time_s", Json::number(h.mc_time, 3));
  return j;
}

Json summaryJson(const CapabilitySummary& s) {
  Json j = Json::object();
  j.set("holes", Json::integer(s.holes));
  Json v = Json::object();
  v.set("conforms", Json::integer(s.conforms));
  v.set("conforms-after-compensation", Json::integer(s.conforms_after_compensation));
  v.set("not-capable", Json::integer(s.not_capable));
  v.set("unreachable", Json::integer(s.unreachable));
  v.set("singular", Json::integer(s.singular));
  v.set("not-converged", Json::integer(s.not_converged));
  j.set("verdicts", v);
  j.set("robot_can_take", Json::integer(s.robot_can_take));
  j.set("mc_time_taken_s", Json::number(s.mc_time_taken, 2));
  j.set("mc_time_total_s", Json::number(s.mc_time_total, 2));
  j.set("process_share_mean", Json::number(s.mean_process_share, 4));
  j.set("process_share_max", Json::number(s.max_process_share, 4));
  return j;
}

}  // namespace roprec::api
