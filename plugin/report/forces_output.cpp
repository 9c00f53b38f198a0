/// The JSON and CSV of `roprec forces` (plugin/report/forces_output.hpp).
#include "plugin/report/forces_output.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <vector>

#include "plugin/report/milling_output.hpp"

namespace roprec::api {

namespace {

constexpr double kMm = 1e-3;
constexpr double kMPa = 1e6;

std::string fixed(double v, int decimals) { return formatNumber(v, decimals); }

Json vec3(const Vec3& v, int decimals) { return Json::vector(v, decimals); }

// ---------------------------------------------------------------- drilling

Json drillJson(const DrillingSpec& s) {
  const DrillGeometry& g = s.geometry;
  Json drill = Json::object();
  drill.set("diameter_mm", Json::number(g.diameter / kMm, 4));
  drill.set("point_angle_deg", Json::number(g.point_angle / kDeg, 3));
  drill.set("helix_angle_deg", Json::number(g.helix_angle / kDeg, 3));
  drill.set("web_mm", Json::number(g.web_thickness / kMm, 4));
  drill.set("chisel_angle_deg", Json::number(g.chisel_angle / kDeg, 3));
  drill.set("chisel_half_length_mm", Json::number(g.chiselHalfLength() / kMm, 4));
  drill.set("point_length_mm", Json::number(g.pointLength() / kMm, 4));
  drill.set("runout_mm", Json::number(g.runout / kMm, 5));
  drill.set("runout_source",
            Json::str(s.runout_given ? "cell <drill runout_mm>" : s.deviation.runout_source));
  drill.set("angle_law", Json::str(s.law == AngleLaw::kGeometric ? "geometric" : "paper"));
  drill.set("working_angles", Json::boolean(s.working_angles));
  return drill;
}

Json drillingCutJson(const DrillingSpec& s) {
  Json cut = Json::object();
  cut.set("feed_mm_per_rev", Json::number(s.feed / kMm, 4));
  cut.set("spindle_rpm", Json::number(s.spindle_rpm, 1));
  cut.set("depth_mm", Json::number(s.hole_depth / kMm, 3));
  cut.set("through", Json::boolean(s.through));
  return cut;
}

Json coefficientsJson(const DrillingCoefficients& c, const std::string& source) {
  Json j = Json::object();
  j.set("kst0_N_mm2", Json::number(c.tangential.k0 / kMPa, 3));
  j.set("at", Json::number(c.tangential.a, 4));
  j.set("bt_per_deg", Json::number(c.tangential.b * kDeg, 5));
  j.set("ct_per_deg", Json::number(c.tangential.c * kDeg, 5));
  j.set("ksa0_N_mm2", Json::number(c.axial.k0 / kMPa, 3));
  j.set("aa", Json::number(c.axial.a, 4));
  j.set("ba_per_deg", Json::number(c.axial.b * kDeg, 5));
  j.set("ca_per_deg", Json::number(c.axial.c * kDeg, 5));
  j.set("m", Json::number(c.tangential.m, 4));
  j.set("chisel_model", Json::str(c.chisel.kind == ChiselModelKind::kRatio ? "ratio" : "pressure"));
  j.set("chisel_thrust_ratio", Json::number(c.chisel.thrust_ratio, 4));
  j.set("chisel_torque_ratio", Json::number(c.chisel.torque_ratio, 4));
  j.set("source", Json::str(source));
  return j;
}

/// "calibration": the test, the model before and after, kst0/ksa0 before and after.
Json calibrationJson(const DrillingForcesData& d) {
  const DrillingMeasurement& meas = *d.measurement;
  const DrillingCalibration& cal = *d.calibration;
  Json c = Json::object();
  c.set("measured_thrust_N", Json::number(meas.thrust, 3));
  c.set("measured_torque_Nm", Json::number(meas.torque, 4));
  c.set("model_before_thrust_N", Json::number(cal.thrust_model_before, 3));
  c.set("model_before_torque_Nm", Json::number(cal.torque_model_before, 4));
  c.set("kst0_before_N_mm2", Json::number(d.coeff_before.tangential.k0 / kMPa, 3));
  c.set("ksa0_before_N_mm2", Json::number(d.coeff_before.axial.k0 / kMPa, 3));
  c.set("kst0_N_mm2", Json::number(cal.coeff.tangential.k0 / kMPa, 3));
  c.set("ksa0_N_mm2", Json::number(cal.coeff.axial.k0 / kMPa, 3));
  c.set("model_after_thrust_N", Json::number(cal.thrust_model_after, 3));
  c.set("model_after_torque_Nm", Json::number(cal.torque_model_after, 4));
  return c;
}

Json lipJson(int index, const LipForces& l) {
  Json j = Json::object();
  j.set("lip", Json::integer(index));
  j.set("Ft_N", Json::number(l.Ft, 2));
  j.set("Fa_N", Json::number(l.Fa, 2));
  j.set("Frad_N", Json::number(l.Frad, 2));
  j.set("M_Nm", Json::number(l.M, 4));
  return j;
}

Json drillingSteadyJson(const DrillingForces& F, double spindle_rpm) {
  Json st = Json::object();
  st.set("thrust_N", Json::number(F.thrust, 2));
  st.set("torque_Nm", Json::number(F.torque, 4));
  st.set("Fr_N", Json::number(F.residual, 2));
  st.set("tangential_N", Json::number(F.tangential, 2));
  st.set("thrust_lips_N", Json::number(F.thrust_lips, 2));
  st.set("thrust_chisel_N", Json::number(F.thrust_chisel, 2));
  st.set("chisel_share", Json::number(F.thrust > 0 ? F.thrust_chisel / F.thrust : 0.0, 4));
  st.set("torque_chisel_Nm", Json::number(F.torque_chisel, 4));
  st.set("power_kW", Json::number(F.torque * spindle_rpm * 2 * kPi / 60.0 / 1000.0, 4));
  Json lips = Json::array();
  lips.push(lipJson(1, F.lip[0]));
  lips.push(lipJson(2, F.lip[1]));
  st.set("lips", lips);
  return st;
}

Json drillingWrenchJson(const DrillingForces& F, double spindle_rpm) {
  const ToolWrench w = toolWrench(F, 0.0);
  Json wj = Json::object();
  wj.set(
      "frame",
      Json::str("tool: z = drill axis into the material; on the TCP; Fr rotates with the spindle "
                "(shown at spindle angle 0, lip 1 on +x)"));
  wj.set("force_N", vec3(w.force, 2));
  wj.set("torque_Nm", vec3(w.torque, 4));
  wj.set("spindle_frequency_Hz", Json::number(spindle_rpm / 60.0, 4));
  return wj;
}

double engagedRadius(const DrillingForces& f) { return f.r_out > f.r_in ? f.r_out : 0.0; }

/// The curve over depth (CSV) and its maxima ("max_over_depth").
Json depthProfile(const std::vector<DepthSample>& prof, double step, std::string& csv) {
  std::ostringstream c;
  c << "depth_mm,engaged_radius_mm,Fa_N,Ft_N,M_Nm,Fr_N\n";
  double maxF = 0;
  double maxM = 0;
  double maxR = 0;
  for (const DepthSample& d : prof) {
    const DrillingForces& f = d.forces;
    c << fixed(d.depth / kMm, 4) << ',' << fixed(engagedRadius(f) / kMm, 4) << ','
      << fixed(f.thrust, 3) << ',' << fixed(f.tangential, 3) << ',' << fixed(f.torque, 5) << ','
      << fixed(f.residual, 3) << '\n';
    maxF = std::max(maxF, f.thrust);
    maxM = std::max(maxM, f.torque);
    maxR = std::max(maxR, f.residual);
  }
  csv = c.str();
  Json mx = Json::object();
  mx.set("thrust_N", Json::number(maxF, 2));
  mx.set("torque_Nm", Json::number(maxM, 4));
  mx.set("Fr_N", Json::number(maxR, 2));
  mx.set("samples", Json::integer(static_cast<std::int64_t>(prof.size())));
  mx.set("step_mm", Json::number(step / kMm, 4));
  return mx;
}

/// The feed absorbed by an axial compliance, one step per revolution: the CSV per revolution and
/// "axial_coupling".
Json axialCoupling(const std::vector<AxialCouplingSample>& ac, double compliance,
                   std::string& csv) {
  std::ostringstream c2;
  c2 << "revolution,depth_mm,engaged_radius_mm,Fa_N,Ft_N,M_Nm,Fr_N,feed_mm,dz_um\n";
  bool all = true;
  double max_dz = 0;
  double min_f = 1e300;
  double max_f = 0;
  for (const AxialCouplingSample& x : ac) {
    const DrillingForces& f = x.forces;
    c2 << x.revolution << ',' << fixed(x.depth / kMm, 5) << ',' << fixed(engagedRadius(f) / kMm, 4)
       << ',' << fixed(f.thrust, 3) << ',' << fixed(f.tangential, 3) << ',' << fixed(f.torque, 5)
       << ',' << fixed(f.residual, 3) << ',' << fixed(x.feed / kMm, 6) << ','
       << fixed(x.deflection * 1e6, 3) << '\n';
    all = all && x.converged;
    max_dz = std::max(max_dz, x.deflection);
    min_f = std::min(min_f, x.feed);
    max_f = std::max(max_f, x.feed);
  }
  csv = c2.str();
  Json aj = Json::object();
  aj.set("axial_compliance_um_per_N", Json::number(compliance * 1e6, 5));
  aj.set("revolutions", Json::integer(static_cast<std::int64_t>(ac.size())));
  aj.set("all_converged", Json::boolean(all));
  aj.set("max_deflection_um", Json::number(max_dz * 1e6, 3));
  aj.set("min_feed_mm", Json::number(min_f / kMm, 6));
  aj.set("max_feed_mm", Json::number(max_f / kMm, 6));
  return aj;
}

Json machiningDeviationJson(const DrillingSpec& s, const DrillingForces& F) {
  const MachiningDeviation md = machiningDeviation(s.deviation, s.geometry, F.residual);
  Json mj = Json::object();
  mj.set("U_mach_um", Json::number(md.U * 1e6, 2));
  mj.set("u_c_um", Json::number(md.u_c * 1e6, 2));
  mj.set("k", Json::number(md.k, 2));
  mj.set("tool_compliance_um_per_N", Json::number(md.tool_compliance * 1e6, 5));
  mj.set("lateral_force_N", Json::number(md.lateral_force, 2));
  Json comps = Json::array();
  for (const UncertaintyComponent& u : md.components) {
    Json cj = Json::object();
    cj.set("name", Json::str(u.name));
    cj.set("half_width_um", Json::number(u.half_width * 1e6, 3));
    cj.set("distribution", Json::str(distributionName(u.distribution)));
    cj.set("u_um", Json::number(u.standard * 1e6, 3));
    cj.set("source", Json::str(u.source));
    comps.push(cj);
  }
  mj.set("components", comps);
  return mj;
}

/// The drilling blocks of the forces JSON; `csv` the curve over depth (or per revolution).
void drillingJson(const DrillingForcesData& d, Json& root, std::string& csv) {
  const DrillingSpec& s = d.spec;
  const DrillingForces& F = d.steady;
  root.set("process", Json::str("drilling"));
  root.set("material", Json::str(s.material->name));
  root.set("material_group", Json::str(s.material->group));
  root.set("drill", drillJson(s));
  root.set("cut", drillingCutJson(s));
  if (d.calibration) root.set("calibration", calibrationJson(d));
  root.set("coefficients", coefficientsJson(s.coeff, s.coeff_source));
  root.set("steady", drillingSteadyJson(F, s.spindle_rpm));
  root.set("wrench_tool", drillingWrenchJson(F, s.spindle_rpm));
  const Json max_over_depth = depthProfile(d.profile, d.step, csv);
  if (d.axial_compliance)
    root.set("axial_coupling", axialCoupling(d.axial, *d.axial_compliance, csv));
  root.set("max_over_depth", max_over_depth);
  root.set("machining_deviation", machiningDeviationJson(s, F));
}

// ---------------------------------------------------------------- milling

Json millJson(const MillingSpec& s) {
  Json tool = Json::object();
  tool.set("diameter_mm", Json::number(s.tool.diameter / kMm, 4));
  tool.set("teeth", Json::integer(s.tool.teeth));
  tool.set("helix_angle_deg", Json::number(s.tool.helix_angle / kDeg, 3));
  tool.set("runout_mm", Json::number(s.tool.runout / kMm, 5));
  tool.set("runout_angle_deg", Json::number(s.tool.runout_angle / kDeg, 3));
  return tool;
}

Json millingCutJson(const MillingSpec& s) {
  Json cut = Json::object();
  cut.set("ap_mm", Json::number(s.cut.ap / kMm, 4));
  cut.set("ae_mm", Json::number(s.cut.ae / kMm, 4));
  cut.set("fz_mm", Json::number(s.cut.fz / kMm, 5));
  cut.set("mode", Json::str(s.cut.mode == MillingMode::kUp     ? "up"
                            : s.cut.mode == MillingMode::kDown ? "down"
                                                               : "slot"));
  cut.set("spindle_rpm", Json::number(s.cut.spindle_rpm, 1));
  return cut;
}

Json millingCoefficientsJson(const MillingSpec& s) {
  Json co = Json::object();
  co.set("kc11_N_mm2", Json::number(s.coeff.kc11 / kMPa, 3));
  co.set("mc", Json::number(s.coeff.mc, 4));
  co.set("radial_ratio", Json::number(s.coeff.radial_ratio, 4));
  co.set("axial_ratio", Json::number(s.coeff.axial_ratio, 4));
  co.set("force_law",
         Json::str(s.mean_law == MeanForceLaw::kInstantaneous ? "instantaneous" : "mean_chip"));
  co.set("source", Json::str(s.coeff_source));
  return co;
}

Json immersionJson(const MillingSpec& s) {
  const ImmersionAngles a = immersionAngles(s.tool.diameter, s.cut.ae, s.cut.mode);
  Json im = Json::object();
  im.set("start_deg", Json::number(a.start / kDeg, 4));
  im.set("exit_deg", Json::number(a.exit / kDeg, 4));
  im.set("h_m_mm", Json::number(meanChipThickness(s.cut.fz, a) / kMm, 6));
  return im;
}

/// "steady" (mean and peak forces over a revolution) and the CSV over the cutter angle.
Json millingSteady(const MillingProfile& P, const MillingModel& m, const MillingSpec& s,
                   std::string& csv) {
  Json st = Json::object();
  st.set("mean_force_N", vec3(P.mean, 2));
  st.set("mean_force_coupling_law_N", vec3(millingMeanForce(m, s.cut.fz, s.cut.ae), 2));
  st.set("peak_xy_N", Json::number(P.peak_xy, 2));
  Json chips = Json::array();
  for (double h : P.max_chip) chips.push(Json::number(h / kMm, 5));
  st.set("max_chip_per_tooth_mm", chips);
  std::ostringstream c;
  c << "angle_deg,Fx_N,Fy_N,Fz_N,Fxy_N\n";
  for (const MillingSample& smp : P.samples) {
    c << fixed(smp.angle / kDeg, 3) << ',' << fixed(smp.force.x(), 3) << ','
      << fixed(smp.force.y(), 3) << ',' << fixed(smp.force.z(), 3) << ','
      << fixed(smp.force.head<2>().norm(), 3) << '\n';
  }
  csv = c.str();
  return st;
}

Json couplingPointJson(int index, const CouplingResult& r) {
  Json p = Json::object();
  p.set("point", Json::integer(index));
  p.set("converged", Json::boolean(r.converged));
  p.set("status", Json::str(couplingStatusName(r.status)));
  p.set("iterations", Json::integer(r.iterations));
  p.set("compliance_evaluations", Json::integer(r.evaluations));
  p.set("residual_um", Json::number(r.residual * 1e6, 5));
  p.set("last_step_um", Json::number(r.step * 1e6, 5));
  p.set("loop_gain", Json::number(r.loop_gain, 4));
  p.set("deflection_um", vec3(r.delta * 1e6, 3));
  p.set("force_N", vec3(r.force, 2));
  p.set("force_nominal_N", vec3(r.force_nominal, 2));
  p.set("fz_effective_mm", Json::number(r.fz_effective / kMm, 6));
  p.set("ae_effective_mm", Json::number(r.ae_effective / kMm, 6));
  p.set("ap_effective_mm", Json::number(r.ap_effective / kMm, 6));
  p.set("uncut_carried_mm", Json::number(r.next.uncut_prev / kMm, 6));
  return p;
}

Json millimetres(const std::vector<double>& v_m, int decimals) {
  Json a = Json::array();
  for (const double v : v_m) a.push(Json::number(v / kMm, decimals));
  return a;
}

/// The revolution resolved by edge angle: per tooth, the chip-area feed and the peak chip of the
/// rigid tool at the programmed cut and of the vibrating tool at the coupled cut.
Json edgesJson(const EdgeRevolution& nominal, const EdgeRevolution& corrected) {
  Json e = Json::object();
  e.set("converged", Json::boolean(corrected.converged));
  e.set("iterations", Json::integer(corrected.iterations));
  e.set("tooth_feed_nominal_mm", millimetres(nominal.tooth_feed, 6));
  e.set("tooth_feed_mm", millimetres(corrected.tooth_feed, 6));
  e.set("max_chip_nominal_mm", millimetres(nominal.max_chip, 6));
  e.set("max_chip_mm", millimetres(corrected.max_chip, 6));
  return e;
}

/// The corrected revolution of the last coupled point (steady state) as CSV, and its summary.
Json correctedRevolutionOf(const CorrectedRevolution& cr, int point, std::string& csv) {
  std::ostringstream c;
  c << "angle_deg,Fx_nom_N,Fy_nom_N,Fz_nom_N,Fxy_nom_N,Fx_N,Fy_N,Fz_N,Fxy_N,dx_um,dy_um,dz_um\n";
  for (const CorrectedSample& s : cr.samples) {
    c << fixed(s.angle / kDeg, 3) << ',' << fixed(s.nominal.x(), 3) << ','
      << fixed(s.nominal.y(), 3) << ',' << fixed(s.nominal.z(), 3) << ','
      << fixed(s.nominal.head<2>().norm(), 3) << ',' << fixed(s.corrected.x(), 3) << ','
      << fixed(s.corrected.y(), 3) << ',' << fixed(s.corrected.z(), 3) << ','
      << fixed(s.corrected.head<2>().norm(), 3) << ',' << fixed(s.tcp_movement.x() * 1e6, 4) << ','
      << fixed(s.tcp_movement.y() * 1e6, 4) << ',' << fixed(s.tcp_movement.z() * 1e6, 4) << '\n';
  }
  csv = c.str();
  Json j = Json::object();
  j.set("point", Json::integer(point));
  j.set("mean_nominal_N", vec3(cr.mean_nominal, 2));
  j.set("mean_corrected_N", vec3(cr.mean_corrected, 2));
  j.set("peak_xy_nominal_N", Json::number(cr.peak_nominal_xy, 2));
  j.set("peak_xy_corrected_N", Json::number(cr.peak_corrected_xy, 2));
  j.set("tcp_movement_range_um", Json::number(cr.movement_range * 1e6, 3));
  j.set("vibration_peak_to_peak_um", vec3(cr.vibration_peak_to_peak * 1e6, 4));
  j.set("tcp_movement", Json::str("coupled static deflection + the vibration of the regenerative "
                                  "steady state through the receptance (\"dynamics\")"));
  j.set("edges", edgesJson(cr.nominal_edges, cr.corrected_edges));
  return j;
}

/// The coupled force/deflection solve over the path points with the cell's linear compliance or
/// the robot's own; the CSV becomes the corrected revolution of the last point.
Json millingCoupling(const MillingCouplingData& d, const MillingSpec& s, std::string& csv) {
  const Mat3& C_tool = d.tool_compliance;
  Json cp = Json::object();
  if (d.robot) {
    cp.set("compliance",
           Json::str("robot model at --joints (nonlinear joint-compliance equilibrium)"));
  } else {
    const Mat3 row_major = s.compliance->transpose();
    cp.set("compliance_um_per_N",
           Json::vector(Eigen::Map<const Eigen::VectorXd>(row_major.data(), 9) * 1e6, 5));
  }
  cp.set("tool_compliance_um_per_N", Json::number(C_tool(0, 0) * 1e6, 5));
  cp.set("solver", Json::str(couplingMethodName(s.coupling.method)));
  cp.set("tolerance_um", Json::number(s.coupling.tolerance * 1e6, 4));
  cp.set("relaxation", Json::number(s.coupling.relaxation, 3));
  Json pts = Json::array();
  int idx = 0;
  for (const CouplingResult& r : d.points) pts.push(couplingPointJson(idx++, r));
  cp.set("points", pts);
  cp.set("corrected_revolution", correctedRevolutionOf(d.corrected, idx - 1, csv));
  return cp;
}

/// A path point's revolution resolved by edge angle (PathPointCompensation::edges_*).
Json pathPointEdgesJson(const PathPointCompensation& p) {
  Json e = Json::object();
  e.set("converged", Json::boolean(p.edges_converged));
  e.set("tooth_feed_mm", millimetres(p.tooth_feed, 6));
  e.set("peak_xy_nominal_N", Json::number(p.peak_xy_nominal, 2));
  e.set("peak_xy_N", Json::number(p.peak_xy, 2));
  e.set("vibration_peak_to_peak_um", vec3(p.vibration_pp * 1e6, 4));
  return e;
}

/// One path point of `--program`: the cutting decision and the coupled solve with the robot's
/// compliance at the point (uncompensated: status, iterations, residual_um, force_N,
/// deviation_um), and the compensated point ("compensated").
Json pathPointJson(const MillingCompensationResult& r, size_t i) {
  const PathPointCompensation& p = r.point(i);
  Json j = Json::object();
  j.set("point", Json::integer(static_cast<std::int64_t>(i + 1)));
  j.set("line", Json::integer(r.targetLine(i)));
  if (r.context.model.process.mills.size() > 1) j.set("tool", Json::str(millOf(r, i).tool_key));
  j.set("cutting", Json::boolean(p.cutting));
  j.set("cutting_reason", Json::str(p.cutting_reason));
  j.set("status", Json::str(p.before_status));
  j.set("iterations", Json::integer(p.before_iterations));
  j.set("residual_um", Json::number(p.before_residual * 1e6, 5));
  j.set("loop_gain", Json::number(p.before_loop_gain, 4));
  j.set("force_N", vec3(p.before_force, 2));
  j.set("deviation_um", vec3(p.deviation_before * 1e6, 3));
  if (p.cutting) {
    j.set("surface_error_um", Json::number(p.surface_error_before * 1e6, 3));
    j.set("teeth_between_points", Json::number(p.teeth_between_points, 2));
    j.set("teeth_between_points_from", Json::str(p.teeth_from_cell ? "cell" : "point_spacing"));
    j.set("fz_effective_mm", Json::number(p.before_fz_effective / kMm, 6));
  }
  Json c = Json::object();
  c.set("ok", Json::boolean(p.ok));
  if (!p.ok) c.set("reason", Json::str(p.reason));
  c.set("status", Json::str(p.coupling_status));
  c.set("iterations", Json::integer(p.coupling_iterations));
  c.set("residual_um", Json::number(p.coupling_residual * 1e6, 5));
  c.set("force_N", vec3(p.force, 2));
  c.set("predicted_residual_um", Json::number(p.residual.norm() * 1e6, 4));
  if (p.cutting_after) c.set("surface_error_um", Json::number(p.surface_error * 1e6, 4));
  // box stock: the engagement each coupling used (the real paths') and the programmed path's
  const std::optional<MillingEngagement>& engaged = r.engagement(i);
  if (engaged && p.cutting_after) {
    c.set("ae_mm", Json::number(p.ae_after / kMm, 4));
    c.set("ap_mm", Json::number(p.ap_after / kMm, 4));
  }
  j.set("compensated", c);
  if (p.cutting && engaged) {
    j.set("ae_mm", Json::number(p.ae / kMm, 4));
    j.set("ap_mm", Json::number(p.ap / kMm, 4));
    j.set("programmed_ae_mm", Json::number(engaged->ae / kMm, 4));
    j.set("programmed_ap_mm", Json::number(engaged->ap / kMm, 4));
  }
  const double ap_i = pathPointAp(r, i);
  if (p.cutting) j.set("stability", pathPointStabilityJson(p, ap_i));
  if (p.edges_checked) j.set("edges", pathPointEdgesJson(p));
  return j;
}

/// `--program`: every linear point of the program (pathPointJson).
Json millingPath(const MillingCompensationResult& r, const std::string& program) {
  Json pts = Json::array();
  for (size_t i = 0; i < r.points_comp.size(); ++i) pts.push(pathPointJson(r, i));
  Json path = Json::object();
  path.set("program", Json::str(program));
  path.set("points", pts);
  return path;
}

/// The milling blocks of the forces JSON; `csv` the revolution (or the corrected revolution).
void millingJson(const MillingForcesData& d, Json& root, std::string& csv) {
  const MillingSpec& s = d.spec;
  const MillingModel& m = d.model;
  if (d.joints) root.set("joints_deg", Json::vector(*d.joints / kDeg, 6));
  root.set("process", Json::str("milling"));
  root.set("material", Json::str(s.material->name));
  root.set(
      "frame",
      Json::str("milling: X = feed, phi clockwise from +Y, Z from the tool tip toward the spindle; "
                "forces on the tool"));
  root.set("mill", millJson(s));
  root.set("cut", millingCutJson(s));
  root.set("coefficients", millingCoefficientsJson(s));
  root.set("immersion", immersionJson(s));
  root.set("steady", millingSteady(d.profile, m, s, csv));
  root.set("dynamics", millingDynamicsJson(d.dynamics, s, d.joints.has_value()));
  root.set("stability", millingStabilityJson(d.dynamics, m));
  if (d.coupling) root.set("coupling", millingCoupling(*d.coupling, s, csv));
  if (d.path) root.set("path", millingPath(*d.path, d.program));
}

// ---------------------------------------------------------------- wrench

Json wrenchJson(const WrenchSpec& w) {
  Json wj = Json::object();
  wj.set("frame", Json::str("tool; on the TCP"));
  wj.set("force_N", vec3(w.force, 3));
  wj.set("torque_Nm", vec3(w.torque, 4));
  return wj;
}

}  // namespace

ForcesOutput forcesOutput(const ForcesResult& r) {
  ForcesOutput out;
  out.json = Json::object();
  out.json.set("cell", Json::str(r.cell));
  if (r.drilling) drillingJson(*r.drilling, out.json, out.curve_csv);
  if (r.milling) millingJson(*r.milling, out.json, out.curve_csv);
  if (r.wrench) {
    out.json.set("process", Json::str("wrench"));
    out.json.set("wrench_tool", wrenchJson(*r.wrench));
  }
  return out;
}

std::string ForcesJsonStream::head(const ForcesResult& r) {
  ForcesOutput o = forcesOutput(r);  // no "path" yet: the milling root's last member
  const std::string text = o.json.dump();
  const std::string_view end = "\n}\n";
  if (!r.milling || r.milling->path || text.size() < end.size() ||
      text.compare(text.size() - end.size(), end.size(), end) != 0)
    throw InternalError("ForcesJsonStream::head: not a milling result before its path");
  write_(std::string_view(text).substr(0, text.size() - end.size()));
  write_(",");
  // the writer's own "{" stands for the root opened above
  json_.beginObject();
  json_.key("path");
  json_.beginObject();
  json_.key("program");
  json_.str(r.milling->program);
  json_.key("points");
  json_.beginArray();
  json_.take(text_);
  write_(std::string_view(text_).substr(1));
  return std::move(o.curve_csv);
}

void ForcesJsonStream::points(const MillingCompensationResult& block) {
  for (size_t i = block.first; i < block.first + block.points_comp.size(); ++i)
    json_.value(pathPointJson(block, i));
  json_.take(text_);
  write_(text_);
}

void ForcesJsonStream::finish() {
  json_.endArray();
  json_.endObject();
  json_.endObject();
  json_.finish();
  json_.take(text_);
  write_(text_);
}

}  // namespace roprec::api
