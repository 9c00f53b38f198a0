#include "compensator/process/milling_mode_coupling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace roprec {
namespace {

/// Two modes of mass m in the XY plane along e1 = (cos θ, sin θ), e2 = (−sin θ, cos θ) with
/// stiffnesses k1, k2 and damping ζ (mass-normalised TCP vectors e_i/√m).
ModalModel twoModes(double m, double k1, double k2, double theta, double zeta) {
  ModalModel d;
  const Vec3 e1(std::cos(theta), std::sin(theta), 0);
  const Vec3 e2(-std::sin(theta), std::cos(theta), 0);
  for (const auto& [k, e] : {std::pair{k1, e1}, std::pair{k2, e2}}) {
    VibrationMode v;
    v.omega = std::sqrt(k / m);
    v.zeta = zeta;
    v.tcp = e / std::sqrt(m);
    d.modes.push_back(v);
  }
  return d;
}

/// The undamped 2-DOF closed form of the file comment: the flutter interval (k_lo, k_hi) of k_p
/// for G = −k_p f nᵀ (f, n given in the principal frame).
struct FlutterInterval {
  double lo, hi;
};
FlutterInterval closedFormInterval(double k1, double k2, const Eigen::Vector2d& f,
                                   const Eigen::Vector2d& n) {
  const double fn = f.dot(n);
  const double a = f.x() * n.x() - f.y() * n.y();
  const double dk = k1 - k2;
  const double root = std::sqrt(a * a - fn * fn);
  const double r1 = dk * (-a - root) / (fn * fn);
  const double r2 = dk * (-a + root) / (fn * fn);
  return {std::min(r1, r2), std::max(r1, r2)};
}

// The linearised check against the undamped 2-DOF closed form (ζ = 1e-5): principal stiffnesses
// 1.0 and 1.2 N/µm turned 30° from the feed, a process stiffness k_p f nᵀ with f and n on
// opposite sides of a principal axis. Unstable just inside the closed-form interval (2 % in),
// stable just outside it; the limit found by the depth scan is the interval's lower end within
// 0.5 %, and the flutter frequency there is √(tr/2m)/2π of the closed form within 0.5 %.
TEST(MillingModeCoupling, TwoModesMatchTheClosedFormFlutterInterval) {
  const double m = 40.0, k1 = 1.0e6, k2 = 1.2e6, theta = 30 * kDeg;
  const ModalModel dyn = twoModes(m, k1, k2, theta, 1e-5);
  // principal-frame directions: f at −60°, n at 10° (f1 f2 n1 n2 < 0)
  const Eigen::Vector2d fp(std::cos(-60 * kDeg), std::sin(-60 * kDeg));
  const Eigen::Vector2d np(std::cos(10 * kDeg), std::sin(10 * kDeg));
  ASSERT_LT(fp.x() * fp.y() * np.x() * np.y(), 0.0);
  const FlutterInterval iv = closedFormInterval(k1, k2, fp, np);
  ASSERT_GT(iv.lo, 0.0);
  const auto toMilling = [&](const Eigen::Vector2d& v) {
    return Vec3(v.x() * std::cos(theta) - v.y() * std::sin(theta),
                v.x() * std::sin(theta) + v.y() * std::cos(theta), 0.0);
  };
  const Vec3 f = toMilling(fp);
  const Vec3 n = toMilling(np);
  const auto G = [&](double kp) { return Mat3(-kp * f * n.transpose()); };
  EXPECT_TRUE(modeCouplingAt(dyn, G(0.98 * iv.lo)).stable);
  EXPECT_FALSE(modeCouplingAt(dyn, G(1.02 * iv.lo)).stable);
  EXPECT_TRUE(modeCouplingAt(dyn, G(1.02 * iv.lo)).flutter);
  EXPECT_FALSE(modeCouplingAt(dyn, G(0.98 * iv.hi)).stable);
  EXPECT_TRUE(modeCouplingAt(dyn, G(1.02 * iv.hi)).stable);
  // the same through the depth scan: G at depth s·ap is s·G_ae (no ap term here)
  ProcessGradient g;
  const double kp_at_cut = 0.25 * iv.lo;
  g.per_depth = G(kp_at_cut);
  const ModeCouplingLimit lim = modeCouplingLimit(dyn, g, 5e-3);
  ASSERT_TRUE(lim.bounded);
  EXPECT_TRUE(lim.at_cut.stable);
  EXPECT_NEAR(lim.margin, iv.lo / kp_at_cut, 0.005 * iv.lo / kp_at_cut);
  EXPECT_NEAR(lim.ap_lim, 5e-3 * lim.margin, 1e-12);
  EXPECT_TRUE(lim.flutter);
  // at coalescence the double root of K + k_p f nᵀ is tr/2
  const double tr = k1 + k2 + iv.lo * fp.dot(np);
  EXPECT_NEAR(lim.frequency_hz, std::sqrt(tr / 2 / m) / (2 * kPi),
              0.005 * std::sqrt(tr / 2 / m) / (2 * kPi));
  // equal stiffnesses never flutter (D = (f·n)² k_p² ≥ 0)
  const ModalModel same = twoModes(m, k1, k1, theta, 1e-5);
  for (double kp : {0.1, 0.5, 1.0, 2.0}) EXPECT_TRUE(modeCouplingAt(same, G(kp * 1e5)).stable);
}

/// Independent reference: the revolution-mean Kienzle force of an up-milling cut (D 10, 3 teeth,
/// kc1.1 800, mc 0.25, cr 0.35, no runout) by midpoint quadrature at (fz, ae, ap).
Vec3 meanForce(double fz, double ae, double ap) {
  const double D = 10e-3, kc = 800e6, mc = 0.25, cr = 0.35;
  ae = std::clamp(ae, 0.0, D);
  const double b = std::acos(1.0 - 2.0 * ae / D);
  const int n = 400;
  Vec3 F = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const double phi = b * (i + 0.5) / n;
    const double h = fz * std::sin(phi);
    const double Ft = kc * ap * 1e-3 * std::pow(h / 1e-3, 1.0 - mc) * b / n;
    F += Vec3(-Ft * std::cos(phi) - cr * Ft * std::sin(phi),
              Ft * std::sin(phi) - cr * Ft * std::cos(phi), 0.0);
  }
  return F * (3.0 / (2.0 * kPi));
}

/// The real cut of the time-domain and gradient checks: up-milling ap 5, ae 2, fz 0.1 mm.
MillingCut upMillingCut() {
  MillingCut c;
  c.ap = 5e-3;
  c.ae = 2e-3;
  c.fz = 0.1e-3;
  return c;
}

/// kc1.1 800 N/mm², mc 0.25, cr 0.35 (the reference's), and the axial ratio when given.
MillingCoefficients kienzle(std::optional<double> axial_ratio) {
  MillingCoefficients k;
  k.kc11 = 800e6;
  k.mc = 0.25;
  k.radial_ratio = 0.35;
  if (axial_ratio) k.axial_ratio = *axial_ratio;
  return k;
}

/// The default tool (D 10, 3 teeth, no runout) on that cut, 360 edge-angle steps.
MillingModel upMillingModel(const MillingCut& c, const MillingCoefficients& k) {
  return makeMillingModel(MillingTool{}, c, k, 360, 20);
}

/// The two modes under the cut's quasi-static mean force (ae = ae0 + y), marched by RK4 from the
/// static equilibrium plus 1 µm: the ratio of the vibration's amplitude over the last 5 periods of
/// the slower mode to that over the first 5.
double amplitudeGrowth(const ModalModel& dyn, double ap) {
  const double fz = 0.1e-3, ae0 = 2e-3;
  Eigen::Matrix2d U;  // columns: the modes' XY vectors
  for (int r = 0; r < 2; ++r) U.col(r) = dyn.modes[static_cast<size_t>(r)].tcp.head<2>();
  const auto force = [&](const Eigen::Vector2d& x) {
    return Eigen::Vector2d(meanForce(fz, ae0 + x.y(), ap).head<2>());
  };
  // static equilibrium: x = U Ω⁻² Uᵀ F(x) by fixed-point iteration (stiff structure: contracts)
  Eigen::Matrix2d W = Eigen::Matrix2d::Zero();
  for (int r = 0; r < 2; ++r) W(r, r) = std::pow(dyn.modes[static_cast<size_t>(r)].omega, -2);
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int i = 0; i < 200; ++i) x = U * W * U.transpose() * force(x);
  Eigen::Vector4d s;  // q, q̇
  s.head<2>() = U.inverse() * (x + Eigen::Vector2d(0.7e-6, 0.7e-6));
  s.tail<2>().setZero();
  const auto rhs = [&](const Eigen::Vector4d& y) {
    const Eigen::Vector2d F = U.transpose() * force(U * y.head<2>());
    Eigen::Vector4d d;
    for (int r = 0; r < 2; ++r) {
      const VibrationMode& mo = dyn.modes[static_cast<size_t>(r)];
      d(r) = y(2 + r);
      d(2 + r) = F(r) - 2 * mo.zeta * mo.omega * y(2 + r) - mo.omega * mo.omega * y(r);
    }
    return d;
  };
  const double period = 2 * kPi / dyn.modes.front().omega;
  const double dt = period / 200;
  const int steps = static_cast<int>(60 * period / dt);
  const int window = static_cast<int>(5 * period / dt);
  double first = 0, last = 0;
  for (int i = 0; i < steps; ++i) {
    const double a = (U * s.head<2>() - x).norm();
    if (i < window) first = std::max(first, a);
    if (i >= steps - window) last = std::max(last, a);
    const Eigen::Vector4d k1 = rhs(s), k2 = rhs(s + 0.5 * dt * k1), k3 = rhs(s + 0.5 * dt * k2),
                          k4 = rhs(s + dt * k3);
    s += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return last / first;
}

// The depth limit of a real cut against a time-domain march of the two modes under the nonlinear
// mean force (independent quadrature, the engagement following the displacement): up-milling
// ae 2, fz 0.1 on modes of 0.60 and 0.66 N/µm turned 30° from the feed (ζ 0.005). Below the
// limit (0.8 ×) the perturbation decays over 60 periods; above it (1.25 ×) it grows. Measured:
// limit 2.26 mm, flutter at 22.9 Hz.
TEST(MillingModeCoupling, DepthLimitSeparatesDecayFromGrowthInTimeDomain) {
  const ModalModel dyn = twoModes(30.0, 0.60e6, 0.66e6, 30 * kDeg, 0.005);
  const MillingCut c = upMillingCut();
  const MillingModel m = upMillingModel(c, kienzle(std::nullopt));
  const ModeCouplingLimit lim = modeCouplingLimit(dyn, processGradient(m, c.fz, c.ae, c.ap), c.ap);
  ASSERT_TRUE(lim.bounded);
  EXPECT_TRUE(lim.flutter);
  EXPECT_GT(lim.ap_lim, 1e-3);
  EXPECT_LT(lim.ap_lim, 50e-3);
  const double below = amplitudeGrowth(dyn, 0.8 * lim.ap_lim);
  const double above = amplitudeGrowth(dyn, 1.25 * lim.ap_lim);
  EXPECT_LT(below, 0.7) << below;
  EXPECT_GT(above, 1.5) << above;
}

// The process stiffness against finite differences of the independent quadrature: ∂F̄/∂ae along
// the wall normal (+Y, up-milling) within 0.3 %, and the ap column −F̄/ap.
TEST(MillingModeCoupling, ProcessGradientIsTheMeanForceDerivative) {
  const MillingCut c = upMillingCut();
  const MillingModel m = upMillingModel(c, kienzle(0.0));
  const ProcessGradient g = processGradient(m, c.fz, c.ae, 4e-3);
  const Vec3 ref = (meanForce(c.fz, c.ae + 2e-6, 4e-3) - meanForce(c.fz, c.ae - 2e-6, 4e-3)) / 4e-6;
  EXPECT_LT((g.per_depth.col(1) - ref).norm(), 0.003 * ref.norm());
  EXPECT_LT(g.per_depth.col(0).norm() + g.per_depth.col(2).norm(), 1e-9);
  const Vec3 F = meanForce(c.fz, c.ae, 4e-3);
  EXPECT_LT((g.fixed.col(2) + F / 4e-3).norm(), 0.003 * F.norm() / 4e-3);
}

}  // namespace
}  // namespace roprec
