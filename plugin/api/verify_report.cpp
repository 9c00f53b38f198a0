/// The HTML report of `roprec verify` (verify.hpp): self-contained, inline SVG, deterministic.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "compensator/support/c_format.hpp"
#include "compensator/support/xml_escape.hpp"
#include "plugin/api/verify.hpp"
#include "plugin/report/hole_report.hpp"

namespace roprec::api {
namespace {

std::string esc(const std::string& s) { return escapeXml(s); }

std::string f(double v, int decimals) { return esc(formatNumber(v, decimals)); }
/// A correlation, "undefined" when it is (fewer than two holes, no spread along the axis).
std::string corr(double v) { return std::isfinite(v) ? f(v, 3) : std::string("undefined"); }

/// Holes of one face: the same drilling direction (workobject frame, rounded to 0.01).
struct Face {
  std::string name;
  /// Plot axes in the workobject (part) frame, as in the prediction report (docs/reports.md §2):
  /// a face drilled along ±Z: x = workobject X; a wall: y = workobject +Z projected on the face;
  /// otherwise e₁, e₂ of the face's first hole. Column 2 = the drilling direction.
  Mat3 R;
  std::string x_label, y_label;
  std::vector<size_t> holes;
};

/// "workobject X [mm]" when `d` is along a workobject axis (sign in `sign`), else its direction.
std::string axisName(const Vec3& d, double& sign) {
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) > 0.9995) {
      sign = d[i] > 0 ? 1.0 : -1.0;
      return std::string("workobject ") + "XYZ"[i] + " [mm]";
    }
  }
  sign = 1.0;
  return "(" + cFixed(d.x() + 0.0, 3) + ", " + cFixed(d.y() + 0.0, 3) + ", " +
         cFixed(d.z() + 0.0, 3) + ") [mm]";
}

Mat3 faceAxes(const Mat3& R_first) {
  const Vec3 a = R_first.col(2);
  Vec3 u, v;
  if (std::abs(a.z()) > 0.9995) {
    u = Vec3::UnitX();
    v = u.cross(a).normalized();
  } else if (std::abs(a.z()) < 0.9) {
    v = (Vec3::UnitZ() - a.z() * a).normalized();
    u = v.cross(a).normalized();
  } else {
    return R_first;
  }
  Mat3 R;
  R.col(0) = u;
  R.col(1) = v;
  R.col(2) = a;
  return R;
}

std::vector<Face> faces(const VerifyResult& r) {
  const Mat3 R_wobj_W = r.prediction.context.cell.T_base_wobj.linear().transpose();
  std::map<std::string, size_t> index;
  std::vector<Face> out;
  for (size_t n = 0; n < r.holes.size(); ++n) {
    const Mat3 R = R_wobj_W * r.nominal[n].linear();
    const Vec3 d = R.col(2);
    // rounded first, so that −0.001 and 0.001 are the same face (no "-0.00")
    auto r2 = [](double x) { return std::round(x * 100.0) / 100.0 + 0.0; };
    const std::string key = "drilled (" + cFixed(r2(d.x()), 2) + ", " + cFixed(r2(d.y()), 2) +
                            ", " + cFixed(r2(d.z()), 2) + ")";
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, out.size()).first;
      const Mat3 axes = faceAxes(R);
      double sx = 1, sy = 1;
      const std::string lx = axisName(axes.col(0), sx), ly = axisName(axes.col(1), sy);
      out.push_back({key, axes, lx, ly, {}});
    }
    out[it->second].holes.push_back(n);
  }
  return out;
}

constexpr double kW = 460, kH = 340, kPad = 30;

struct Plot {
  double x0, y0, s;  ///< mm → px: px = kPad + (x − x0) s
  double px(double x) const { return kPad + (x - x0) * s; }
  double py(double y) const { return kH - kPad - (y - y0) * s; }
};

Plot plotFor(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::Vector2d lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1.0});
  const double s = std::min((kW - 2 * kPad) / span, (kH - 2 * kPad) / span);
  return {lo.x(), lo.y(), s};
}

std::string arrow(double x, double y, double dx, double dy, const char* colour) {
  std::ostringstream o;
  o << "<line x1=\"" << f(x, 1) << "\" y1=\"" << f(y, 1) << "\" x2=\"" << f(x + dx, 1) << "\" y2=\""
    << f(y + dy, 1) << "\" stroke=\"" << colour << "\" stroke-width=\"1.6\" marker-end=\"url(#a"
    << colour + 1 << ")\"/>\n";
  return o.str();
}

std::string markers() {
  std::string s = "<defs>";
  for (const char* c : {"#1f5fbf", "#e07b00"}) {
    s += std::string("<marker id=\"a") + (c + 1) +
         "\" markerWidth=\"6\" markerHeight=\"6\" refX=\"5\" refY=\"3\" orient=\"auto\">"
         "<path d=\"M0,0 L6,3 L0,6 z\" fill=\"" +
         c + "\"/></marker>";
  }
  return s + "</defs>\n";
}

/// Positions of a face's holes in its plot axes (mm).
std::vector<Eigen::Vector2d> facePoints(const VerifyResult& r, const Face& face) {
  const Pose T_wobj_W = r.prediction.context.cell.T_base_wobj.inverse();
  std::vector<Eigen::Vector2d> pts;
  for (const size_t n : face.holes) {
    const Vec3 p = T_wobj_W * r.nominal[n].translation() * 1e3;
    pts.emplace_back(face.R.col(0).dot(p), face.R.col(1).dot(p));
  }
  return pts;
}

/// The face's axis names along the bottom and left edges (the part frame, docs/reports.md §2).
std::string axisLabels(const Face& face) {
  std::ostringstream o;
  o << "<text x=\"" << f(kW / 2, 1) << "\" y=\"" << f(kH - 8, 1)
    << "\" text-anchor=\"middle\" font-size=\"11\">" << esc(face.x_label) << " \u2192</text>\n"
    << "<text transform=\"translate(12 " << f(kH / 2, 1)
    << ") rotate(-90)\" text-anchor=\"middle\" font-size=\"11\">" << esc(face.y_label)
    << " \u2192</text>\n";
  return o.str();
}

std::string arrowMap(const VerifyResult& r, const Face& face, double scale_px_per_um) {
  const std::vector<Eigen::Vector2d> pts = facePoints(r, face);
  const Plot pl = plotFor(pts);
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kW << "\" height=\"" << kH
    << "\" viewBox=\"0 0 " << kW << " " << kH << "\">\n"
    << markers();
  o << "<rect width=\"" << kW << "\" height=\"" << kH << "\" fill=\"#fafafa\" stroke=\"#ccc\"/>\n";
  for (size_t m = 0; m < face.holes.size(); ++m) {
    const HoleVerification& h = r.holes[face.holes[m]];
    const double x = pl.px(pts[m].x()), y = pl.py(pts[m].y());
    o << "<circle cx=\"" << f(x, 1) << "\" cy=\"" << f(y, 1) << "\" r=\"2\" fill=\"#444\"><title>"
      << esc(h.id) << "</title></circle>\n";
    const Vec3 em = face.R.transpose() *
                    r.prediction.context.cell.T_base_wobj.linear().transpose() * h.e_meas_W * 1e6 *
                    scale_px_per_um;
    const Vec3 dp = face.R.transpose() *
                    r.prediction.context.cell.T_base_wobj.linear().transpose() * h.d_pred_W * 1e6 *
                    scale_px_per_um;
    o << arrow(x, y, em.x(), -em.y(), "#1f5fbf") << arrow(x, y, dp.x(), -dp.y(), "#e07b00");
  }
  o << axisLabels(face);
  o << "</svg>\n";
  return o.str();
}

std::string residualMap(const VerifyResult& r, const Face& face) {
  const std::vector<Eigen::Vector2d> pts = facePoints(r, face);
  const Plot pl = plotFor(pts);
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kW << "\" height=\"" << kH
    << "\" viewBox=\"0 0 " << kW << " " << kH << "\">\n";
  o << "<rect width=\"" << kW << "\" height=\"" << kH << "\" fill=\"#fafafa\" stroke=\"#ccc\"/>\n";
  for (size_t m = 0; m < face.holes.size(); ++m) {
    const HoleVerification& h = r.holes[face.holes[m]];
    const double q = h.U_region > 0 ? std::min(h.r_norm / h.U_region, 1.5) : 1.5;
    const int red = static_cast<int>(std::lround(255 * std::min(q, 1.0)));
    const int green = static_cast<int>(std::lround(180 * (1 - std::min(q, 1.0))));
    char col[16];
    std::snprintf(col, sizeof col, "#%02x%02x40", red, green);
    const bool nc = h.decision == MeasuredDecision::kNonConformanceProven;
    const char* outline = nc                                                   ? "#cf222e"
                          : h.decision == MeasuredDecision::kConformanceProven ? "#2da44e"
                                                                               : "#b07d00";
    const double x = pl.px(pts[m].x()), y = pl.py(pts[m].y()), rad = 4 + 6 * q;
    o << "<circle class=\"vmk\" cx=\"" << f(x, 1) << "\" cy=\"" << f(y, 1) << "\" r=\"" << f(rad, 1)
      << "\" fill=\"" << col << "\" stroke=\"" << outline << "\" stroke-width=\""
      << (nc ? "2.6" : "1.6") << "\"><title>" << esc(h.id) << ": |r| " << f(h.r_norm * 1e6, 1)
      << " µm, region " << f(h.U_region * 1e6, 1) << " µm, " << measuredDecisionName(h.decision)
      << "</title></circle>\n";
    if (!h.inside) {
      o << "<circle cx=\"" << f(x, 1) << "\" cy=\"" << f(y, 1) << "\" r=\"" << f(rad + 3, 1)
        << "\" fill=\"none\" stroke=\"#000\"/>\n";
    }
    if (nc || !h.inside) {
      o << "<text class=\"flabel\" x=\"" << f(x + rad + 3, 1) << "\" y=\"" << f(y + 4, 1)
        << "\" font-size=\"11\" font-weight=\"600\" fill=\"#a40e26\">" << esc(h.id) << "</text>\n";
    }
  }
  o << axisLabels(face);
  o << "</svg>\n";
  return o.str();
}

std::string statsRow(const char* name, const MagnitudeStats& s) {
  return std::string("<tr><td>") + name + "</td><td>" + f(s.rms * 1e6, 1) + "</td><td>" +
         f(s.mean * 1e6, 1) + "</td><td>" + f(s.max * 1e6, 1) + "</td></tr>\n";
}

std::string statistics(const VerifyResult& r) {
  const VerificationSummary& s = r.summary;
  std::ostringstream o;
  o << "<h2>Statistics</h2>\n<table><tr><th>|deviation ⊥ axis| [µm]</th><th>RMS</th><th>mean</th>"
       "<th>max</th></tr>\n"
    << statsRow("measured e_meas", s.measured) << statsRow("predicted δwork⊥", s.predicted)
    << statsRow("residual r = e_meas − δwork⊥", s.residual) << "</table>\n<p>" << s.holes
    << " holes; explained share 1 − RMS(r)/RMS(e_meas) = " << f(s.explained, 3)
    << "; inside the predicted 95 % region: " << s.inside << " (coverage " << f(s.coverage, 3)
    << "); correlation predicted/measured along workobject x, y, z: " << corr(s.correlation.x())
    << ", " << corr(s.correlation.y()) << ", " << corr(s.correlation.z())
    << ". ISO 14253-1 on the measured values: " << s.conformance_proven << " conformance proven, "
    << s.nonconformance_proven << " non-conformance proven, " << s.no_decision
    << " no decision.</p>\n";
  return o.str();
}

std::string identification(const VerifyResult& r) {
  if (!r.identification)
    return "<h2>Identification</h2>\n<p>Not run (no --calibrate, no --register).</p>\n";
  const IdentificationResult& id = *r.identification;
  std::ostringstream o;
  o << "<h2>Identification</h2>\n<p>" << id.holes << " holes, registration "
    << registrationName(r.registration) << "; " << (id.converged ? "converged" : "NOT converged")
    << " in " << id.iterations << " iterations; condition number "
    << (std::isfinite(id.condition_number)
            ? f(id.condition_number, -1)
            : std::string("undefined (the holes identify no parameter)"))
    << "; residual RMS " << f(id.rms_prior * 1e6, 1) << " µm with the card → "
    << f(id.rms_final * 1e6, 1) << " µm at the estimate. " << esc(id.message) << "</p>\n";
  o << "<table><tr><th>parameter</th><th>unit</th><th>prior</th><th>σ prior</th><th>estimate</th>"
       "<th>σ</th><th>σ/σ prior</th><th>identifiable</th></tr>\n";
  for (const IdentifiedParameter& q : id.parameters) {
    o << "<tr><td>" << esc(q.name) << "</td><td>" << esc(q.unit) << "</td><td>" << f(q.prior, -1)
      << "</td><td>" << f(q.prior_sigma, -1) << "</td><td>" << f(q.value, -1) << "</td><td>"
      << f(q.sigma, -1) << "</td><td>" << f(q.ratio, 3) << "</td><td>"
      << (q.identifiable ? "yes" : "no (prior kept)") << "</td></tr>\n";
  }
  o << "</table>\n<table><tr><th>joint</th><th>k card [N·m/rad]</th><th>k identified</th>"
       "<th>σ</th></tr>\n";
  for (int j = 0; j < 6; ++j) {
    o << "<tr><td>" << j + 1 << "</td><td>"
      << f(r.prediction.context.robot.card.joints[static_cast<size_t>(j)].stiffness, -1)
      << "</td><td>" << f(id.compliance.k[j], 0) << "</td><td>" << f(id.k_sigma[j], 0)
      << (id.joint_identified[static_cast<size_t>(j)] ? "" : " (prior)") << "</td></tr>\n";
  }
  o << "</table>\n";
  return o.str();
}

std::string holeTable(const VerifyResult& r) {
  std::ostringstream o;
  size_t failing = 0;
  for (const HoleVerification& h : r.holes)
    failing += (!h.inside || h.decision == MeasuredDecision::kNonConformanceProven) ? 1 : 0;
  o << "<h2>Holes</h2>\n<p>In program order; click a column head to sort (again: the other "
       "way), tick the box to show only the holes outside the predicted region or proven "
       "non-conforming.</p>\n<input type=\"checkbox\" id=\"failonly\"><label for=\"failonly\"> "
       "outside the predicted region or non-conformance proven only ("
    << failing
    << ")</label>\n<table class=\"holes\" id=\"holetable\"><thead><tr><th>#</th><th "
       "class=\"l\" data-t=\"1\">id</th><th>|e_meas|<br><small>µm</small></th>"
       "<th>|δwork⊥|<br><small>µm</small></th><th>|r|<br><small>µm</small></th><th>95 % "
       "region<br><small>µm</small></th><th "
       "class=\"l\" data-t=\"1\">inside</th><th>U_work<br><small>µm</small></th>"
       "<th class=\"l\" data-t=\"1\">decision</th></tr></thead>\n<tbody>\n";
  for (size_t n = 0; n < r.holes.size(); ++n) {
    const HoleVerification& h = r.holes[n];
    const bool pass = h.inside && h.decision != MeasuredDecision::kNonConformanceProven;
    o << "<tr" << (pass ? " class=\"pass\"" : "") << "><td>" << n + 1 << "</td><td class=\"l\">"
      << esc(h.id) << "</td><td>" << f(h.e_meas_norm * 1e6, 1) << "</td><td>"
      << f(h.d_pred_norm * 1e6, 1) << "</td><td>" << f(h.r_norm * 1e6, 1) << "</td><td>"
      << f(h.U_region * 1e6, 1) << "</td><td class=\"l\">" << (h.inside ? "yes" : "NO")
      << "</td><td>" << f(h.U_work * 1e6, 1) << "</td><td class=\"l\">"
      << measuredDecisionName(h.decision) << "</td></tr>\n";
  }
  // the prediction report's sort and filter script, inline: the file stays self-contained
  return o.str() + "</tbody></table>\n<script>" + reportTableScript() + "</script>\n";
}

}  // namespace

std::string verifyReport(const VerifyResult& r) {
  const PredictionContext& c = r.prediction.context;
  double mx = 1e-9;
  for (const HoleVerification& h : r.holes) mx = std::max({mx, h.e_meas_norm, h.d_pred_norm});
  const double scale = 60.0 / (mx * 1e6);  // px per µm: the largest arrow is 60 px
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>roprec verify — "
    << esc(std::filesystem::path(r.program_path).filename().string())
    << "</title>\n<style>"
       "body{font-family:sans-serif;margin:20px}table{border-collapse:collapse;margin:8px 0}"
       "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}"
       "th{background:#eee}.maps{display:flex;flex-wrap:wrap;gap:12px}"
       "body{font-variant-numeric:tabular-nums}td.l,th.l{text-align:left}th small{font-weight:400}"
       "#failonly:checked~table.holes tr.pass{display:none}.holes.fonly tr.pass{display:none}"
       ".holes thead th{cursor:pointer;user-select:none}"
       ".holes th[aria-sort=ascending]::after{content:\" \\25b2\"}"
       ".holes th[aria-sort=descending]::after{content:\" \\25bc\"}"
       ".flabel{paint-order:stroke;stroke:#fff;stroke-width:3px}</style></head><body>\n";
  o << "<h1>roprec verify — measured vs predicted</h1>\n<p>robot " << esc(c.robot.card.name)
    << ", cell " << esc(c.cell.name) << ", program "
    << esc(std::filesystem::path(r.program_path).filename().string()) << ", measured "
    << esc(std::filesystem::path(r.measured.path).filename().string()) << " ("
    << postproc::measuredFormatName(r.measured.format) << ", " << r.measured.holes.size()
    << " holes, " << r.match.matched
    << " matched). Registration: " << registrationName(r.registration);
  if (r.identification && r.registration != Registration::kNone) {
    const Vec3 t = r.identification->registration.translation * 1e6;
    o << " t = (" << f(t.x(), 1) << ", " << f(t.y(), 1) << ", " << f(t.z(), 1) << ") µm";
  }
  o << ".</p>\n" << statistics(r);
  o << "<h2>Measured (blue) and predicted (orange) deviation ⊥ axis, per face</h2>\n<p>Arrows: "
    << f(scale, 3)
    << " px per µm; positions in the face's plane, workobject (part) frame, mm.</p>\n<div "
       "class=\"maps\">\n";
  const std::vector<Face> fs = faces(r);
  for (const Face& face : fs)
    o << "<div><h3>" << esc(face.name) << "</h3>\n" << arrowMap(r, face, scale) << "</div>\n";
  o << "</div>\n<h2>Residual map</h2>\n<p>Colour and size: |r| / the predicted 95 % region; a "
       "black ring marks a hole outside it. Outline: the ISO 14253-1 decision on the measured "
       "value (green conformance proven, amber no decision, red non-conformance proven); the ids "
       "of holes outside the region or proven non-conforming are written next to them. Faces in "
       "the workobject (part) frame.</p>\n<div class=\"maps\">\n";
  for (const Face& face : fs)
    o << "<div><h3>" << esc(face.name) << "</h3>\n" << residualMap(r, face) << "</div>\n";
  o << "</div>\n" << identification(r) << holeTable(r);
  if (!r.notes.empty()) {
    o << "<h2>Notes</h2>\n<ul>\n";
    for (const auto& n : r.notes) o << "<li>" << esc(n) << "</li>\n";
    o << "</ul>\n";
  }
  o << "<p>generated by roprec " << version() << "</p>\n</body></html>\n";
  return o.str();
}

}  // namespace roprec::api
