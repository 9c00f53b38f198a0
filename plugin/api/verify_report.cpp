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

namespace roprec::api {
namespace {

std::string esc(const std::string& s) { return escapeXml(s); }

std::string f(double v, int decimals) { return esc(formatNumber(v, decimals)); }

/// Holes of one face: the same drilling direction (workobject frame, rounded to 0.01).
struct Face {
  std::string name;
  Mat3 R;  ///< plot axes: x = e₁, y = e₂ of the face's first hole (workobject frame)
  std::vector<size_t> holes;
};

std::vector<Face> faces(const VerifyResult& r) {
  const Mat3 R_wobj_W = r.prediction.context.cell.T_base_wobj.linear().transpose();
  std::map<std::string, size_t> index;
  std::vector<Face> out;
  for (size_t n = 0; n < r.holes.size(); ++n) {
    const Mat3 R = R_wobj_W * r.nominal[n].linear();
    const Vec3 d = R.col(2);
    const std::string key = "drilled (" + cFixed(d.x() + 0.0, 2) + ", " + cFixed(d.y() + 0.0, 2) +
                            ", " + cFixed(d.z() + 0.0, 2) + ")";
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, out.size()).first;
      out.push_back({key, R, {}});
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
    o << "<circle cx=\"" << f(pl.px(pts[m].x()), 1) << "\" cy=\"" << f(pl.py(pts[m].y()), 1)
      << "\" r=\"" << f(4 + 6 * q, 1) << "\" fill=\"" << col << "\" stroke=\""
      << (h.inside ? "none" : "#000") << "\"><title>" << esc(h.id) << ": |r| "
      << f(h.r_norm * 1e6, 1) << " µm, region " << f(h.U_region * 1e6, 1)
      << " µm</title></circle>\n";
  }
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
    << "); correlation predicted/measured along workobject x, y, z: " << f(s.correlation.x(), 3)
    << ", " << f(s.correlation.y(), 3) << ", " << f(s.correlation.z(), 3)
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
    << " in " << id.iterations << " iterations; condition number " << f(id.condition_number, -1)
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
  o << "<h2>Holes</h2>\n<table><tr><th>id</th><th>|e_meas| µm</th><th>|δwork⊥| µm</th>"
       "<th>|r| µm</th><th>95 % region µm</th><th>inside</th><th>U_work "
       "µm</th><th>decision</th></tr>\n";
  for (const HoleVerification& h : r.holes) {
    o << "<tr><td>" << esc(h.id) << "</td><td>" << f(h.e_meas_norm * 1e6, 1) << "</td><td>"
      << f(h.d_pred_norm * 1e6, 1) << "</td><td>" << f(h.r_norm * 1e6, 1) << "</td><td>"
      << f(h.U_region * 1e6, 1) << "</td><td>" << (h.inside ? "yes" : "NO") << "</td><td>"
      << f(h.U_work * 1e6, 1) << "</td><td>" << measuredDecisionName(h.decision) << "</td></tr>\n";
  }
  return o.str() + "</table>\n";
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
       "th{background:#eee}.maps{display:flex;flex-wrap:wrap;gap:12px}</style></head><body>\n";
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
    << f(scale, 3) << " px per µm; positions in the face's plane (mm).</p>\n<div class=\"maps\">\n";
  const std::vector<Face> fs = faces(r);
  for (const Face& face : fs)
    o << "<div><h3>" << esc(face.name) << "</h3>\n" << arrowMap(r, face, scale) << "</div>\n";
  o << "</div>\n<h2>Residual map</h2>\n<p>Colour and size: |r| / the predicted 95 % region; a "
       "black ring marks a hole outside it.</p>\n<div class=\"maps\">\n";
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
