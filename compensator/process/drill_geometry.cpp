#include "compensator/process/drill_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "compensator/support/error.hpp"

namespace roprec {
namespace {

Eigen::Quaterniond rot(const Vec3& axis, double angle) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

}  // namespace

double DrillGeometry::chiselHalfLength() const { return halfWeb() / std::sin(chisel_angle); }

double DrillGeometry::pointLength() const {
  const double R = radius();
  const double w = halfWeb();
  const double a = chiselHalfLength();
  return (std::sqrt(R * R - w * w) - std::sqrt(std::max(0.0, a * a - w * w))) /
         std::tan(halfPoint());
}

std::string drillGeometryProblem(const DrillGeometry& g) {
  if (!(g.diameter > 0)) return "drill diameter must be > 0";
  if (!(g.point_angle > 60 * kDeg && g.point_angle < 180 * kDeg)) {
    return "point angle must lie in (60, 180) degrees, got " + numberText(g.point_angle / kDeg);
  }
  if (!(g.helix_angle >= 0 && g.helix_angle < 60 * kDeg))
    return "helix angle must lie in [0, 60) degrees";
  if (!(g.web_thickness >= 0)) return "web thickness must be >= 0";
  if (!(g.web_thickness < g.diameter)) {
    return "web is wider than the drill: 2w = " + numberText(g.web_thickness * 1e3) +
           " mm >= Dc = " + numberText(g.diameter * 1e3) + " mm";
  }
  if (!(g.chisel_angle > 90 * kDeg && g.chisel_angle < 180 * kDeg)) {
    return "chisel-edge angle must lie in (90, 180) degrees (obtuse end-view angle)";
  }
  if (g.lips != 2) return "only two-lip drills are modelled (lips=\"2\")";
  if (!(g.runout >= 0)) return "runout must be >= 0";
  if (!(g.chiselHalfLength() < 0.9 * g.radius())) {
    return "web is too wide for the drill: chisel half-length w/sin(psi) = " +
           numberText(g.chiselHalfLength() * 1e3) +
           " mm must stay below 0.9 R = " + numberText(0.9 * g.radius() * 1e3) + " mm";
  }
  if (!(g.runout < 0.1 * g.radius())) return "runout must be < 0.1 R";
  return {};
}

EdgeAngles closedFormEdgeAngles(const DrillGeometry& g, double r) {
  const double R = g.radius();
  const double p = g.halfPoint();
  const double w = g.halfWeb();
  EdgeAngles e;
  e.omega = std::asin(w / r);
  e.helix = std::atan(r / R * std::tan(g.helix_angle));
  e.lambda_s = std::asin(w / r * std::sin(p));
  e.kappa_r = std::atan(std::tan(p) * std::cos(e.omega));
  const double cl = std::cos(e.lambda_s);
  e.gamma_n = std::atan(std::tan(e.helix) * cl * cl / (std::sin(p) * std::cos(e.omega)) -
                        std::cos(p) * std::tan(e.omega));
  return e;
}

EdgeAngles paperEdgeAngles(const DrillGeometry& g, double r) {
  const EdgeAngles corner = closedFormEdgeAngles(g, g.radius());
  const double s = r / g.radius();
  EdgeAngles e;
  e.omega = std::asin(g.halfWeb() / r);
  e.helix = std::atan(s * std::tan(g.helix_angle));
  e.gamma_n = std::atan(s * std::tan(corner.gamma_n));
  e.lambda_s = std::atan(s * std::tan(corner.lambda_s));
  e.kappa_r = g.halfPoint();
  return e;
}

EdgeFrame edgeFrame(const DrillGeometry& g, double r, int lip, double feed_per_rev) {
  const double R = g.radius();
  const double p = g.halfPoint();
  const double w = g.halfWeb();
  const Vec3 z = Vec3::UnitZ();
  EdgeFrame F;
  // 1. position on the lip
  const double x = std::sqrt(r * r - w * w);
  const double theta = std::atan2(w, x);
  const Eigen::Quaterniond q_lip = rot(z, lip * 2.0 * kPi / g.lips);
  const Eigen::Quaterniond q_theta = rot(z, theta);
  const double xa = std::sqrt(std::max(0.0, g.chiselHalfLength() * g.chiselHalfLength() - w * w));
  F.position = q_lip * Vec3(x, w, -(x - xa) / std::tan(p));
  // 2. edge tangent (straight lip, outward)
  F.t = q_lip * Vec3(std::sin(p), 0.0, -std::cos(p));
  // 3. radial and tangential directions
  const Eigen::Quaterniond q_pos = q_lip * q_theta;
  F.e_r = q_pos * Vec3::UnitX();
  F.e_theta = q_pos * Vec3::UnitY();
  // 4. cutting velocity (static or working)
  F.v = feed_per_rev > 0 ? (2.0 * kPi * r * F.e_theta + feed_per_rev * z).normalized() : F.e_theta;
  // 5. helix tangent on the flute, up the flute: rot(e_r, -δ(r)) (-z)
  const double delta = std::atan(r / R * std::tan(g.helix_angle));
  F.helix = rot(F.e_r, -delta) * (-z);
  // 6. rake-face normal
  F.n_gamma = F.t.cross(F.helix).normalized();
  if (F.n_gamma.dot(F.v) < 0) F.n_gamma = -F.n_gamma;
  // 7. inclination (signed)
  F.lambda_s = std::asin(std::clamp(F.t.dot(F.v), -1.0, 1.0));
  // 8. normal plane Pn, chip-thickness direction, normal rake
  F.v_n = (F.v - F.v.dot(F.t) * F.t).normalized();
  F.c = F.t.cross(F.v_n).normalized();
  if (F.c.dot(z) > 0) F.c = -F.c;
  F.gamma_n = std::atan2(F.n_gamma.dot(F.c), F.n_gamma.dot(F.v_n));
  // 9. tool cutting-edge angle in the reference plane Pr (normal v)
  const Vec3 t_r = F.t - F.t.dot(F.v) * F.v;
  F.kappa_r = std::acos(std::clamp(std::abs(t_r.dot(z)) / t_r.norm(), 0.0, 1.0));
  // 10. chip flow: rotate the up-the-flute in-face direction by λs inside the rake face
  Vec3 u = F.n_gamma.cross(F.t).normalized();
  if (u.dot(F.helix) < 0) u = -u;
  F.chip_flow = rot(F.n_gamma, -F.lambda_s) * u;
  return F;
}

EdgeAngles edgeAngles(const DrillGeometry& g, AngleLaw law, double r, double feed_per_rev) {
  if (law == AngleLaw::kPaperProportional) return paperEdgeAngles(g, r);
  const EdgeFrame F = edgeFrame(g, r, 0, feed_per_rev);
  EdgeAngles e;
  e.gamma_n = F.gamma_n;
  e.lambda_s = std::abs(F.lambda_s);
  e.kappa_r = F.kappa_r;
  e.omega = std::asin(g.halfWeb() / r);
  e.helix = std::atan(r / g.radius() * std::tan(g.helix_angle));
  return e;
}

}  // namespace roprec
