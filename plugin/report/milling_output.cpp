/// The JSON, CSV and HTML of milling dynamics and chatter stability
/// (plugin/report/milling_output.hpp).
#include "plugin/report/milling_output.hpp"

#include <algorithm>
#include <sstream>

#include "compensator/support/c_format.hpp"
#include "compensator/support/xml_escape.hpp"
#include "plugin/api/job.hpp"

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
  if (p.mode_coupling_checked) j.set("mode_coupling", pathPointModeCouplingJson(p, ap));
  return j;
}

Json pathPointModeCouplingJson(const PathPointCompensation& p, double ap) {
  Json j = Json::object();
  j.set("bounded", Json::boolean(p.mode_coupling_bounded));
  if (p.mode_coupling_bounded) {
    j.set("ap_limit_mm", Json::number(p.mode_coupling_ap_limit / kMm, 4));
    j.set("frequency_Hz", Json::number(p.mode_coupling_hz, 3));
    j.set("kind", Json::str(p.mode_coupling_flutter ? "flutter" : "divergence"));
    j.set("margin", Json::number(p.mode_coupling_ap_limit / ap, 4));
  }
  j.set("stable", Json::boolean(!p.modeCouplingUnstable(ap)));
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

}  // namespace

namespace {

/// "lobes": the range and the deepest stable ap over it.
Json lobesSummaryJson(const MillingStabilityResult& r) {
  const double lo = r.rpm_lo;
  Json lj = Json::object();
  lj.set("rpm_min", Json::number(lo, 1));
  lj.set("rpm_max", Json::number(r.rpm_hi, 1));
  lj.set("speeds", Json::integer(r.steps));
  double best_rpm = lo;
  double best_ap = 0;
  for (const LobeSample& x : r.lobes) {
    if (x.limit.bounded && x.limit.ap_lim > best_ap) {
      best_ap = x.limit.ap_lim;
      best_rpm = x.spindle_rpm;
    }
  }
  lj.set("deepest_stable_ap_mm", Json::number(best_ap / kMm, 4));
  lj.set("at_rpm", Json::number(best_rpm, 1));
  return lj;
}

}  // namespace

MillingStabilityOutput millingStabilityOutput(const MillingStabilityResult& r) {
  MillingStabilityOutput out;
  out.json = Json::object();
  out.json.set("cell", Json::str(r.cell));
  if (r.joints) out.json.set("joints_deg", Json::vector(*r.joints / kDeg, 6));
  out.json.set("dynamics", millingDynamicsJson(r.dynamics, r.spec, r.joints.has_value()));
  out.json.set("stability", millingStabilityJson(r.dynamics, r.model));
  out.json.set("lobes", lobesSummaryJson(r));
  out.csv = lobeCsv(r.lobes);
  out.report = lobeReport(r.cell, r.lobes, r.spec, r.at);
  return out;
}

}  // namespace roprec::api
