/// The summary and time history of `roprec simulate` (plugin/report/simulate_output.hpp).
#include "plugin/report/simulate_output.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "compensator/support/c_format.hpp"
#include "compensator/support/fixed_chars.hpp"
#include "plugin/report/deflect_json.hpp"

namespace roprec::api {

namespace {

/// What the summary reports of the history.
struct HistoryStats {
  const nc::TransientSample* last_full{nullptr};  ///< last sample in full engagement
  double max_entry{0.0};                          ///< |dp| max during entry, m
  double max_dev{0.0};                            ///< |dp| max, m
  double t_max{0.0};                              ///< its time, s
  double max_change{0.0};                         ///< max |dp − dp(0)|, m
};

HistoryStats historyStats(const nc::TransientResult& r) {
  HistoryStats h;
  const Vec3 dp0 = r.samples.empty() ? Vec3::Zero() : r.samples.front().dp;
  for (const nc::TransientSample& smp : r.samples) {
    const double n = smp.dp.norm();
    if (smp.process.phase == nc::CyclePhase::kFull) h.last_full = &smp;
    if (smp.process.phase == nc::CyclePhase::kEntry) h.max_entry = std::max(h.max_entry, n);
    if (n > h.max_dev) {
      h.max_dev = n;
      h.t_max = smp.t;
    }
    h.max_change = std::max(h.max_change, (smp.dp - dp0).norm());
  }
  return h;
}

Json driveJson(const nc::DriveModel& d) {
  Json drive = Json::object();
  drive.set("servo", Json::str(d.servo == nc::ServoMode::kIdeal
                                   ? "ideal (no position_gain in the card)"
                                   : (d.integral ? "cascade P + PI" : "cascade P + P")));
  drive.set("stiffness_Nm_per_rad", Json::vector(d.k, -1));
  drive.set("motor_inertia_kgm2", Json::vector(d.motor_inertia, 4));
  drive.set("damping_Nms_per_rad", Json::vector(d.damping, 3));
  drive.set("position_gain_per_s", Json::vector(d.kv, 3));
  drive.set("velocity_gain_Nms_per_rad", Json::vector(d.kw, 3));
  return drive;
}

Json staticJson(const StaticReference& ref) {
  Json st = Json::object();
  st.set("gravity_only_um", Json::vector(ref.gravity_only.dp * 1e6, 4));
  st.set("full_engagement_um", Json::vector(ref.full_engagement.dp * 1e6, 4));
  st.set("full_engagement_rotation_urad", Json::vector(ref.full_engagement.drot * 1e6, 3));
  return st;
}

/// Band of the settling time (the static model's resolution goal), m.
constexpr double kSettlingTolerance = 0.1e-6;

/// Settling onto the static deviation of the constant load that ends the run: the held load of a
/// constant process (from the end of its ramp), gravity alone after the end of a drilling cut,
/// gravity alone for no process.
Json settlingJson(const nc::TransientResult& r, const StaticReference& ref,
                  const nc::ProcessCycle& cycle) {
  const double t_last = r.samples.empty() ? 0.0 : r.samples.back().t;
  Vec3 dp_ref = ref.gravity_only.dp;
  double t_from = 0.0;
  double t_to = t_last;
  std::string reference = "static deviation under gravity alone";
  if (const auto* step = dynamic_cast<const nc::StepWrenchCycle*>(&cycle)) {
    dp_ref = ref.full_engagement.dp;
    t_from = step->holdStart();
    t_to = std::min(t_last, step->holdEnd());
    reference = "static deviation under the held load (deflect model, same compliance)";
  } else if (const auto* drill = dynamic_cast<const nc::DrillingCycle*>(&cycle)) {
    t_from = drill->cutEnd() >= 0 ? drill->cutEnd() : t_last;
    reference += " after the end of the cut";
  }
  const nc::Settling st = nc::settling(r.samples, dp_ref, t_from, t_to, kSettlingTolerance);
  Json j = Json::object();
  j.set("reference", Json::str(reference));
  j.set("tolerance_um", Json::number(kSettlingTolerance * 1e6, 3));
  j.set("from_t_s", Json::number(t_from, 6));
  j.set("settled", Json::boolean(st.settled));
  if (st.settled) {
    j.set("settling_time_s", Json::number(st.time, 6));
  } else {
    j.set("settling_time_s", Json::str("not settled within the run (extend --duration)"));
  }
  j.set("initial_error_um", Json::number(st.initial_error * 1e6, 4));
  j.set("final_error_um", Json::number(st.final_error * 1e6, 4));
  j.set("frequency_hz", Json::number(st.frequency_hz, 3));
  j.set("equivalent_damping_ratio", Json::number(st.damping_ratio, 4));
  return j;
}

/// The damping the run used: an estimate, not a card value.
Json dampingJson() {
  Json j = Json::object();
  j.set("joint_damping_ratio", Json::number(nc::DriveEstimateOptions{}.damping_ratio, 4));
  j.set("source",
        Json::str("estimate (not in the robot card): D = 2 zeta sqrt(k J_eff) per joint, "
                  "docs/transient.md; the equivalent damping ratio of the settling is what this "
                  "estimate produces, not a measurement"));
  return j;
}

/// What the drilling cycle did with the real penetration.
void drillingJson(const nc::TransientResult& r, const nc::DrillingCycle& c, Json& tr) {
  double fa_max = 0.0;
  double t_fa = 0.0;
  double h_min_cut = std::numeric_limits<double>::infinity();
  double last_cut = -1.0;
  for (const nc::TransientSample& smp : r.samples) {
    if (smp.process.Fa > fa_max) {
      fa_max = smp.process.Fa;
      t_fa = smp.t;
    }
    if (smp.process.cutting) {
      last_cut = smp.t;
      if (smp.t > c.feedEndTime()) h_min_cut = std::min(h_min_cut, smp.process.feed_per_rev);
    }
  }
  if (c.firstContact() >= 0) {
    tr.set("first_contact_t_s", Json::number(c.firstContact(), 6));
  } else {
    tr.set("first_contact_t_s", Json::str("no contact within the run"));
  }
  tr.set("feed_end_t_s", Json::number(c.feedEndTime(), 6));
  if (c.cutEnd() >= 0) {
    tr.set("end_of_cut_t_s", Json::number(c.cutEnd(), 6));
  } else {
    tr.set("end_of_cut_t_s", Json::str(last_cut >= 0 ? "still cutting at the end of the run"
                                                     : "no cut within the run"));
  }
  tr.set("end_of_cut_rule",
         Json::str("through hole: the corner leaves the plate; blind: the real feed per rev falls "
                   "below " +
                   cFixed(c.cutEndFeed() * 1e3, 4) +
                   " mm/rev (cut_end_feed_fraction of the feed) during the dwell"));
  tr.set("max_thrust_N", Json::number(fa_max, 3));
  tr.set("max_thrust_t_s", Json::number(t_fa, 6));
  const double depth = r.samples.empty() ? 0.0 : r.samples.back().process.depth;
  tr.set("cut_depth_mm", Json::number(depth * 1e3, 4));
  tr.set("commanded_end_depth_mm", Json::number(c.endDepth() * 1e3, 4));
  if (std::isfinite(h_min_cut))
    tr.set("dwell_min_feed_mm_per_rev", Json::number(h_min_cut * 1e3, 5));
}

Json transientJson(const nc::TransientResult& r, const StaticReference& ref,
                   const nc::ProcessCycle& cycle) {
  const HistoryStats h = historyStats(r);
  Json tr = Json::object();
  if (h.last_full != nullptr) {
    tr.set("end_of_full_engagement_t_s", Json::number(h.last_full->t, 6));
    tr.set("end_of_full_engagement_um", Json::vector(h.last_full->dp * 1e6, 4));
    tr.set("difference_to_static_um",
           Json::number((h.last_full->dp - ref.full_engagement.dp).norm() * 1e6, 4));
  }
  tr.set("max_deviation_entry_um", Json::number(h.max_entry * 1e6, 4));
  tr.set("max_deviation_um", Json::number(h.max_dev * 1e6, 4));
  tr.set("max_deviation_t_s", Json::number(h.t_max, 6));
  tr.set("max_change_from_start_um", Json::number(h.max_change * 1e6, 4));
  if (const auto* drill = dynamic_cast<const nc::DrillingCycle*>(&cycle)) {
    drillingJson(r, *drill, tr);
  }
  tr.set("settling", settlingJson(r, ref, cycle));
  tr.set("damping", dampingJson());
  return tr;
}

Json cvodeJson(const nc::TransientResult& r, const nc::TransientOptions& opt, double t_end) {
  Json cv = Json::object();
  cv.set("ok", Json::boolean(r.ok));
  if (!r.ok) cv.set("message", Json::str(r.message));
  cv.set("method", Json::str(opt.method == nc::Method::kBdf ? "BDF" : "Adams-Moulton"));
  cv.set("rtol", Json::number(opt.rtol, -1));
  cv.set("t_end_s", Json::number(t_end, 6));
  cv.set("stopped_at_cycle_end", Json::boolean(opt.stop_at_cycle_end && r.t_reached < t_end));
  cv.set("t_reached_s", Json::number(r.t_reached, 6));
  cv.set("steps", Json::integer(r.stats.steps));
  cv.set("rhs_evaluations", Json::integer(r.stats.rhs_evals + r.stats.rhs_evals_jac));
  cv.set("rhs_evaluations_jacobian", Json::integer(r.stats.rhs_evals_jac));
  cv.set("jacobian_evaluations", Json::integer(r.stats.jac_evals));
  cv.set("error_test_failures", Json::integer(r.stats.error_test_failures));
  cv.set("restarts", Json::integer(r.stats.restarts));
  cv.set("events", Json::integer(r.stats.events));
  return cv;
}

}  // namespace

Json simulationSummaryJson(const RobotSetup& setup, const HoleJoints& at,
                           const SimulationResult& r) {
  Json root = Json::object();
  root.set("robot", Json::str(setup.robot.card.name));
  root.set("cell", Json::str(setup.cell->name));
  root.set("joints_deg", Json::vector(at.joints / kDeg, 6));
  root.set("joints_source", Json::str(at.source));
  root.set("process", Json::str(r.process));
  if (!r.process_source.empty()) root.set("process_source", Json::str(r.process_source));
  root.set("gravity_handling", gravityHandlingJson(setup.robot, r.controller));
  root.set("drive", driveJson(r.drive));
  root.set("static", staticJson(r.static_reference));
  root.set("transient", transientJson(r.transient, r.static_reference, *r.cycle));
  root.set("cvode", cvodeJson(r.transient, r.options, r.t_end));
  return root;
}

namespace {

/// Fixed-point text with `decimals` decimals in the "C" locale; no "-0" ("nan"/"inf" as cFixed).
std::string fmt(int decimals, double v) {
  if (!std::isfinite(v)) return cFixed(v, decimals);
  std::string s;
  appendFixed(s, v, decimals);
  return s;
}

}  // namespace

std::string transientHistoryCsv(const nc::TransientResult& r) {
  std::string out =
      "t_s,depth_mm,Fa_N,Ft_N,M_Nm,Fr_N,dx_um,dy_um,dz_um,rx_urad,ry_urad,rz_urad,"
      "dq1_urad,dq2_urad,dq3_urad,dq4_urad,dq5_urad,dq6_urad,tip_mm,cut_depth_mm,"
      "feed_per_rev_mm,axial_um,phase\n";
  out.reserve(r.samples.size() * 200 + out.size());
  const nc::Vec6 q0 = r.samples.empty() ? nc::Vec6::Zero() : nc::Vec6(r.samples.front().theta_m);
  for (const nc::TransientSample& s : r.samples) {
    const double commanded = std::max(0.0, s.process.feed_position);
    out += fmt(6, s.t) + ',' + fmt(6, commanded * 1e3) + ',' + fmt(3, s.process.Fa) + ',' +
           fmt(3, s.process.Ft) + ',' + fmt(4, s.process.M) + ',' + fmt(3, s.process.Fr);
    for (int i = 0; i < 3; ++i) out += ',' + fmt(4, s.dp[i] * 1e6);
    for (int i = 0; i < 3; ++i) out += ',' + fmt(3, s.drot[i] * 1e6);
    for (int i = 0; i < 6; ++i) out += ',' + fmt(3, (s.theta[i] - q0[i]) * 1e6);
    out += ',' + fmt(6, s.process.tip * 1e3) + ',' + fmt(6, s.process.depth * 1e3) + ',' +
           fmt(6, s.process.feed_per_rev * 1e3) + ',' + fmt(4, s.process.axial * 1e6);
    out += ',';
    out += nc::phaseName(s.process.phase);
    out += '\n';
  }
  return out;
}
}  // namespace roprec::api
