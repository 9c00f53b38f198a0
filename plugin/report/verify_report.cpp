/// \file verify_report.cpp
/// The HTML report of `roprec verify` (see verify_report.hpp): self-contained, inline SVG,
/// deterministic; written with the element builder (html.hpp).
#include "plugin/report/verify_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "compensator/support/c_format.hpp"
#include "compensator/support/str_cat.hpp"
#include "plugin/api/job.hpp"
#include "plugin/report/hole_report.hpp"
#include "plugin/report/html.hpp"
#include "plugin/report/json.hpp"

namespace roprec::api {
namespace {

using report::Attr;
using report::fixed;
using report::Html;

/// A number as the report writes it (formatNumber: decimals < 0 is the shortest round trip).
std::string f(double v, int decimals) { return formatNumber(v, decimals); }
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

const char* const kArrowColours[] = {"#1f5fbf", "#e07b00"};  ///< measured, predicted

/// The arrow heads, one marker per colour (id "a" + the colour's hex digits).
void arrowHeads(Html& h) {
  h.open("defs");
  for (const char* c : kArrowColours) {
    h.open("marker", {{"id", std::string("a") + (c + 1)},
                      {"markerWidth", "6"},
                      {"markerHeight", "6"},
                      {"refX", "5"},
                      {"refY", "3"},
                      {"orient", "auto"}})
        .leaf("path", {{"d", "M0,0 L6,3 L0,6 z"}, {"fill", c}})
        .close("marker");
  }
  h.close("defs").markup("\n");
}

void arrow(Html& h, double x, double y, double dx, double dy, const char* colour) {
  h.leaf("line", {{"x1", fixed(x, 1)},
                  {"y1", fixed(y, 1)},
                  {"x2", fixed(x + dx, 1)},
                  {"y2", fixed(y + dy, 1)},
                  {"stroke", colour},
                  {"stroke-width", "1.6"},
                  {"marker-end", std::string("url(#a") + (colour + 1) + ")"}})
      .markup("\n");
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
void axisLabels(Html& h, const Face& face) {
  h.element("text",
            {{"x", fixed(kW / 2, 1)},
             {"y", fixed(kH - 8, 1)},
             {"text-anchor", "middle"},
             {"font-size", "11"}},
            face.x_label + " \u2192")
      .markup("\n")
      .element("text",
               {Attr::markup("transform", "translate(12 " + f(kH / 2, 1) + ") rotate(-90)"),
                {"text-anchor", "middle"},
                {"font-size", "11"}},
               face.y_label + " \u2192")
      .markup("\n");
}

/// The map's svg element and its background.
void openMap(Html& h) {
  h.open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
                 {"width", fixed(kW, 0)},
                 {"height", fixed(kH, 0)},
                 Attr::markup("viewBox", "0 0 " + report::num(kW, 0) + " " + report::num(kH, 0))})
      .markup("\n");
}

void background(Html& h) {
  h.leaf(
       "rect",
       {{"width", fixed(kW, 0)}, {"height", fixed(kH, 0)}, {"fill", "#fafafa"}, {"stroke", "#ccc"}})
      .markup("\n");
}

/// A workobject-frame vector (m) in the face's plot axes, scaled to px.
Vec3 inFace(const VerifyResult& r, const Face& face, const Vec3& v_W, double px_per_um) {
  return face.R.transpose() * r.prediction.context.cell.T_base_wobj.linear().transpose() * v_W *
         1e6 * px_per_um;
}

/// Each hole of the face with its measured (blue) and predicted (orange) deviation arrows.
void arrowMap(Html& h, const VerifyResult& r, const Face& face, double scale_px_per_um) {
  const std::vector<Eigen::Vector2d> pts = facePoints(r, face);
  const Plot pl = plotFor(pts);
  openMap(h);
  arrowHeads(h);
  background(h);
  for (size_t m = 0; m < face.holes.size(); ++m) {
    const HoleVerification& hole = r.holes[face.holes[m]];
    const double x = pl.px(pts[m].x()), y = pl.py(pts[m].y());
    h.open("circle", {{"cx", fixed(x, 1)}, {"cy", fixed(y, 1)}, {"r", "2"}, {"fill", "#444"}})
        .element("title", {}, hole.id)
        .close("circle")
        .markup("\n");
    const Vec3 em = inFace(r, face, hole.e_meas_W, scale_px_per_um);
    const Vec3 dp = inFace(r, face, hole.d_pred_W, scale_px_per_um);
    arrow(h, x, y, em.x(), -em.y(), kArrowColours[0]);
    arrow(h, x, y, dp.x(), -dp.y(), kArrowColours[1]);
  }
  axisLabels(h, face);
  h.close("svg").markup("\n");
}

/// Red to green by |r| / the 95 % region (capped at 1).
std::string residualColour(double q) {
  const int red = static_cast<int>(std::lround(255 * std::min(q, 1.0)));
  const int green = static_cast<int>(std::lround(180 * (1 - std::min(q, 1.0))));
  char col[16];
  std::snprintf(col, sizeof col, "#%02x%02x40", red, green);
  return col;
}

/// One hole of the residual map: coloured and sized by |r| / region, outlined by the decision,
/// ringed when outside the region, labelled when outside or non-conforming.
void residualMarker(Html& h, const HoleVerification& hole, double x, double y) {
  const double q = hole.U_region > 0 ? std::min(hole.r_norm / hole.U_region, 1.5) : 1.5;
  const bool nc = hole.decision == MeasuredDecision::kNonConformanceProven;
  const char* outline = nc                                                      ? "#cf222e"
                        : hole.decision == MeasuredDecision::kConformanceProven ? "#2da44e"
                                                                                : "#b07d00";
  const double rad = 4 + 6 * q;
  h.open("circle", {{"class", "vmk"},
                    {"cx", fixed(x, 1)},
                    {"cy", fixed(y, 1)},
                    {"r", fixed(rad, 1)},
                    {"fill", residualColour(q)},
                    {"stroke", outline},
                    {"stroke-width", nc ? "2.6" : "1.6"}})
      .element("title", {},
               strCat(hole.id, ": |r| ", formatNumber(hole.r_norm * 1e6, 1), " µm, region ",
                      formatNumber(hole.U_region * 1e6, 1), " µm, ",
                      measuredDecisionName(hole.decision)))
      .close("circle")
      .markup("\n");
  if (!hole.inside) {
    h.leaf("circle", {{"cx", fixed(x, 1)},
                      {"cy", fixed(y, 1)},
                      {"r", fixed(rad + 3, 1)},
                      {"fill", "none"},
                      {"stroke", "#000"}})
        .markup("\n");
  }
  if (nc || !hole.inside) {
    h.element("text",
              {{"class", "flabel"},
               {"x", fixed(x + rad + 3, 1)},
               {"y", fixed(y + 4, 1)},
               {"font-size", "11"},
               {"font-weight", "600"},
               {"fill", "#a40e26"}},
              hole.id)
        .markup("\n");
  }
}

void residualMap(Html& h, const VerifyResult& r, const Face& face) {
  const std::vector<Eigen::Vector2d> pts = facePoints(r, face);
  const Plot pl = plotFor(pts);
  openMap(h);
  background(h);
  for (size_t m = 0; m < face.holes.size(); ++m) {
    residualMarker(h, r.holes[face.holes[m]], pl.px(pts[m].x()), pl.py(pts[m].y()));
  }
  axisLabels(h, face);
  h.close("svg").markup("\n");
}

/// A table row of cells (text, escaped).
void row(Html& h, std::initializer_list<std::string> cells) {
  h.open("tr");
  for (const std::string& c : cells) h.element("td", {}, c);
  h.close("tr").markup("\n");
}

void statsRow(Html& h, const char* name, const MagnitudeStats& s) {
  row(h, {name, formatNumber(s.rms * 1e6, 1), formatNumber(s.mean * 1e6, 1),
          formatNumber(s.max * 1e6, 1)});
}

void statistics(Html& h, const VerifyResult& r) {
  const VerificationSummary& s = r.summary;
  h.markup(
      "<h2>Statistics</h2>\n<table><tr><th>|deviation ⊥ axis| [µm]</th><th>RMS</th>"
      "<th>mean</th><th>max</th></tr>\n");
  statsRow(h, "measured e_meas", s.measured);
  statsRow(h, "predicted δwork⊥", s.predicted);
  statsRow(h, "residual r = e_meas − δwork⊥", s.residual);
  h.markup("</table>\n")
      .element(
          "p", {},
          strCat(std::to_string(s.holes),
                 " holes; explained share 1 − RMS(r)/RMS(e_meas) = ", formatNumber(s.explained, 3),
                 "; inside the predicted 95 % region: ", std::to_string(s.inside), " (coverage ",
                 formatNumber(s.coverage, 3),
                 "); correlation predicted/measured along workobject x, y, z: ",
                 corr(s.correlation.x()), ", ", corr(s.correlation.y()), ", ",
                 corr(s.correlation.z()),
                 ". ISO 14253-1 on the measured values: ", std::to_string(s.conformance_proven),
                 " conformance proven, ", std::to_string(s.nonconformance_proven),
                 " non-conformance proven, ", std::to_string(s.no_decision), " no decision."))
      .markup("\n");
}

void identificationSummary(Html& h, const VerifyResult& r, const IdentificationResult& id) {
  h.element(
       "p", {},
       strCat(std::to_string(id.holes), " holes, registration ", registrationName(r.registration),
              "; ", id.converged ? "converged" : "NOT converged", " in ",
              std::to_string(id.iterations), " iterations; condition number ",
              std::isfinite(id.condition_number)
                  ? formatNumber(id.condition_number, -1)
                  : std::string("undefined (the holes identify no parameter)"),
              "; residual RMS ", formatNumber(id.rms_prior * 1e6, 1), " µm with the card → ",
              formatNumber(id.rms_final * 1e6, 1), " µm at the estimate. ", id.message))
      .markup("\n");
}

void parameterTable(Html& h, const IdentificationResult& id) {
  h.markup(
      "<table><tr><th>parameter</th><th>unit</th><th>prior</th><th>σ prior</th>"
      "<th>estimate</th><th>σ</th><th>σ/σ prior</th><th>identifiable</th></tr>\n");
  for (const IdentifiedParameter& q : id.parameters) {
    row(h, {q.name, q.unit, formatNumber(q.prior, -1), formatNumber(q.prior_sigma, -1),
            formatNumber(q.value, -1), formatNumber(q.sigma, -1), formatNumber(q.ratio, 3),
            q.identifiable ? "yes" : "no (prior kept)"});
  }
  h.markup("</table>\n");
}

void stiffnessTable(Html& h, const VerifyResult& r, const IdentificationResult& id) {
  h.markup(
      "<table><tr><th>joint</th><th>k card [N·m/rad]</th><th>k identified</th>"
      "<th>σ</th></tr>\n");
  for (int j = 0; j < 6; ++j) {
    const auto J = static_cast<size_t>(j);
    row(h, {std::to_string(j + 1),
            formatNumber(r.prediction.context.robot.card.joints[J].stiffness, -1),
            formatNumber(id.compliance.k[j], 0),
            formatNumber(id.k_sigma[j], 0) + (id.joint_identified[J] ? "" : " (prior)")});
  }
  h.markup("</table>\n");
}

void identification(Html& h, const VerifyResult& r) {
  h.markup("<h2>Identification</h2>\n");
  if (!r.identification) {
    h.markup("<p>Not run (no --calibrate, no --register).</p>\n");
    return;
  }
  identificationSummary(h, r, *r.identification);
  parameterTable(h, *r.identification);
  stiffnessTable(h, r, *r.identification);
}

bool passes(const HoleVerification& hole) {
  return hole.inside && hole.decision != MeasuredDecision::kNonConformanceProven;
}

constexpr const char* kHoleHead =
    "<table class=\"holes\" id=\"holetable\"><thead><tr><th>#</th><th class=\"l\" "
    "data-t=\"1\">id</th><th>|e_meas|<br><small>µm</small></th><th>|δwork⊥|<br><small>µm</small>"
    "</th><th>|r|<br><small>µm</small></th><th>95 % region<br><small>µm</small></th><th "
    "class=\"l\" data-t=\"1\">inside</th><th>U_work<br><small>µm</small></th><th class=\"l\" "
    "data-t=\"1\">decision</th></tr></thead>\n<tbody>\n";

void holeRow(Html& h, const HoleVerification& hole, size_t n) {
  if (passes(hole)) {
    h.open("tr", {{"class", "pass"}});
  } else {
    h.open("tr");
  }
  h.element("td", {}, std::to_string(n + 1))
      .element("td", {{"class", "l"}}, hole.id)
      .element("td", {}, formatNumber(hole.e_meas_norm * 1e6, 1))
      .element("td", {}, formatNumber(hole.d_pred_norm * 1e6, 1))
      .element("td", {}, formatNumber(hole.r_norm * 1e6, 1))
      .element("td", {}, formatNumber(hole.U_region * 1e6, 1))
      .element("td", {{"class", "l"}}, hole.inside ? "yes" : "NO")
      .element("td", {}, formatNumber(hole.U_work * 1e6, 1))
      .element("td", {{"class", "l"}}, measuredDecisionName(hole.decision))
      .close("tr")
      .markup("\n");
}

void holeTable(Html& h, const VerifyResult& r) {
  const long failing =
      std::count_if(r.holes.begin(), r.holes.end(), [](const auto& x) { return !passes(x); });
  h.markup(
       "<h2>Holes</h2>\n<p>In program order; click a column head to sort (again: the other "
       "way), tick the box to show only the holes outside the predicted region or proven "
       "non-conforming.</p>\n<input type=\"checkbox\" id=\"failonly\"><label for=\"failonly\"> "
       "outside the predicted region or non-conformance proven only (" +
       std::to_string(failing) + ")</label>\n")
      .markup(kHoleHead);
  for (size_t n = 0; n < r.holes.size(); ++n) holeRow(h, r.holes[n], n);
  // the prediction report's sort and filter script, inline: the file stays self-contained
  h.markup("</tbody></table>\n").markupElement("script", {}, reportTableScript()).markup("\n");
}

constexpr const char* kVerifyCss =
    "body{font-family:sans-serif;margin:20px}table{border-collapse:collapse;margin:8px 0}"
    "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}"
    "th{background:#eee}.maps{display:flex;flex-wrap:wrap;gap:12px}"
    "body{font-variant-numeric:tabular-nums}td.l,th.l{text-align:left}th small{font-weight:400}"
    "#failonly:checked~table.holes tr.pass{display:none}.holes.fonly tr.pass{display:none}"
    ".holes thead th{cursor:pointer;user-select:none}"
    ".holes th[aria-sort=ascending]::after{content:\" \\25b2\"}"
    ".holes th[aria-sort=descending]::after{content:\" \\25bc\"}"
    ".flabel{paint-order:stroke;stroke:#fff;stroke-width:3px}";

std::string fileName(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

/// Robot, cell, program, measured file and the registration found.
void intro(Html& h, const VerifyResult& r) {
  const PredictionContext& c = r.prediction.context;
  std::string text =
      strCat("robot ", c.robot.card.name, ", cell ", c.cell.name, ", program ",
             fileName(r.program_path), ", measured ", fileName(r.measured.path), " (",
             postproc::measuredFormatName(r.measured.format), ", ",
             std::to_string(r.measured.holes.size()), " holes, ", std::to_string(r.match.matched),
             " matched). Registration: ", registrationName(r.registration));
  if (r.identification && r.registration != Registration::kNone) {
    const Vec3 t = r.identification->registration.translation * 1e6;
    strAppend(text, " t = (", formatNumber(t.x(), 1), ", ", formatNumber(t.y(), 1), ", ",
              formatNumber(t.z(), 1), ") µm");
  }
  h.markup("<h1>roprec verify — measured vs predicted</h1>\n")
      .element("p", {}, text + ".")
      .markup("\n");
}

/// One map per face, each under its face's name.
template <class DrawMap>
void faceMaps(Html& h, const std::vector<Face>& fs, const DrawMap& draw) {
  h.open("div", {{"class", "maps"}}).markup("\n");
  for (const Face& face : fs) {
    h.open("div").element("h3", {}, face.name).markup("\n");
    draw(face);
    h.close("div").markup("\n");
  }
  h.close("div").markup("\n");
}

void maps(Html& h, const VerifyResult& r) {
  double mx = 1e-9;
  for (const HoleVerification& x : r.holes) mx = std::max({mx, x.e_meas_norm, x.d_pred_norm});
  const double scale = 60.0 / (mx * 1e6);  // px per µm: the largest arrow is 60 px
  const std::vector<Face> fs = faces(r);
  h.markup(
      "<h2>Measured (blue) and predicted (orange) deviation ⊥ axis, per face</h2>\n<p>Arrows: " +
      f(scale, 3) +
      " px per µm; positions in the face's plane, workobject (part) frame, mm.</p>\n");
  faceMaps(h, fs, [&](const Face& face) { arrowMap(h, r, face, scale); });
  h.markup(
      "<h2>Residual map</h2>\n<p>Colour and size: |r| / the predicted 95 % region; a black "
      "ring marks a hole outside it. Outline: the ISO 14253-1 decision on the measured value "
      "(green conformance proven, amber no decision, red non-conformance proven); the ids of "
      "holes outside the region or proven non-conforming are written next to them. Faces in "
      "the workobject (part) frame.</p>\n");
  faceMaps(h, fs, [&](const Face& face) { residualMap(h, r, face); });
}

void notes(Html& h, const VerifyResult& r) {
  if (r.notes.empty()) return;
  h.markup("<h2>Notes</h2>\n<ul>\n");
  for (const auto& n : r.notes) h.element("li", {}, n).markup("\n");
  h.markup("</ul>\n");
}

}  // namespace

std::string verifyReport(const VerifyResult& r) {
  std::string o;
  Html h(o);
  h.markup("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">")
      .element("title", {}, "roprec verify — " + fileName(r.program_path))
      .markup("\n")
      .markupElement("style", {}, kVerifyCss)
      .markup("</head><body>\n");
  intro(h, r);
  statistics(h, r);
  maps(h, r);
  identification(h, r);
  holeTable(h, r);
  notes(h, r);
  h.markup("<p>generated by roprec ").markup(version()).markup("</p>\n</body></html>\n");
  return o;
}

}  // namespace roprec::api
