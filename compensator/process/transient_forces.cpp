#include "compensator/process/transient_forces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roprec::nc {
namespace {

constexpr double kHRef = 1e-3;  ///< Kienzle reference chip thickness (1 mm), as drilling_forces

/// c(q) = k0 (q/1 mm)^−m q, the feed factor of a lip (0 for q ≤ 0).
double feedFactor(const SpecificPressure& k, double q) {
  return q > 0 ? k.k0 * std::pow(q / kHRef, -k.m) * q : 0.0;
}

/// The eight sums of one node table (see the file comment).
DrillingForceTable::Sums nodeSums(const EdgeNodes& N) {
  DrillingForceTable::Sums S = DrillingForceTable::Sums::Zero();
  for (size_t i = 0; i < N.r.size(); ++i) {
    const double t = N.weight[i] * N.g_t[i] * N.sin_pow_t[i];
    const double a = N.weight[i] * N.g_a[i] * N.sin_pow_a[i];
    const double rad = a * N.cot_kappa[i];
    S += (DrillingForceTable::Sums() << t, a, rad, t * N.r[i], t * N.vx[i], t * N.vy[i],
          rad * N.erx[i], rad * N.ery[i])
             .finished();
  }
  return S;
}

/// Cubic Hermite basis on u ∈ [0, 1]: (h00, h10, h01, h11).
Eigen::Vector4d hermite(double u) {
  const double u2 = u * u;
  const double u3 = u2 * u;
  return {2 * u3 - 3 * u2 + 1, u3 - 2 * u2 + u, -2 * u3 + 3 * u2, u3 - u2};
}

/// Slopes (per unit x, grid x = 0 .. n) of the clamped cubic spline through v[0 .. n]: the end
/// slopes from the one-sided 4th-order differences, the interior from the C² conditions
/// m_{j−1} + 4 m_j + m_{j+1} = 3 (v_{j+1} − v_{j−1}) (Thomas algorithm). Needs n ≥ 4.
void splineSlopes(const DrillingForceTable::Sums* v, DrillingForceTable::Sums* m, int n) {
  using Sums = DrillingForceTable::Sums;
  m[0] = (-25 * v[0] + 48 * v[1] - 36 * v[2] + 16 * v[3] - 3 * v[4]) / 12.0;
  m[n] = (25 * v[n] - 48 * v[n - 1] + 36 * v[n - 2] - 16 * v[n - 3] + 3 * v[n - 4]) / 12.0;
  std::vector<double> c(static_cast<size_t>(n), 0.0);  // modified super-diagonal
  std::vector<Sums> d(static_cast<size_t>(n), Sums::Zero());
  for (int j = 1; j < n; ++j) {
    const auto k = static_cast<size_t>(j);
    Sums r = 3.0 * (v[j + 1] - v[j - 1]);
    if (j == 1) r -= m[0];
    if (j == n - 1) r -= m[n];
    const double denom = 4.0 - (j > 1 ? c[k - 1] : 0.0);
    c[k] = 1.0 / denom;
    if (j > 1) r -= d[k - 1];
    d[k] = r / denom;
  }
  for (int j = n - 1; j >= 1; --j) {
    const auto k = static_cast<size_t>(j);
    m[j] = d[k];
    if (j < n - 1) m[j] -= c[k] * m[j + 1];
  }
}

/// One lip's forces and in-plane force (lip-1 orientation).
struct Lip {
  LipForces F;
  Eigen::Vector2d inplane{Eigen::Vector2d::Zero()};
};

/// Adds sign × the corner element of width dr cut with chip factor q (drilling_forces.hpp: the
/// runout annulus [R − ρ, R + ρ] that lip 1 alone cuts at the full feed).
void addCornerStrip(const DrillingModel& m, double q, double dr, double sign, Lip& lip) {
  if (!(q > 0) || !(dr > 0)) return;
  const SpecificPressure& kt = m.coeff.tangential;
  const SpecificPressure& ka = m.coeff.axial;
  const double h = std::max(q * m.corner_sin_kappa, 0.0);
  const double Ft = kt.k0 * m.corner_g_t * std::pow(std::max(h, kt.h_min) / kHRef, -kt.m) * q * dr;
  const double Fa = ka.k0 * m.corner_g_a * std::pow(std::max(h, ka.h_min) / kHRef, -ka.m) * q * dr;
  const double Frad = Fa * m.corner_cot_kappa;
  lip.F.Ft += sign * Ft;
  lip.F.Fa += sign * Fa;
  lip.F.Frad += sign * Frad;
  lip.F.M += sign * Ft * m.geometry.radius();
  lip.inplane -= sign * (Ft * m.corner_v + Frad * m.corner_er);
}

}  // namespace

DrillingForceTable::DrillingForceTable(const DrillingModel& model, double thickness, int cells)
    : model_(model),
      data_(model_),
      thickness_(thickness),
      a_(model.geometry.chiselHalfLength()),
      R_(model.geometry.radius()) {
  if (cells < 4) throw std::invalid_argument("DrillingForceTable: cells must be >= 4");
  if (!(R_ - a_ > 1e-9)) return;  // no lip to tabulate: every call is exact
  for (const double s : model_.full.sin_kappa) min_sin_kappa_ = std::min(min_sin_kappa_, s);
  const double entry = (R_ - a_) / std::tan(model_.geometry.halfPoint());
  std::vector<double> b{0.0, entry};
  if (thickness_ > 0) b.insert(b.end(), {thickness_, thickness_ + entry});
  std::sort(b.begin(), b.end());
  const double step = entry / cells;
  for (size_t k = 0; k + 1 < b.size(); ++k) {
    const double len = b[k + 1] - b[k];
    if (!(len > 1e-12)) continue;
    const Engagement e = engagementAtDepth(model_.geometry, b[k] + 0.5 * len, thickness_);
    if (e.r_in <= a_ && e.r_out >= R_) continue;  // full engagement: exact and cheap
    Segment sg;
    sg.d0 = b[k];
    sg.cells = std::max(4, static_cast<int>(std::ceil(len / step - 1e-9)));
    sg.length = len;
    sg.first = values_.size();
    for (int j = 0; j <= sg.cells; ++j) {
      const double u = static_cast<double>(j) / sg.cells;
      values_.push_back(exactSums(sg.d0 + len * u * u));
    }
    slopes_.resize(values_.size());
    splineSlopes(&values_[sg.first], &slopes_[sg.first], sg.cells);
    segments_.push_back(sg);
  }
}

DrillingForceTable::Sums DrillingForceTable::exactSums(double depth) {
  const Engagement e = engagementAtDepth(model_.geometry, depth, thickness_);
  const double r_in = std::clamp(e.r_in, a_, R_);
  const double r_out = std::clamp(e.r_out, a_, R_);
  if (r_out - r_in <= 1e-12) return Sums::Zero();
  if (r_in <= a_ && r_out >= R_) return nodeSums(model_.full);
  (void)drillingForcesEngaged(model_, data_, 1e-4, r_in, r_out, e.chisel);
  for (const double s : data_.partial.sin_kappa) min_sin_kappa_ = std::min(min_sin_kappa_, s);
  return nodeSums(data_.partial);
}

bool DrillingForceTable::sums(double depth, Sums& S) const {
  for (const Segment& sg : segments_) {
    const double v = (depth - sg.d0) / sg.length;
    if (!(v >= 0.0) || !(v <= 1.0)) continue;
    const double x = sg.cells * std::sqrt(v);
    const int j = std::min(static_cast<int>(x), sg.cells - 1);
    const Eigen::Vector4d h = hermite(x - j);
    const size_t i = sg.first + static_cast<size_t>(j);
    S = h[0] * values_[i] + h[1] * slopes_[i] + h[2] * values_[i + 1] + h[3] * slopes_[i + 1];
    return true;
  }
  return false;
}

bool DrillingForceTable::separable(double q) const {
  const double floor = std::max(model_.coeff.tangential.h_min, model_.coeff.axial.h_min);
  return !(q > 0) || q * min_sin_kappa_ >= 1.01 * floor;  // 1 % margin: nodes between samples
}

DrillingForces DrillingForceTable::forces(double feed, double depth) {
  const DrillGeometry& g = model_.geometry;
  const Engagement e = engagementAtDepth(g, depth, thickness_);
  const double r_in = std::clamp(e.r_in, a_, R_);
  const double r_out = std::clamp(e.r_out, a_, R_);
  const double dz = 2.0 * g.runout / std::tan(g.halfPoint());
  const double q1 = std::min(feed, 0.5 * feed + dz);
  const double q2 = std::max(0.0, 0.5 * feed - dz);
  Sums S;
  if (r_out - r_in <= 1e-12 || !separable(q1) || !separable(q2) || !sums(depth, S)) {
    ++exact_calls_;
    return drillingForcesEngaged(model_, data_, feed, r_in, r_out, e.chisel);
  }
  ++table_calls_;
  const SpecificPressure& kt = model_.coeff.tangential;
  const SpecificPressure& ka = model_.coeff.axial;
  DrillingForces F;
  F.r_in = r_in;
  F.r_out = r_out;
  F.chisel_engaged = e.chisel;
  Lip lip[2];
  const double q[2] = {q1, q2};
  for (int k = 0; k < 2; ++k) {
    const double ct = feedFactor(kt, q[k]);
    const double ca = feedFactor(ka, q[k]);
    lip[k].F = LipForces{ct * S[0], ca * S[1], ca * S[2], ct * S[3]};
    lip[k].inplane = -(ct * S.segment<2>(4) + ca * S.segment<2>(6));
  }
  if (r_out >= R_ && g.runout > 0) {  // corner engaged (breakthrough): the runout annulus
    addCornerStrip(model_, feed, 2.0 * g.runout, +1.0, lip[0]);
    addCornerStrip(model_, q1, g.runout, -1.0, lip[0]);
    addCornerStrip(model_, q2, g.runout, -1.0, lip[1]);
  }
  F.lip[0] = lip[0].F;
  F.lip[1] = lip[1].F;
  F.thrust_lips = F.lip[0].Fa + F.lip[1].Fa;
  F.tangential = F.lip[0].Ft + F.lip[1].Ft;
  const double M_lips = F.lip[0].M + F.lip[1].M;
  if (e.chisel) {
    const ChiselModel& ch = model_.coeff.chisel;
    F.thrust_chisel = ch.kind == ChiselModelKind::kRatio ? ch.thrust_ratio * F.thrust_lips
                                                         : ch.pressure_ratio * ka.k0 * a_ * feed;
    F.torque_chisel = ch.torque_ratio * M_lips;
  }
  F.thrust = F.thrust_lips + F.thrust_chisel;
  F.torque = M_lips + F.torque_chisel;
  F.residual_xy = lip[0].inplane - lip[1].inplane;  // lip 2 at 180°
  F.residual = F.residual_xy.norm();
  return F;
}

}  // namespace roprec::nc
