// Zero-order chatter stability against closed forms and a time-domain simulation:
//  - one mode in Y: the limiting depth at a speed equals the textbook 1-DOF lobe
//    a = −1/(2 K Re G), K = Nt Kt |α_yy| / 4π, ε = 3π + 2 arg G, solved for the speed by bisection
//    (0.5 %); its minimum over speeds equals a_min = 2 k ζ (1 + ζ)/K (0.5 %);
//  - two uncoupled modes in X and Y: the eigenvalues of Altintas' closed-form quadratic
//    a0 Λ² + a1 Λ + 1 = 0 give the same limiting depths (0.5 %);
//  - the regenerative delay equation of one mode, integrated in time (RK4 with the delayed state
//    interpolated from the history), decays at 0.85 a_lim and grows at 1.15 a_lim.
#include "compensator/process/milling_stability.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <functional>
#include <limits>

namespace roprec {
namespace {

using cd = std::complex<double>;

struct OneMode {
  double m{2.0}, k{2e7}, zeta{0.03};
  [[nodiscard]] double wn() const { return std::sqrt(k / m); }
  [[nodiscard]] cd G(double w) const {
    return 1.0 / cd(k - m * w * w, 2 * zeta * std::sqrt(k * m) * w);
  }
};

VibrationMode modeAlong(const OneMode& o, int axis) {
  VibrationMode v;
  v.omega = o.wn();
  v.zeta = o.zeta;
  v.tcp = Vec3::Unit(axis) / std::sqrt(o.m);
  return v;
}

StabilityCut slotCut() {
  StabilityCut c;
  c.teeth = 4;
  c.Kt = 700e6;
  c.Kr = 0.3;
  c.arc = {0.0, kPi};
  return c;
}

/// Smallest a over lobes k of a closed-form branch a(ω), ε(ω) at `rpm`: bisection on
/// g(ω) = ω T − ε(ω) − 2kπ over the ω where a(ω) > 0 (a fine scan brackets the roots).
double closedFormLimit(const std::function<std::pair<double, double>(double)>& a_eps, double rpm,
                       int teeth, double w_lo, double w_hi) {
  const double T = 60.0 / (teeth * rpm);
  double best = std::numeric_limits<double>::infinity();
  const int n = 200000;
  auto g = [&](double w, double K) { return w * T - a_eps(w).second - 2 * kPi * K; };
  for (int i = 0; i < n; ++i) {
    const double w0 = w_lo + (w_hi - w_lo) * i / n;
    const double w1 = w_lo + (w_hi - w_lo) * (i + 1) / n;
    if (!(a_eps(w0).first > 0) || !(a_eps(w1).first > 0)) continue;
    const double k0 = (w0 * T - a_eps(w0).second) / (2 * kPi);
    const double k1 = (w1 * T - a_eps(w1).second) / (2 * kPi);
    for (double K = std::max(0.0, std::ceil(std::min(k0, k1))); K <= std::max(k0, k1); K += 1) {
      double lo = w0;
      double hi = w1;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        if ((g(lo, K) <= 0) == (g(mid, K) <= 0)) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      best = std::min(best, a_eps(0.5 * (lo + hi)).first);
    }
  }
  return best;
}

TEST(MillingStability, OneModeLimitMatchesTheTextbookLobes) {
  const OneMode o;
  ModalModel dyn;
  dyn.modes.push_back(modeAlong(o, 1));
  const StabilityCut cut = slotCut();
  const double alpha_yy = directionalFactors(cut.arc, cut.Kr)(1, 1);
  EXPECT_NEAR(alpha_yy, -cut.Kr * kPi, 1e-12);  // slot: α_yy = −Kr π
  const double K = cut.teeth * cut.Kt * std::abs(alpha_yy) / (4 * kPi);
  const auto tlusty = [&](double w) {
    const cd G = o.G(w);
    const double a = G.real() < 0 ? -1.0 / (2 * K * G.real()) : -1.0;
    return std::make_pair(a, 3 * kPi + 2 * std::arg(G));
  };
  for (double rpm : {3000.0, 5200.0, 8000.0, 11500.0, 16000.0}) {
    const StabilityLimit lim = limitingDepth(dyn, cut, rpm);
    ASSERT_TRUE(lim.bounded) << rpm;
    const double ref = closedFormLimit(tlusty, rpm, cut.teeth, 0.5 * o.wn(), 2.0 * o.wn());
    EXPECT_NEAR(lim.ap_lim, ref, 0.005 * ref) << rpm;
  }
  // absolute limit: min over speeds
  const std::vector<LobeSample> lobes = stabilityLobes(dyn, cut, 2000, 20000, 1500);
  double amin = 1e300;
  for (const LobeSample& s : lobes)
    if (s.limit.bounded) amin = std::min(amin, s.limit.ap_lim);
  const double a_min_ref = 2 * o.k * o.zeta * (1 + o.zeta) / K;
  EXPECT_NEAR(amin, a_min_ref, 0.005 * a_min_ref);
}

TEST(MillingStability, TwoModesMatchAltintasClosedFormQuadratic) {
  const OneMode ox{1.5, 1.2e7, 0.025};
  const OneMode oy{2.5, 2.6e7, 0.04};
  ModalModel dyn;
  dyn.modes.push_back(modeAlong(ox, 0));
  dyn.modes.push_back(modeAlong(oy, 1));
  StabilityCut cut = slotCut();
  cut.arc = immersionAngles(10e-3, 5e-3, MillingMode::kDown);  // half immersion, down-milling
  // the book's α for this arc, from its integrand written out
  const double p0 = cut.arc.start;
  const double p1 = cut.arc.exit;
  const double Kr = cut.Kr;
  const double axx = 0.5 * ((std::cos(2 * p1) - std::cos(2 * p0)) - 2 * Kr * (p1 - p0) +
                            Kr * (std::sin(2 * p1) - std::sin(2 * p0)));
  const double axy = 0.5 * (-(std::sin(2 * p1) - std::sin(2 * p0)) - 2 * (p1 - p0) +
                            Kr * (std::cos(2 * p1) - std::cos(2 * p0)));
  const double ayx = 0.5 * (-(std::sin(2 * p1) - std::sin(2 * p0)) + 2 * (p1 - p0) +
                            Kr * (std::cos(2 * p1) - std::cos(2 * p0)));
  const double ayy = 0.5 * (-(std::cos(2 * p1) - std::cos(2 * p0)) - 2 * Kr * (p1 - p0) -
                            Kr * (std::sin(2 * p1) - std::sin(2 * p0)));
  const Eigen::Matrix2d alpha = directionalFactors(cut.arc, cut.Kr);
  EXPECT_NEAR(alpha(0, 0), axx, 1e-12);
  EXPECT_NEAR(alpha(0, 1), axy, 1e-12);
  EXPECT_NEAR(alpha(1, 0), ayx, 1e-12);
  EXPECT_NEAR(alpha(1, 1), ayy, 1e-12);
  // Altintas: a0 = Gxx Gyy (αxx αyy − αxy αyx), a1 = αxx Gxx + αyy Gyy,
  // Λ = −(a1 ± sqrt(a1² − 4 a0)) / (2 a0)
  auto branch = [&](int sign) {
    return [&, sign](double w) {
      const cd gx = ox.G(w);
      const cd gy = oy.G(w);
      const cd a0 = gx * gy * (axx * ayy - axy * ayx);
      const cd a1 = axx * gx + ayy * gy;
      const cd L = -(a1 + double(sign) * std::sqrt(a1 * a1 - 4.0 * a0)) / (2.0 * a0);
      if (!(L.real() < 0)) return std::make_pair(-1.0, 0.0);
      const double kappa = L.imag() / L.real();
      return std::make_pair(-2 * kPi * L.real() * (1 + kappa * kappa) / (cut.teeth * cut.Kt),
                            kPi - 2 * std::atan(kappa));
    };
  };
  // at every frequency both branches' depths are found among chatterRoots
  for (double f = 300; f < 800; f += 7.3) {
    const double w = 2 * kPi * f;
    const auto roots = chatterRoots(dyn, cut, w);
    for (int sign : {-1, 1}) {
      const auto ref = branch(sign)(w);
      if (!(ref.first > 0)) continue;
      const double d =
          std::min(std::abs(roots[0].a_lim - ref.first), std::abs(roots[1].a_lim - ref.first));
      EXPECT_LE(d, 1e-9 * ref.first) << f;
    }
  }
  const double wlo = 0.5 * std::min(ox.wn(), oy.wn());
  const double whi = 2.0 * std::max(ox.wn(), oy.wn());
  for (double rpm : {4000.0, 7000.0, 9500.0, 14000.0}) {
    const StabilityLimit lim = limitingDepth(dyn, cut, rpm);
    ASSERT_TRUE(lim.bounded) << rpm;
    // the closed-form branches can swap where the square root crosses its branch cut: take
    // the smaller of the two branch limits, each over a scan that skips the swap points
    const double ref = std::min(closedFormLimit(branch(1), rpm, cut.teeth, wlo, whi),
                                closedFormLimit(branch(-1), rpm, cut.teeth, wlo, whi));
    EXPECT_NEAR(lim.ap_lim, ref, 0.005 * ref) << rpm;
  }
}

/// m ÿ + c ẏ + k y = (Nt a Kt α_yy / 4π) (y(t) − y(t − T)); returns the ratio of the vibration
/// amplitude over the last 20 delays to the one over delays 10–30.
double regenerativeGrowth(const OneMode& o, const StabilityCut& cut, double a, double rpm) {
  const double alpha_yy = directionalFactors(cut.arc, cut.Kr)(1, 1);
  const double kc = cut.teeth * a * cut.Kt * alpha_yy / (4 * kPi);  // < 0
  const double c = 2 * o.zeta * std::sqrt(o.k * o.m);
  const double T = 60.0 / (cut.teeth * rpm);
  const int per = 400;  // steps per delay
  const double h = T / per;
  const int delays = 400;
  std::vector<double> y(static_cast<size_t>(per * delays + 1), 0.0);
  std::vector<double> v(y.size(), 0.0);
  y[0] = 1e-6;
  // history before t = 0: at rest at y = 0 (the disturbance starts at t = 0)
  auto delayed = [&](size_t i, double frac) {
    if (i < static_cast<size_t>(per)) return 0.0;
    const size_t j = i - static_cast<size_t>(per);
    return y[j] + frac * (y[j + 1] - y[j]);
  };
  auto acc = [&](double yy, double vv, double yd) {
    return (kc * (yy - yd) - c * vv - o.k * yy) / o.m;
  };
  for (size_t i = 0; i + 1 < y.size(); ++i) {
    const double yd0 = delayed(i, 0.0);
    const double ydh = delayed(i, 0.5);
    const double yd1 = delayed(i, 1.0);
    const double k1y = v[i];
    const double k1v = acc(y[i], v[i], yd0);
    const double k2y = v[i] + 0.5 * h * k1v;
    const double k2v = acc(y[i] + 0.5 * h * k1y, k2y, ydh);
    const double k3y = v[i] + 0.5 * h * k2v;
    const double k3v = acc(y[i] + 0.5 * h * k2y, k3y, ydh);
    const double k4y = v[i] + h * k3v;
    const double k4v = acc(y[i] + h * k3y, k4y, yd1);
    y[i + 1] = y[i] + h / 6 * (k1y + 2 * k2y + 2 * k3y + k4y);
    v[i + 1] = v[i] + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  auto amplitude = [&](int from, int to) {
    double mx = 0;
    for (size_t i = static_cast<size_t>(from * per); i < static_cast<size_t>(to * per); ++i)
      mx = std::max(mx, std::abs(y[i]));
    return mx;
  };
  return amplitude(delays - 20, delays) / amplitude(10, 30);
}

TEST(MillingStability, TimeDomainRegenerationGrowsAboveTheLobeAndDecaysBelow) {
  const OneMode o{2.0, 2e7, 0.03};
  ModalModel dyn;
  dyn.modes.push_back(modeAlong(o, 1));
  const StabilityCut cut = slotCut();
  for (double rpm : {6000.0, 9000.0}) {
    const StabilityLimit lim = limitingDepth(dyn, cut, rpm);
    ASSERT_TRUE(lim.bounded);
    EXPECT_LT(regenerativeGrowth(o, cut, 0.85 * lim.ap_lim, rpm), 0.5) << rpm;
    EXPECT_GT(regenerativeGrowth(o, cut, 1.15 * lim.ap_lim, rpm), 2.0) << rpm;
  }
}

}  // namespace
}  // namespace roprec
