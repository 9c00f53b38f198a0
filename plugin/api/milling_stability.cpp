/// Milling dynamics and chatter stability of a cell (plugin/api/milling_stability.hpp).
#include "plugin/api/milling_stability.hpp"

#include <algorithm>
#include <sstream>

#include "compensator/precision/cell.hpp"
#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"
#include "compensator/support/xml_escape.hpp"
#include "plugin/api/job.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/api/robot_setup.hpp"

namespace roprec::api {

namespace {

constexpr double kMm = 1e-3;
constexpr double kMPa = 1e6;

Json vec3(const Vec3& v, int decimals) { return Json::vector(v, decimals); }

Json modeJson(int index, const VibrationMode& v) {
  Json j = Json::object();
  j.set("mode", Json::integer(index));
  j.set("kind", Json::str(v.robot ? "robot" : "tool"));
  j.set("frequency_Hz", Json::number(v.omega / (2 * kPi), 3));
  j.set("damping_ratio", Json::number(v.zeta, 4));
  const double u = v.tcp.norm();
  j.set("tcp_direction", vec3(u > 0 ? Vec3(v.tcp / u) : Vec3::Zero(), 4));
  j.set("tcp_stiffness_N_per_um",
        Json::number(u > 0 ? v.tcpStiffness() * 1e-6 : 0.0, u > 0 ? 4 : 0));
  if (v.robot) j.set("joint_shape", Json::vector(v.joints, 4));
  return j;
}

}  // namespace

Json millingDynamicsJson(const ModalModel& dyn, const MillingSpec& s, bool robot) {
  Json d = Json::object();
  d.set("source", Json::str(s.dynamics_source));
  d.set("robot_modes",
        Json::str(robot ? "multibody mass matrix and joint+servo stiffness at --joints"
                        : "none: give --joints for the robot's modes at a pose"));
  d.set("tooth_frequency_Hz", Json::number(s.cut.spindle_rpm / 60.0 * s.tool.teeth, 3));
  Json modes = Json::array();
  int i = 0;
  for (const VibrationMode& v : dyn.modes) modes.push(modeJson(++i, v));
  d.set("modes", modes);
  const Mat3 H0 = receptance(dyn, 0.0).real().transpose();  // row-major below
  d.set("static_compliance_um_per_N",
        Json::vector(Eigen::Map<const Eigen::VectorXd>(H0.data(), 9) * 1e6, 5));
  return d;
}

Json millingStabilityJson(const ModalModel& dyn, const MillingModel& m) {
  const StabilityCut cut = stabilityCutOf(m);
  const StabilityLimit lim = limitingDepth(dyn, cut, m.cut.spindle_rpm);
  Json j = Json::object();
  j.set("method", Json::str("zero-order approximation (Altintas & Budak), XY receptance"));
  j.set("Kt_N_mm2", Json::number(cut.Kt / kMPa, 3));
  j.set("Kr", Json::number(cut.Kr, 4));
  const Eigen::Matrix2d a = directionalFactors(cut.arc, cut.Kr).transpose();
  j.set("directional_factors", Json::vector(Eigen::Map<const Eigen::Vector4d>(a.data()), 5));
  j.set("spindle_rpm", Json::number(m.cut.spindle_rpm, 1));
  j.set("bounded", Json::boolean(lim.bounded));
  if (lim.bounded) {
    j.set("ap_limit_mm", Json::number(lim.ap_lim / kMm, 4));
    j.set("chatter_frequency_Hz", Json::number(lim.chatter_hz, 2));
    j.set("lobe", Json::integer(lim.lobe));
    j.set("margin", Json::number(lim.ap_lim / m.cut.ap, 4));
  }
  j.set("stable", Json::boolean(!lim.bounded || lim.ap_lim > m.cut.ap));
  return j;
}

Json pathPointStabilityJson(const PathPointCompensation& p, double ap) {
  Json j = Json::object();
  j.set("checked", Json::boolean(p.stability_checked));
  if (!p.stability_checked) return j;
  j.set("bounded", Json::boolean(p.stability_bounded));
  if (p.stability_bounded) {
    j.set("ap_limit_mm", Json::number(p.ap_limit / kMm, 4));
    j.set("chatter_frequency_Hz", Json::number(p.chatter_hz, 2));
    j.set("margin", Json::number(p.ap_limit / ap, 4));
  }
  j.set("stable", Json::boolean(!p.unstable(ap)));
  j.set("first_mode_Hz", Json::number(p.first_mode_hz, 3));
  return j;
}

namespace {

std::string lobeCsv(const std::vector<LobeSample>& lobes) {
  std::ostringstream c;
  c << "spindle_rpm,ap_limit_mm,chatter_Hz,lobe\n";
  for (const LobeSample& s : lobes) {
    c << formatNumber(s.spindle_rpm, 1) << ',';
    if (s.limit.bounded) {
      c << formatNumber(s.limit.ap_lim / kMm, 4) << ',' << formatNumber(s.limit.chatter_hz, 2)
        << ',' << s.limit.lobe;
    } else {
      c << ",,";
    }
    c << '\n';
  }
  return c.str();
}

/// The lobe diagram as an SVG polyline (ap limit vs speed), the programmed cut as a dot.
std::string lobePlot(const std::vector<LobeSample>& lobes, double rpm, double ap) {
  double top = ap;
  for (const LobeSample& s : lobes)
    if (s.limit.bounded) top = std::max(top, std::min(s.limit.ap_lim, 20 * ap));
  top *= 1.1;
  const double w = 760, h = 300, x0 = 60, y0 = 20;
  const double lo = lobes.front().spindle_rpm;
  const double hi = std::max(lobes.back().spindle_rpm, lo + 1);
  auto px = [&](double n) { return cFixed(x0 + w * (n - lo) / (hi - lo), 1); };
  auto py = [&](double a) { return cFixed(y0 + h - h * std::min(a, top) / top, 1); };
  std::string line;
  for (const LobeSample& s : lobes)
    line += px(s.spindle_rpm) + "," + py(s.limit.bounded ? s.limit.ap_lim : top) + " ";
  std::string svg = "<svg width=\"860\" height=\"360\" role=\"img\" aria-label=\"lobes\">\n";
  svg +=
      "<polyline fill=\"none\" stroke=\"#1f4e9c\" stroke-width=\"1.5\" points=\"" + line + "\"/>\n";
  svg += "<circle cx=\"" + px(rpm) + "\" cy=\"" + py(ap) + "\" r=\"4\" fill=\"#c0392b\"/>\n";
  svg += "<text x=\"4\" y=\"" + cFixed(y0 + 4, 0) + "\" font-size=\"11\">" + cFixed(top / kMm, 2) +
         " mm</text>\n";
  svg += "<text x=\"" + cFixed(x0, 0) + "\" y=\"" + cFixed(y0 + h + 20, 0) +
         "\" font-size=\"11\">" + cFixed(lo, 0) + " rpm</text>\n<text x=\"" +
         cFixed(x0 + w - 60, 0) + "\" y=\"" + cFixed(y0 + h + 20, 0) + "\" font-size=\"11\">" +
         cFixed(hi, 0) + " rpm</text>\n</svg>\n";
  return svg;
}

std::string lobeReport(const std::string& cell, const std::vector<LobeSample>& lobes,
                       const MillingSpec& s, const StabilityLimit& at) {
  std::string r =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>roprec milling "
      "stability — " +
      escapeXml(cell) + "</title></head><body style=\"font-family:sans-serif\">\n";
  r +=
      "<h1>Stability lobes (zero-order approximation)</h1>\n<p>cell <b>" + escapeXml(cell) +
      "</b>; cut ap " + cFixed(s.cut.ap / kMm, 3) + " mm at " + cFixed(s.cut.spindle_rpm, 0) +
      " rpm (red dot); limiting ap there: <b>" +
      (at.bounded ? cFixed(at.ap_lim / kMm, 3) + " mm (chatter " + cFixed(at.chatter_hz, 1) + " Hz)"
                  : std::string("unbounded")) +
      "</b>.</p>\n";
  r += lobePlot(lobes, s.cut.spindle_rpm, s.cut.ap);
  r += "<p>Above the blue line the cut chatters. Dynamics: " + escapeXml(s.dynamics_source) +
       ". roprec " + std::string(version()) + "</p>\n</body></html>\n";
  return r;
}

/// The index of the mill `tool` selects (ProcessSpec::mills); the single mill without it.
size_t millOfRequest(const ProcessSpec& spec, const std::optional<std::string>& tool) {
  std::string mills;
  for (const MillingSpec& m : spec.mills) mills += (mills.empty() ? "" : ", ") + millLabel(m);
  if (!tool) {
    if (spec.mills.size() == 1) return 0;
    throw UsageError("the cell's tool table has " + std::to_string(spec.mills.size()) + " mills (" +
                     mills + "): which mill? Give --tool N");
  }
  const int i =
      spec.mills.size() == 1 && spec.mills.front().tool_key.empty() ? -1 : millIndex(spec, *tool);
  if (i < 0) throw UsageError("--tool " + *tool + ": the cell has no such mill (" + mills + ")");
  return static_cast<size_t>(i);
}

}  // namespace

MillingStabilityResult millingStability(const MillingStabilityRequest& req) {
  const CellSpec cell = loadCell(req.cell);
  if (!cell.has_process)
    throw InputError(cell.file, cell.root.line, "the cell has no <process> element");
  const ProcessSpec spec = parseProcess(cell.process);
  if (spec.type != ProcessType::kMilling)
    throw InputError(cell.file, cell.process.line,
                     "milling-stability needs a <process type=\"milling\">");
  const size_t mill = millOfRequest(spec, req.tool);
  const MillingSpec& s = spec.mills[mill];
  const double lo = req.rpm_lo.value_or(std::max(100.0, 0.2 * s.cut.spindle_rpm));
  const double hi = req.rpm_hi.value_or(2.0 * s.cut.spindle_rpm);
  if (!(lo > 0 && hi > lo)) throw UsageError("--rpm: give \"LO HI\" with 0 < LO < HI");
  ModalModel dyn;
  MillingStabilityResult out;
  out.json = Json::object();
  out.json.set("cell", Json::str(cell.name));
  if (req.joints) {
    const Robot r = loadRobot(cell.robot);
    CellSpec with = cell;  // the mill's own <tcp>, else the cell's <tool>
    if (mill < cell.drill_tools.size() && cell.drill_tools[mill])
      with.tool = *cell.drill_tools[mill];
    const nc::Model model = nc::buildModel(r.real_chain, toolOf(with));
    dyn = robotModes(model, complianceOf(r.card), *req.joints, s.robot_damping_ratio);
    out.json.set("joints_deg", Json::vector(*req.joints / kDeg, 6));
  }
  addToolMode(dyn, s.tool_mode);
  const MillingModel m = millingModelOf(s);
  out.json.set("dynamics", millingDynamicsJson(dyn, s, req.joints.has_value()));
  out.json.set("stability", millingStabilityJson(dyn, m));
  const StabilityCut cut = stabilityCutOf(m);
  const std::vector<LobeSample> lobes = stabilityLobes(dyn, cut, lo, hi, req.steps);
  const StabilityLimit at = limitingDepth(dyn, cut, s.cut.spindle_rpm);
  out.stable = !at.bounded || at.ap_lim > s.cut.ap;
  Json lj = Json::object();
  lj.set("rpm_min", Json::number(lo, 1));
  lj.set("rpm_max", Json::number(hi, 1));
  lj.set("speeds", Json::integer(req.steps));
  double best_rpm = lo;
  double best_ap = 0;
  for (const LobeSample& x : lobes) {
    if (x.limit.bounded && x.limit.ap_lim > best_ap) {
      best_ap = x.limit.ap_lim;
      best_rpm = x.spindle_rpm;
    }
  }
  lj.set("deepest_stable_ap_mm", Json::number(best_ap / kMm, 4));
  lj.set("at_rpm", Json::number(best_rpm, 1));
  out.json.set("lobes", lj);
  out.csv = lobeCsv(lobes);
  out.report = lobeReport(cell.name, lobes, s, at);
  return out;
}

}  // namespace roprec::api
