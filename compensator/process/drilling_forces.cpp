#include "compensator/process/drilling_forces.hpp"

#include <algorithm>
#include <cmath>

#include "compensator/support/error.hpp"
#include "compensator/support/quadrature.hpp"

namespace roprec {
namespace {

constexpr double kHRef = 1e-3;  // Kienzle reference chip thickness 1 mm

double geometryFactor(const SpecificPressure& k, double gamma_n, double lambda_s) {
  return std::max(0.0, k.a + k.b * gamma_n + k.c * std::abs(lambda_s));
}

void fillNodes(const DrillingModel& m, double r_in, double r_out, EdgeNodes& N) {
  const double half = 0.5 * (r_out - r_in);
  const double mid = 0.5 * (r_out + r_in);
  for (int i = 0; i < m.nodes; ++i) {
    const size_t s = static_cast<size_t>(i);
    const double r = mid + half * m.gl_x[s];
    N.r[s] = r;
    N.weight[s] = half * m.gl_w[s];
    const EdgeFrame F =
        edgeFrame(m.geometry, r, 0, m.law == AngleLaw::kGeometric ? m.angle_feed : 0.0);
    EdgeAngles e;
    if (m.law == AngleLaw::kGeometric) {
      e.gamma_n = F.gamma_n;
      e.lambda_s = std::abs(F.lambda_s);
      e.kappa_r = F.kappa_r;
    } else {
      e = paperEdgeAngles(m.geometry, r);
    }
    N.g_t[s] = geometryFactor(m.coeff.tangential, e.gamma_n, e.lambda_s);
    N.g_a[s] = geometryFactor(m.coeff.axial, e.gamma_n, e.lambda_s);
    N.sin_kappa[s] = std::sin(e.kappa_r);
    N.cot_kappa[s] = 1.0 / std::tan(e.kappa_r);
    N.sin_pow_t[s] = std::pow(N.sin_kappa[s], -m.coeff.tangential.m);
    N.sin_pow_a[s] = std::pow(N.sin_kappa[s], -m.coeff.axial.m);
    const Eigen::Vector2d v(F.v.x(), F.v.y());
    const Eigen::Vector2d vn = v.normalized();
    N.vx[s] = vn.x();
    N.vy[s] = vn.y();
    N.erx[s] = F.e_r.x();
    N.ery[s] = F.e_r.y();
  }
}

struct LipSums {
  double Ft{0}, Fa{0}, Frad{0}, M{0};
  Eigen::Vector2d inplane{Eigen::Vector2d::Zero()};  // force on the tool, lip-1 orientation
};

/// One lip with chip factor q = h / sin κr [m] (constant along the lip).
LipSums integrateLip(const DrillingModel& m, const EdgeNodes& N, double q) {
  LipSums s;
  if (!(q > 0)) return s;
  const SpecificPressure& kt = m.coeff.tangential;
  const SpecificPressure& ka = m.coeff.axial;
  const double qt = std::pow(q / kHRef, -kt.m);
  const double qa = std::pow(q / kHRef, -ka.m);
  const double floor_t = std::pow(kt.h_min / kHRef, -kt.m);
  const double floor_a = std::pow(ka.h_min / kHRef, -ka.m);
  for (size_t i = 0; i < N.r.size(); ++i) {
    const double h = q * N.sin_kappa[i];
    const double ft = h >= kt.h_min ? qt * N.sin_pow_t[i] : floor_t;
    const double fa = h >= ka.h_min ? qa * N.sin_pow_a[i] : floor_a;
    const double dFt = kt.k0 * N.g_t[i] * ft * q * N.weight[i];
    const double dFa = ka.k0 * N.g_a[i] * fa * q * N.weight[i];
    const double dFrad = dFa * N.cot_kappa[i];
    s.Ft += dFt;
    s.Fa += dFa;
    s.Frad += dFrad;
    s.M += dFt * N.r[i];
    s.inplane.x() -= dFt * N.vx[i] + dFrad * N.erx[i];
    s.inplane.y() -= dFt * N.vy[i] + dFrad * N.ery[i];
  }
  return s;
}

/// Element of width dr at the corner cut with chip factor q (for the runout annulus).
LipSums cornerStrip(const DrillingModel& m, double q, double dr) {
  LipSums s;
  if (!(q > 0) || !(dr > 0)) return s;
  const SpecificPressure& kt = m.coeff.tangential;
  const SpecificPressure& ka = m.coeff.axial;
  const double h = std::max(q * m.corner_sin_kappa, 0.0);
  const double ft = std::pow(std::max(h, kt.h_min) / kHRef, -kt.m);
  const double fa = std::pow(std::max(h, ka.h_min) / kHRef, -ka.m);
  const double R = m.geometry.radius();
  s.Ft = kt.k0 * m.corner_g_t * ft * q * dr;
  s.Fa = ka.k0 * m.corner_g_a * fa * q * dr;
  s.Frad = s.Fa * m.corner_cot_kappa;
  s.M = s.Ft * R;
  s.inplane = -(s.Ft * m.corner_v + s.Frad * m.corner_er);
  return s;
}

void addSums(LipSums& a, const LipSums& b, double sign) {
  a.Ft += sign * b.Ft;
  a.Fa += sign * b.Fa;
  a.Frad += sign * b.Frad;
  a.M += sign * b.M;
  a.inplane += sign * b.inplane;
}

DrillingForces evaluate(const DrillingModel& m, const EdgeNodes& N, double feed, bool to_periphery,
                        bool chisel_engaged, double r_in, double r_out) {
  const DrillGeometry& g = m.geometry;
  const double rho = g.runout;
  const double dz = 2.0 * rho / std::tan(g.halfPoint());
  const double q1 = std::min(feed, 0.5 * feed + dz);  // alone (q2 = 0) lip 1 cuts the whole feed
  const double q2 = std::max(0.0, 0.5 * feed - dz);
  LipSums l1 = integrateLip(m, N, q1);
  LipSums l2 = integrateLip(m, N, q2);
  if (to_periphery && rho > 0) {
    // Lip 1 alone cuts [R−ρ, R+ρ] at the full feed; remove what the lips were credited on [R−ρ, R].
    addSums(l1, cornerStrip(m, feed, 2.0 * rho), +1.0);
    addSums(l1, cornerStrip(m, q1, rho), -1.0);
    addSums(l2, cornerStrip(m, q2, rho), -1.0);
  }
  DrillingForces F;
  F.r_in = r_in;
  F.r_out = r_out;
  F.chisel_engaged = chisel_engaged;
  F.lip[0] = LipForces{l1.Ft, l1.Fa, l1.Frad, l1.M};
  F.lip[1] = LipForces{l2.Ft, l2.Fa, l2.Frad, l2.M};
  F.thrust_lips = l1.Fa + l2.Fa;
  F.tangential = l1.Ft + l2.Ft;
  const double M_lips = l1.M + l2.M;
  if (chisel_engaged) {
    const ChiselModel& ch = m.coeff.chisel;
    F.thrust_chisel = ch.kind == ChiselModelKind::kRatio
                          ? ch.thrust_ratio * F.thrust_lips
                          : ch.pressure_ratio * m.coeff.axial.k0 * g.chiselHalfLength() * feed;
    F.torque_chisel = ch.torque_ratio * M_lips;
  }
  F.thrust = F.thrust_lips + F.thrust_chisel;
  F.torque = M_lips + F.torque_chisel;
  // Lip 2 sits at 180°: its in-plane vectors are the negatives of lip 1's at the same radius.
  F.residual_xy = l1.inplane - l2.inplane;
  F.residual = F.residual_xy.norm();
  return F;
}

}  // namespace

void EdgeNodes::resize(int n) {
  const size_t s = static_cast<size_t>(n);
  for (std::vector<double>* v : {&r, &weight, &g_t, &g_a, &sin_kappa, &cot_kappa, &sin_pow_t,
                                 &sin_pow_a, &vx, &vy, &erx, &ery}) {
    v->assign(s, 0.0);
  }
}

DrillingData::DrillingData(const DrillingModel& model) { partial.resize(model.nodes); }

DrillingModel makeDrillingModel(const DrillGeometry& g, const DrillingCoefficients& c, AngleLaw law,
                                double working_feed, int nodes) {
  DrillingModel m;
  m.geometry = g;
  m.coeff = c;
  m.law = law;
  m.angle_feed = working_feed;
  m.nodes = nodes;
  gaussLegendre(nodes, m.gl_x, m.gl_w);
  m.full.resize(nodes);
  fillNodes(m, g.chiselHalfLength(), g.radius(), m.full);
  const double R = g.radius();
  const EdgeFrame Fc = edgeFrame(g, R, 0, law == AngleLaw::kGeometric ? working_feed : 0.0);
  const EdgeAngles ec = law == AngleLaw::kGeometric
                            ? EdgeAngles{Fc.gamma_n, std::abs(Fc.lambda_s), Fc.kappa_r, 0, 0}
                            : paperEdgeAngles(g, R);
  m.corner_sin_kappa = std::sin(ec.kappa_r);
  m.corner_cot_kappa = 1.0 / std::tan(ec.kappa_r);
  m.corner_g_t = geometryFactor(c.tangential, ec.gamma_n, ec.lambda_s);
  m.corner_g_a = geometryFactor(c.axial, ec.gamma_n, ec.lambda_s);
  m.corner_v = Eigen::Vector2d(Fc.v.x(), Fc.v.y()).normalized();
  m.corner_er = Eigen::Vector2d(Fc.e_r.x(), Fc.e_r.y());
  return m;
}

ToolWrench toolWrench(const DrillingForces& F, double spindle_angle) {
  const double c = std::cos(spindle_angle);
  const double s = std::sin(spindle_angle);
  ToolWrench w;
  w.force = Vec3(c * F.residual_xy.x() - s * F.residual_xy.y(),
                 s * F.residual_xy.x() + c * F.residual_xy.y(), -F.thrust);
  w.torque = Vec3(0.0, 0.0, -F.torque);
  return w;
}

DrillingForces drillingForces(const DrillingModel& model, double feed) {
  return evaluate(model, model.full, feed, true, true, model.geometry.chiselHalfLength(),
                  model.geometry.radius());
}

DrillingForces drillingForcesEngaged(const DrillingModel& model, DrillingData& data, double feed,
                                     double r_in, double r_out, bool chisel_engaged) {
  const double a = model.geometry.chiselHalfLength();
  const double R = model.geometry.radius();
  r_in = std::clamp(r_in, a, R);
  r_out = std::clamp(r_out, a, R);
  if (r_out - r_in <= 1e-12) {
    DrillingForces F;
    F.r_in = r_in;
    F.r_out = r_out;
    F.chisel_engaged = chisel_engaged;
    if (chisel_engaged && model.coeff.chisel.kind == ChiselModelKind::kPressure) {
      F.thrust_chisel = model.coeff.chisel.pressure_ratio * model.coeff.axial.k0 * a * feed;
      F.thrust = F.thrust_chisel;
    }
    return F;
  }
  if (r_in <= a && r_out >= R)
    return evaluate(model, model.full, feed, true, chisel_engaged, r_in, r_out);
  fillNodes(model, r_in, r_out, data.partial);
  return evaluate(model, data.partial, feed, r_out >= R, chisel_engaged, r_in, r_out);
}

Engagement engagementAtDepth(const DrillGeometry& g, double depth, double thickness) {
  const double a = g.chiselHalfLength();
  const double R = g.radius();
  const double tp = std::tan(g.halfPoint());
  Engagement e;
  if (depth <= 0) {
    e.r_in = e.r_out = a;
    e.chisel = false;
    e.cutting = false;
    return e;
  }
  e.r_out = std::min(R, a + depth * tp);
  e.r_in = a;
  e.chisel = true;
  if (thickness > 0 && depth > thickness) {
    e.chisel = false;
    e.r_in = std::min(R, a + (depth - thickness) * tp);
  }
  e.cutting = e.r_out > e.r_in;
  return e;
}

DrillingForces drillingForcesAtDepth(const DrillingModel& model, DrillingData& data, double feed,
                                     double depth, double thickness) {
  const Engagement e = engagementAtDepth(model.geometry, depth, thickness);
  return drillingForcesEngaged(model, data, feed, e.r_in, e.r_out, e.chisel);
}

namespace {
double exitExtra(const DrillGeometry& g, bool through) {
  return through ? (g.radius() - g.chiselHalfLength()) / std::tan(g.halfPoint()) : 0.0;
}
std::string holeDepthProblem(double hole_depth) {
  if (!std::isfinite(hole_depth) || hole_depth < 0 || hole_depth > kMaxHoleDepth) {
    return "the hole depth " + numberText(hole_depth * 1e3) + " mm is out of range (0 to " +
           numberText(kMaxHoleDepth * 1e3) + " mm)";
  }
  return "";
}
}  // namespace

std::string depthProfileProblem(const DrillingModel& model, double hole_depth, bool through,
                                double step) {
  if (std::string p = holeDepthProblem(hole_depth); !p.empty()) return p;
  if (!std::isfinite(step) || !(step > 0)) {
    return "the depth step " + numberText(step * 1e3) + " mm must be a positive finite number";
  }
  const double z_end = hole_depth + exitExtra(model.geometry, through);
  const double rows = std::ceil(z_end / step - 1e-9) + 1;
  if (!(rows <= kMaxDepthSamples)) {
    return "a depth step of " + numberText(step * 1e3) + " mm over " + numberText(z_end * 1e3) +
           " mm gives " + numberText(rows, 3) + " rows (at most " + numberText(kMaxDepthSamples) +
           "; use a step of at least " + numberText(z_end / (kMaxDepthSamples - 1) * 1e3, 3) +
           " mm)";
  }
  return "";
}

std::string axialCouplingProblem(const DrillingModel& model, double feed, double hole_depth,
                                 bool through) {
  if (std::string p = holeDepthProblem(hole_depth); !p.empty()) return p;
  if (!std::isfinite(feed) || !(feed > 0)) return "";  // no revolutions at all
  const double z_end = hole_depth + exitExtra(model.geometry, through);
  const double revs = std::ceil(100.0 * z_end / feed) + 10;
  if (!(revs <= kMaxCouplingRevolutions)) {
    return "the axial coupling over " + numberText(z_end * 1e3) + " mm at " +
           numberText(feed * 1e3) + " mm per revolution needs more than " +
           numberText(kMaxCouplingRevolutions) + " revolutions";
  }
  return "";
}

std::vector<DepthSample> drillingDepthProfile(const DrillingModel& model, DrillingData& data,
                                              double feed, double hole_depth, bool through,
                                              double step) {
  if (std::string p = depthProfileProblem(model, hole_depth, through, step); !p.empty())
    throw InputError("", 0, p);
  const DrillGeometry& g = model.geometry;
  const double exit_extra = exitExtra(g, through);
  const double z_end = hole_depth + exit_extra;
  const int n = std::max(1, static_cast<int>(std::ceil(z_end / step - 1e-9)));
  std::vector<DepthSample> out;
  out.reserve(static_cast<size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double z = std::min(z_end, i * step);
    out.push_back({z, drillingForcesAtDepth(model, data, feed, z, through ? hole_depth : 0.0)});
  }
  return out;
}

std::vector<AxialCouplingSample> drillingAxialCoupling(const DrillingModel& model,
                                                       DrillingData& data, double feed,
                                                       double hole_depth, bool through,
                                                       double axial_compliance, double tolerance,
                                                       int max_iterations) {
  if (std::string p = axialCouplingProblem(model, feed, hole_depth, through); !p.empty())
    throw InputError("", 0, p);
  const DrillGeometry& g = model.geometry;
  const double exit_extra = exitExtra(g, through);
  const double z_end = hole_depth + exit_extra;
  const double thickness = through ? hole_depth : 0.0;
  std::vector<AxialCouplingSample> out;
  if (!(feed > 0)) return out;
  double z = 0.0;
  double d_prev = 0.0;
  const int max_revs = static_cast<int>(std::ceil(100.0 * z_end / feed)) + 10;
  for (int k = 1; k <= max_revs && z < z_end; ++k) {
    AxialCouplingSample s;
    s.revolution = k;
    const double z0 = z;
    auto eval = [&](double d, DrillingForces& F) {
      const double fk = feed - (d - d_prev);
      F = fk > 0 ? drillingForcesAtDepth(model, data, fk, std::min(z0 + fk, z_end), thickness)
                 : DrillingForces{};
      return d - axial_compliance * F.thrust;
    };
    DrillingForces Flo, Fhi, Fm;
    double lo = d_prev;
    double hi = d_prev + feed;
    double glo = eval(lo, Flo);
    double ghi = eval(hi, Fhi);
    double d = lo;
    if (glo >= 0) {
      // The load fell below what the previous deflection holds (breakthrough): the tool springs
      // forward and the root lies in [0, δ_{k−1}] (g(0) = −c_z Fz ≤ 0).
      hi = lo;
      ghi = glo;
      lo = 0.0;
      glo = eval(lo, Flo);
    }
    int side = 0;
    for (int it = 1; it <= max_iterations; ++it) {
      d = ghi - glo > 0 ? (lo * ghi - hi * glo) / (ghi - glo) : 0.5 * (lo + hi);
      const double gm = eval(d, Fm);
      s.iterations = it;
      s.residual = std::abs(gm);
      if (s.residual <= tolerance || hi - lo <= tolerance) {
        s.converged = true;
        break;
      }
      if ((gm < 0) == (glo < 0)) {
        lo = d;
        glo = gm;
        if (side == -1) ghi *= 0.5;
        side = -1;
      } else {
        hi = d;
        ghi = gm;
        if (side == 1) glo *= 0.5;
        side = 1;
      }
    }
    s.deflection = d;
    s.feed = feed - (d - d_prev);
    z = std::min(z0 + std::max(0.0, s.feed), z_end);
    s.depth = z;
    s.forces = Fm;
    d_prev = d;
    out.push_back(s);
  }
  return out;
}

DrillingCalibration calibrateDrilling(const DrillingModel& model, double feed,
                                      double thrust_measured, double torque_measured) {
  DrillingCalibration c;
  const DrillingForces before = drillingForces(model, feed);
  c.thrust_model_before = before.thrust;
  c.torque_model_before = before.torque;
  c.coeff = model.coeff;
  c.coeff.tangential.k0 *= torque_measured / before.torque;
  c.coeff.axial.k0 *= thrust_measured / before.thrust;
  DrillingModel after = model;
  after.coeff = c.coeff;
  const DrillingForces fa = drillingForces(after, feed);
  c.thrust_model_after = fa.thrust;
  c.torque_model_after = fa.torque;
  return c;
}

}  // namespace roprec
