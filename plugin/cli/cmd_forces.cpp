/// `roprec forces`: the process forces of a cell alone (drilling, milling or a given wrench):
/// steady values as JSON, curves vs depth (drilling) or vs cutter angle (milling) as CSV, and the
/// single-test calibration of kst0/ksa0.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "compensator/support/atomic_file.hpp"
#include "compensator/precision/cell.hpp"
#include "compensator/support/error.hpp"
#include "compensator/process/process_spec.hpp"
#include "compensator/process/milling_robot.hpp"
#include "plugin/cli/cli.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/api/json.hpp"

namespace roprec::cli {
namespace {

constexpr double kMm = 1e-3;
constexpr double kMPa = 1e6;

std::string fixed(double v, int decimals) { return formatNumber(v, decimals); }

struct Measured {
  double thrust{0};
  double torque{0};
};

Measured parseCalibration(const std::string& text) {
  Measured m;
  bool has_f = false;
  bool has_m = false;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    const auto eq = tok.find('=');
    if (eq == std::string::npos) throw UsageError("--calibrate expects \"Fa_N=... M_Nm=...\", got '" + tok + "'");
    const std::string key = tok.substr(0, eq);
    const auto v = parseNumber(tok.substr(eq + 1));
    if (!v || !(*v > 0)) throw InputError("", 0, "--calibrate: " + key + " must be a positive number, got '" + tok.substr(eq + 1) + "'");
    if (key == "Fa_N" || key == "Fz_N") {
      m.thrust = *v;
      has_f = true;
    } else if (key == "M_Nm") {
      m.torque = *v;
      has_m = true;
    } else {
      throw UsageError("--calibrate: unknown key '" + key + "' (Fa_N, M_Nm)");
    }
  }
  if (!has_f || !has_m) throw UsageError("--calibrate needs both Fa_N=... and M_Nm=...");
  return m;
}

Json vec3(const Vec3& v, int decimals) { return Json::vector(v, decimals); }

Json lipJson(int index, const LipForces& l) {
  Json j = Json::object();
  j.set("lip", Json::integer(index));
  j.set("Ft_N", Json::number(l.Ft, 2));
  j.set("Fa_N", Json::number(l.Fa, 2));
  j.set("Frad_N", Json::number(l.Frad, 2));
  j.set("M_Nm", Json::number(l.M, 4));
  return j;
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

int runDrilling(const CellSpec& cell, ProcessSpec& spec, Json& root, std::string& csv,
                const std::optional<std::string>& calibrate, const std::optional<std::string>& out_xml,
                std::string& out_xml_text, double step, std::optional<double> axial_compliance) {
  DrillingSpec& s = spec.drilling;
  const DrillGeometry& g = s.geometry;
  root.set("process", Json::str("drilling"));
  root.set("material", Json::str(s.material->name));
  root.set("material_group", Json::str(s.material->group));
  Json drill = Json::object();
  drill.set("diameter_mm", Json::number(g.diameter / kMm, 4));
  drill.set("point_angle_deg", Json::number(g.point_angle / kDeg, 3));
  drill.set("helix_angle_deg", Json::number(g.helix_angle / kDeg, 3));
  drill.set("web_mm", Json::number(g.web_thickness / kMm, 4));
  drill.set("chisel_angle_deg", Json::number(g.chisel_angle / kDeg, 3));
  drill.set("chisel_half_length_mm", Json::number(g.chiselHalfLength() / kMm, 4));
  drill.set("point_length_mm", Json::number(g.pointLength() / kMm, 4));
  drill.set("runout_mm", Json::number(g.runout / kMm, 5));
  drill.set("runout_source", Json::str(s.runout_given ? "cell <drill runout_mm>" : s.deviation.runout_source));
  drill.set("angle_law", Json::str(s.law == AngleLaw::kGeometric ? "geometric" : "paper"));
  drill.set("working_angles", Json::boolean(s.working_angles));
  root.set("drill", drill);
  Json cut = Json::object();
  cut.set("feed_mm_per_rev", Json::number(s.feed / kMm, 4));
  cut.set("spindle_rpm", Json::number(s.spindle_rpm, 1));
  cut.set("depth_mm", Json::number(s.hole_depth / kMm, 3));
  cut.set("through", Json::boolean(s.through));
  root.set("cut", cut);

  DrillingModel model = drillingModelOf(s);
  if (calibrate) {
    const Measured meas = parseCalibration(*calibrate);
    const DrillingCalibration cal = calibrateDrilling(model, s.feed, meas.thrust, meas.torque);
    Json c = Json::object();
    c.set("measured_thrust_N", Json::number(meas.thrust, 3));
    c.set("measured_torque_Nm", Json::number(meas.torque, 4));
    c.set("model_before_thrust_N", Json::number(cal.thrust_model_before, 3));
    c.set("model_before_torque_Nm", Json::number(cal.torque_model_before, 4));
    c.set("kst0_before_N_mm2", Json::number(model.coeff.tangential.k0 / kMPa, 3));
    c.set("ksa0_before_N_mm2", Json::number(model.coeff.axial.k0 / kMPa, 3));
    c.set("kst0_N_mm2", Json::number(cal.coeff.tangential.k0 / kMPa, 3));
    c.set("ksa0_N_mm2", Json::number(cal.coeff.axial.k0 / kMPa, 3));
    c.set("model_after_thrust_N", Json::number(cal.thrust_model_after, 3));
    c.set("model_after_torque_Nm", Json::number(cal.torque_model_after, 4));
    root.set("calibration", c);
    std::ostringstream note;
    note << "calibrated by roprec forces from one test: Fa=" << fixed(meas.thrust, 3) << " N, M=" << fixed(meas.torque, 4)
         << " N m at Dc " << fixed(g.diameter / kMm, 3) << " mm, f " << fixed(s.feed / kMm, 4) << " mm/rev ("
         << s.material->name << ")";
    s.coeff = cal.coeff;
    s.coeff_source = note.str();
    model.coeff = cal.coeff;
    if (out_xml) out_xml_text = cellWithCalibratedCoefficients(readFileBytes(cell.file), cell.file, cal.coeff, note.str());
  }
  root.set("coefficients", coefficientsJson(s.coeff, s.coeff_source));

  const DrillingForces F = drillingForces(model, s.feed);
  Json st = Json::object();
  st.set("thrust_N", Json::number(F.thrust, 2));
  st.set("torque_Nm", Json::number(F.torque, 4));
  st.set("Fr_N", Json::number(F.residual, 2));
  st.set("tangential_N", Json::number(F.tangential, 2));
  st.set("thrust_lips_N", Json::number(F.thrust_lips, 2));
  st.set("thrust_chisel_N", Json::number(F.thrust_chisel, 2));
  st.set("chisel_share", Json::number(F.thrust > 0 ? F.thrust_chisel / F.thrust : 0.0, 4));
  st.set("torque_chisel_Nm", Json::number(F.torque_chisel, 4));
  st.set("power_kW", Json::number(F.torque * s.spindle_rpm * 2 * kPi / 60.0 / 1000.0, 4));
  Json lips = Json::array();
  lips.push(lipJson(1, F.lip[0]));
  lips.push(lipJson(2, F.lip[1]));
  st.set("lips", lips);
  root.set("steady", st);

  const ToolWrench w = toolWrench(F, 0.0);
  Json wj = Json::object();
  wj.set("frame", Json::str("tool: z = drill axis into the material; on the TCP; Fr rotates with the spindle "
                            "(shown at spindle angle 0, lip 1 on +x)"));
  wj.set("force_N", vec3(w.force, 2));
  wj.set("torque_Nm", vec3(w.torque, 4));
  wj.set("spindle_frequency_Hz", Json::number(s.spindle_rpm / 60.0, 4));
  root.set("wrench_tool", wj);

  DrillingData data(model);
  const std::vector<DepthSample> prof = drillingDepthProfile(model, data, s.feed, s.hole_depth, s.through, step);
  std::ostringstream c;
  c << "depth_mm,engaged_radius_mm,Fa_N,Ft_N,M_Nm,Fr_N\n";
  double maxF = 0;
  double maxM = 0;
  double maxR = 0;
  for (const DepthSample& d : prof) {
    const DrillingForces& f = d.forces;
    c << fixed(d.depth / kMm, 4) << ',' << fixed((f.r_out > f.r_in ? f.r_out : 0.0) / kMm, 4) << ','
      << fixed(f.thrust, 3) << ',' << fixed(f.tangential, 3) << ',' << fixed(f.torque, 5) << ','
      << fixed(f.residual, 3) << '\n';
    maxF = std::max(maxF, f.thrust);
    maxM = std::max(maxM, f.torque);
    maxR = std::max(maxR, f.residual);
  }
  csv = c.str();
  int code = 0;
  if (axial_compliance) {
    const std::vector<AxialCouplingSample> ac =
        drillingAxialCoupling(model, data, s.feed, s.hole_depth, s.through, *axial_compliance);
    std::ostringstream c2;
    c2 << "revolution,depth_mm,engaged_radius_mm,Fa_N,Ft_N,M_Nm,Fr_N,feed_mm,dz_um\n";
    bool all = true;
    double max_dz = 0;
    double min_f = 1e300;
    double max_f = 0;
    for (const AxialCouplingSample& x : ac) {
      const DrillingForces& f = x.forces;
      c2 << x.revolution << ',' << fixed(x.depth / kMm, 5) << ','
         << fixed((f.r_out > f.r_in ? f.r_out : 0.0) / kMm, 4) << ',' << fixed(f.thrust, 3) << ','
         << fixed(f.tangential, 3) << ',' << fixed(f.torque, 5) << ',' << fixed(f.residual, 3) << ','
         << fixed(x.feed / kMm, 6) << ',' << fixed(x.deflection * 1e6, 3) << '\n';
      all = all && x.converged;
      max_dz = std::max(max_dz, x.deflection);
      min_f = std::min(min_f, x.feed);
      max_f = std::max(max_f, x.feed);
    }
    csv = c2.str();
    Json aj = Json::object();
    aj.set("axial_compliance_um_per_N", Json::number(*axial_compliance * 1e6, 5));
    aj.set("revolutions", Json::integer(static_cast<std::int64_t>(ac.size())));
    aj.set("all_converged", Json::boolean(all));
    aj.set("max_deflection_um", Json::number(max_dz * 1e6, 3));
    aj.set("min_feed_mm", Json::number(min_f / kMm, 6));
    aj.set("max_feed_mm", Json::number(max_f / kMm, 6));
    root.set("axial_coupling", aj);
    if (!all) code = 1;
  }
  Json mx = Json::object();
  mx.set("thrust_N", Json::number(maxF, 2));
  mx.set("torque_Nm", Json::number(maxM, 4));
  mx.set("Fr_N", Json::number(maxR, 2));
  mx.set("samples", Json::integer(static_cast<std::int64_t>(prof.size())));
  mx.set("step_mm", Json::number(step / kMm, 4));
  root.set("max_over_depth", mx);

  const MachiningDeviation md = machiningDeviation(s.deviation, g, F.residual);
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
  root.set("machining_deviation", mj);
  return code;
}

int runMilling(ProcessSpec& spec, Json& root, std::string& csv, int points,
               const std::optional<ComplianceFunction>& robot_compliance) {
  const MillingSpec& s = spec.milling;
  root.set("process", Json::str("milling"));
  root.set("material", Json::str(s.material->name));
  root.set("frame", Json::str("milling: X = feed, phi clockwise from +Y, Z from the tool tip toward the spindle; "
                              "forces on the tool"));
  Json tool = Json::object();
  tool.set("diameter_mm", Json::number(s.tool.diameter / kMm, 4));
  tool.set("teeth", Json::integer(s.tool.teeth));
  tool.set("helix_angle_deg", Json::number(s.tool.helix_angle / kDeg, 3));
  tool.set("runout_mm", Json::number(s.tool.runout / kMm, 5));
  tool.set("runout_angle_deg", Json::number(s.tool.runout_angle / kDeg, 3));
  root.set("mill", tool);
  Json cut = Json::object();
  cut.set("ap_mm", Json::number(s.cut.ap / kMm, 4));
  cut.set("ae_mm", Json::number(s.cut.ae / kMm, 4));
  cut.set("fz_mm", Json::number(s.cut.fz / kMm, 5));
  cut.set("mode", Json::str(s.cut.mode == MillingMode::kUp ? "up" : s.cut.mode == MillingMode::kDown ? "down" : "slot"));
  cut.set("spindle_rpm", Json::number(s.cut.spindle_rpm, 1));
  root.set("cut", cut);
  Json co = Json::object();
  co.set("kc11_N_mm2", Json::number(s.coeff.kc11 / kMPa, 3));
  co.set("mc", Json::number(s.coeff.mc, 4));
  co.set("radial_ratio", Json::number(s.coeff.radial_ratio, 4));
  co.set("axial_ratio", Json::number(s.coeff.axial_ratio, 4));
  co.set("force_law", Json::str(s.mean_law == MeanForceLaw::kInstantaneous ? "instantaneous" : "mean_chip"));
  co.set("source", Json::str(s.coeff_source));
  root.set("coefficients", co);

  const MillingModel m = millingModelOf(s);
  const ImmersionAngles a = immersionAngles(s.tool.diameter, s.cut.ae, s.cut.mode);
  Json im = Json::object();
  im.set("start_deg", Json::number(a.start / kDeg, 4));
  im.set("exit_deg", Json::number(a.exit / kDeg, 4));
  im.set("h_m_mm", Json::number(meanChipThickness(s.cut.fz, a) / kMm, 6));
  root.set("immersion", im);
  const MillingProfile P = millingForceProfile(m);
  Json st = Json::object();
  st.set("mean_force_N", vec3(P.mean, 2));
  st.set("mean_force_coupling_law_N", vec3(millingMeanForce(m, s.cut.fz, s.cut.ae), 2));
  st.set("peak_xy_N", Json::number(P.peak_xy, 2));
  Json chips = Json::array();
  for (double h : P.max_chip) chips.push(Json::number(h / kMm, 5));
  st.set("max_chip_per_tooth_mm", chips);
  root.set("steady", st);
  std::ostringstream c;
  c << "angle_deg,Fx_N,Fy_N,Fz_N,Fxy_N\n";
  for (const MillingSample& smp : P.samples) {
    c << fixed(smp.angle / kDeg, 3) << ',' << fixed(smp.force.x(), 3) << ',' << fixed(smp.force.y(), 3) << ','
      << fixed(smp.force.z(), 3) << ',' << fixed(smp.force.head<2>().norm(), 3) << '\n';
  }
  csv = c.str();
  int code = 0;
  if (s.compliance || robot_compliance) {
    const std::vector<ComplianceFunction> path(static_cast<size_t>(points),
                                               robot_compliance ? *robot_compliance : linearCompliance(*s.compliance));
    const std::vector<CouplingResult> res = coupleMillingPath(m, path, s.coupling);
    Json cp = Json::object();
    if (robot_compliance) {
      cp.set("compliance", Json::str("robot model at --joints (nonlinear joint-compliance equilibrium)"));
    } else {
      const Mat3 row_major = s.compliance->transpose();
      cp.set("compliance_um_per_N", Json::vector(Eigen::Map<const Eigen::VectorXd>(row_major.data(), 9) * 1e6, 5));
    }
    cp.set("tolerance_um", Json::number(s.coupling.tolerance * 1e6, 4));
    cp.set("relaxation", Json::number(s.coupling.relaxation, 3));
    Json pts = Json::array();
    int idx = 0;
    for (const CouplingResult& r : res) {
      Json p = Json::object();
      p.set("point", Json::integer(idx++));
      p.set("converged", Json::boolean(r.converged));
      p.set("status", Json::str(couplingStatusName(r.status)));
      p.set("iterations", Json::integer(r.iterations));
      p.set("residual_um", Json::number(r.residual * 1e6, 5));
      p.set("loop_gain", Json::number(r.loop_gain, 4));
      p.set("deflection_um", vec3(r.delta * 1e6, 3));
      p.set("force_N", vec3(r.force, 2));
      p.set("fz_effective_mm", Json::number(r.fz_effective / kMm, 6));
      p.set("ae_effective_mm", Json::number(r.ae_effective / kMm, 6));
      pts.push(p);
      if (!r.converged) code = 1;
    }
    cp.set("points", pts);
    root.set("coupling", cp);
  }
  return code;
}

int run(Args& args, CommandContext& ctx) {
  const auto cell_path = args.option("cell");
  const auto csv_path = args.option("csv");
  const auto json_path = args.option("json");
  const auto calibrate = args.option("calibrate");
  auto out_xml = args.option("o");
  if (const auto alt = args.option("output")) out_xml = alt;
  const auto step_mm = args.option("step-mm");
  const auto points_opt = args.option("points");
  const auto axial_opt = args.option("axial-compliance-um-per-N");
  const auto joints_opt = args.option("joints");
  args.finish();
  if (!cell_path) throw UsageError("give --cell CELL.xml");
  double step = 0.05 * kMm;
  if (step_mm) {
    const auto v = parseNumber(*step_mm);
    if (!v || !(*v > 0)) throw InputError("", 0, "--step-mm must be a positive number");
    step = *v * kMm;
  }
  int points = 10;
  if (points_opt) {
    const auto v = parseNumber(*points_opt);
    if (!v || !(*v >= 1 && *v <= 100000) || *v != std::floor(*v)) throw InputError("", 0, "--points must be an integer >= 1");
    points = static_cast<int>(*v);
  }
  std::optional<double> axial_compliance;
  if (axial_opt) {
    const auto v = parseNumber(*axial_opt);
    if (!v || !(*v >= 0)) throw InputError("", 0, "--axial-compliance-um-per-N must be a number >= 0");
    axial_compliance = *v * 1e-6;
  }
  const CellSpec cell = loadCell(*cell_path);
  if (!cell.has_process) throw InputError(cell.file, cell.root.line, "the cell has no <process> element");
  ProcessSpec spec = parseProcess(cell.process);
  if (calibrate && spec.type != ProcessType::kDrilling) {
    throw InputError(cell.file, cell.process.line, "--calibrate needs a <process type=\"drilling\">");
  }
  if (out_xml && !calibrate) throw UsageError("-o/--o writes the calibrated cell: use it with --calibrate");

  Json root = Json::object();
  root.set("cell", Json::str(cell.name));
  std::string csv;
  std::string out_xml_text;
  int code = 0;
  switch (spec.type) {
    case ProcessType::kDrilling:
      code = runDrilling(cell, spec, root, csv, calibrate, out_xml, out_xml_text, step, axial_compliance);
      break;
    case ProcessType::kMilling:
    {
      std::optional<ComplianceFunction> robot;
      if (joints_opt) {
        // the robot's own deflection at this pose is the coupling's compliance
        const Robot r = loadRobot(cell.robot);
        nc::ToolAttachment tool;
        tool.T_flange_tcp = cell.tool.T_flange_tcp;
        tool.mass = cell.tool.mass;
        tool.com = cell.tool.com;
        tool.inertia = cell.tool.inertia;
        const nc::Model model = nc::buildModel(r.chain, tool);
        robot = robotMillingCompliance(model, complianceOf(r.card), parseJointsDeg(*joints_opt));
        root.set("joints_deg", Json::vector(parseJointsDeg(*joints_opt) / kDeg, 6));
      }
      code = runMilling(spec, root, csv, points, robot);
    }
      break;
    case ProcessType::kWrench: {
      root.set("process", Json::str("wrench"));
      Json wj = Json::object();
      wj.set("frame", Json::str("tool; on the TCP"));
      wj.set("force_N", vec3(spec.wrench.force, 3));
      wj.set("torque_Nm", vec3(spec.wrench.torque, 4));
      root.set("wrench_tool", wj);
      if (csv_path) throw InputError(cell.file, cell.process.line, "a wrench process has no curve: drop --csv");
      break;
    }
  }
  const std::string json_text = root.dump() + "\n";
  if (csv_path) emit(ctx, *csv_path, csv);
  if (out_xml) emit(ctx, *out_xml, out_xml_text);
  if (json_path) {
    emit(ctx, *json_path, json_text);
  } else {
    ctx.out << json_text;
  }
  return code;
}

const CommandRegistration reg{
    {"forces", "process forces of a cell (drilling, milling, wrench); single-test calibration",
     "usage: roprec forces --cell CELL.xml [--csv F.csv] [--json F.json] [--step-mm S]\n"
     "                     [--calibrate \"Fa_N=... M_Nm=...\" [--o|--output OUT.xml]] [--points N]\n"
     "                     [--axial-compliance-um-per-N C] [--joints \"j1 .. j6\"]\n\n"
     "Computes the process forces of the cell's <process> (the robot is loaded only with --joints).\n"
     "  drilling: steady thrust, torque, rotating runout force Fr, per-lip forces, chisel share, the wrench\n"
     "            on the TCP in the tool frame (z into the material: force z = -thrust, torque z = -M), the\n"
     "            machining-deviation budget (U_mach, k = 2); --csv writes depth_mm, engaged_radius_mm,\n"
     "            Fa_N, Ft_N, M_Nm, Fr_N through entry, steady cut and breakthrough.\n"
     "  milling:  immersion, h_m, revolution-mean and peak forces; --csv writes angle_deg, Fx_N, Fy_N,\n"
     "            Fz_N, Fxy_N over one revolution; with <coupling compliance_um_per_N=...> the coupled\n"
     "            iteration over --points path points (default 10), per point converged/iterations;\n"
     "            --joints (deg): the coupling's compliance is the cell robot's own deflection at that pose\n"
     "            (nonlinear joint-compliance equilibrium, feed along tool x).\n"
     "  wrench:   echoes the given tool-frame wrench.\n"
     "--axial-compliance-um-per-N (drilling): the feed absorbed by an axial compliance C at the TCP, one\n"
     "            quasi-static step per revolution (entry, steady cut, breakthrough lunge); the CSV is then\n"
     "            per revolution with feed_mm and dz_um columns.\n"
     "--calibrate identifies kst0 and ksa0 from one measured thrust and torque at the cell's diameter and\n"
     "feed; --o OUT.xml writes a copy of the cell with the calibrated <coefficients> (atomically).\n"
     "Exit 0 done; 1 some coupled points did not converge; 2 bad input (nothing written).\n",
     40, run}};

}  // namespace
}  // namespace roprec::cli
