#include "compensator/process/milling_stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

namespace roprec {

namespace {

using cd = std::complex<double>;
using Eigs = std::array<cd, 2>;

constexpr double kH0 = 1e-3;      // Kienzle reference chip thickness [m]
constexpr int kBandPoints = 97;   // grid points across each mode's band
constexpr double kBandLo = -6.0;  // band: ω_r (1 + ζ_r x), x in [kBandLo, kBandHi]
constexpr double kBandHi = 18.0;
constexpr double kStepPerTooth = 1.0 / 16;  // largest grid step, in tooth frequencies

double toothOmega(const StabilityCut& cut, double rpm) { return 2 * kPi * cut.teeth * rpm / 60.0; }

Eigs eigenvaluesAt(const ModalModel& dyn, const Eigen::Matrix2d& alpha, double omega) {
  const Mat3c H = receptance(dyn, omega);
  const Eigen::Matrix2cd Phi0 = alpha.cast<cd>() * H.topLeftCorner<2, 2>();
  const Eigen::ComplexEigenSolver<Eigen::Matrix2cd> es(Phi0, false);
  return {es.eigenvalues()[0], es.eigenvalues()[1]};
}

ChatterRoot rootOf(const cd& lambda, const StabilityCut& cut) {
  ChatterRoot r;
  if (std::abs(lambda) == 0) return r;
  const cd L = -1.0 / lambda;
  if (!(L.real() < 0)) return r;
  const double kappa = L.imag() / L.real();
  r.a_lim = -2 * kPi * L.real() * (1 + kappa * kappa) / (cut.teeth * cut.Kt);
  r.epsilon = kPi - 2 * std::atan(kappa);
  return r;
}

/// The chatter-frequency grid for speeds ≥ rpm_min [rad/s], ascending.
std::vector<double> frequencyGrid(const ModalModel& dyn, const StabilityCut& cut, double rpm_min) {
  std::vector<double> g;
  double w_lo = 1e300;
  double w_hi = 0;
  for (const VibrationMode& m : dyn.modes) {
    if (!(m.omega > 0) || m.tcp.head<2>().squaredNorm() == 0) continue;
    w_lo = std::min(w_lo, m.omega);
    w_hi = std::max(w_hi, m.omega);
    const double z = std::max(m.zeta, 1e-3);
    for (int i = 0; i < kBandPoints; ++i) {
      const double x = kBandLo + (kBandHi - kBandLo) * i / (kBandPoints - 1);
      const double w = m.omega * (1 + z * x);
      if (w > 0) g.push_back(w);
    }
  }
  if (g.empty()) return g;
  w_lo *= 0.25;
  w_hi *= 3.0;
  g.push_back(w_lo);
  g.push_back(w_hi);
  std::sort(g.begin(), g.end());
  g.erase(std::remove_if(g.begin(), g.end(), [&](double w) { return w < w_lo || w > w_hi; }),
          g.end());
  const double step = kStepPerTooth * toothOmega(cut, rpm_min);
  std::vector<double> out;
  for (size_t i = 0; i < g.size(); ++i) {
    if (i > 0) {
      const double gap = g[i] - g[i - 1];
      if (gap <= 0) continue;
      const int sub = static_cast<int>(std::ceil(gap / step));
      for (int s = 1; s < sub; ++s) out.push_back(g[i - 1] + gap * s / sub);
    }
    out.push_back(g[i]);
  }
  return out;
}

/// Both branches on the grid, followed by nearest match of the eigenvalues.
struct RootTable {
  std::vector<double> omega;
  std::vector<std::array<ChatterRoot, 2>> roots;
};

/// The tracked roots of the raw eigenvalue pairs `eig` at the ascending `omega`.
RootTable track(const std::vector<double>& omega, const std::vector<Eigs>& eig,
                const StabilityCut& cut) {
  RootTable t;
  t.omega = omega;
  Eigs prev{};
  for (size_t i = 0; i < omega.size(); ++i) {
    Eigs e = eig[i];
    if (i > 0 && std::abs(e[0] - prev[0]) + std::abs(e[1] - prev[1]) >
                     std::abs(e[0] - prev[1]) + std::abs(e[1] - prev[0])) {
      std::swap(e[0], e[1]);
    }
    prev = e;
    t.roots.push_back({rootOf(e[0], cut), rootOf(e[1], cut)});
  }
  return t;
}

bool valid(const ChatterRoot& r) { return r.a_lim > 0 && std::isfinite(r.a_lim); }

/// Whether the segment [i−1, i] needs a midpoint: on some branch the chatter condition starts or
/// ends inside it (a_lim → ∞ there), a_lim changes by more than kMaxRelativeChange, or the lobe
/// number at period T changes by more than kMaxLobeChange.
bool needsMidpoint(const RootTable& t, size_t i, double T) {
  constexpr double kMaxRelativeChange = 0.01;
  constexpr double kMaxLobeChange = 0.2;
  if (t.omega[i] - t.omega[i - 1] < 1e-9 * t.omega[i]) return false;
  for (size_t b = 0; b < 2; ++b) {
    const ChatterRoot& r0 = t.roots[i - 1][b];
    const ChatterRoot& r1 = t.roots[i][b];
    if (valid(r0) != valid(r1)) return true;
    if (!valid(r0)) continue;
    if (std::abs(r1.a_lim - r0.a_lim) > kMaxRelativeChange * std::min(r0.a_lim, r1.a_lim))
      return true;
    const double dk = ((t.omega[i] - t.omega[i - 1]) * T - (r1.epsilon - r0.epsilon)) / (2 * kPi);
    if (std::abs(dk) > kMaxLobeChange) return true;
  }
  return false;
}

/// The grid refined (at most kPasses halvings of a segment) until needsMidpoint holds nowhere.
RootTable rootTable(const ModalModel& dyn, const StabilityCut& cut, double rpm_min) {
  constexpr int kPasses = 14;
  const Eigen::Matrix2d alpha = directionalFactors(cut.arc, cut.Kr);
  const double T = 60.0 / (cut.teeth * rpm_min);
  std::vector<double> omega = frequencyGrid(dyn, cut, rpm_min);
  std::vector<Eigs> eig;
  for (double w : omega) eig.push_back(eigenvaluesAt(dyn, alpha, w));
  RootTable t = track(omega, eig, cut);
  for (int pass = 0; pass < kPasses; ++pass) {
    std::vector<double> w2;
    std::vector<Eigs> e2;
    bool added = false;
    for (size_t i = 0; i < omega.size(); ++i) {
      if (i > 0 && needsMidpoint(t, i, T)) {
        const double mid = 0.5 * (omega[i - 1] + omega[i]);
        w2.push_back(mid);
        e2.push_back(eigenvaluesAt(dyn, alpha, mid));
        added = true;
      }
      w2.push_back(omega[i]);
      e2.push_back(eig[i]);
    }
    if (!added) break;
    omega.swap(w2);
    eig.swap(e2);
    t = track(omega, eig, cut);
  }
  return t;
}

StabilityLimit limitFromTable(const RootTable& t, const StabilityCut& cut, double rpm) {
  StabilityLimit best;
  const double T = 60.0 / (cut.teeth * rpm);
  for (int b = 0; b < 2; ++b) {
    for (size_t i = 1; i < t.omega.size(); ++i) {
      const ChatterRoot& r0 = t.roots[i - 1][static_cast<size_t>(b)];
      const ChatterRoot& r1 = t.roots[i][static_cast<size_t>(b)];
      if (!(r0.a_lim > 0) || !(r1.a_lim > 0) || !std::isfinite(r0.a_lim) ||
          !std::isfinite(r1.a_lim))
        continue;
      const double k0 = (t.omega[i - 1] * T - r0.epsilon) / (2 * kPi);
      const double k1 = (t.omega[i] * T - r1.epsilon) / (2 * kPi);
      const double lo = std::min(k0, k1);
      const double hi = std::max(k0, k1);
      for (double K = std::max(0.0, std::ceil(lo)); K <= hi; K += 1.0) {
        if (k1 == k0) continue;
        const double s = (K - k0) / (k1 - k0);
        const double a = r0.a_lim + s * (r1.a_lim - r0.a_lim);
        if (!best.bounded || a < best.ap_lim) {
          best.bounded = true;
          best.ap_lim = a;
          best.chatter_hz = (t.omega[i - 1] + s * (t.omega[i] - t.omega[i - 1])) / (2 * kPi);
          best.lobe = static_cast<int>(K);
        }
      }
    }
  }
  return best;
}

}  // namespace

StabilityCut stabilityCutOf(const MillingModel& m) {
  StabilityCut c;
  c.teeth = m.tool.teeth;
  c.arc = immersionAngles(m.tool.diameter, m.cut.ae, m.cut.mode);
  const double hm = std::max(meanChipThickness(m.cut.fz, c.arc), m.coeff.h_min);
  c.Kt = m.coeff.kc11 * (1 - m.coeff.mc) * std::pow(hm / kH0, -m.coeff.mc);
  c.Kr = m.coeff.radial_ratio;
  return c;
}

Eigen::Matrix2d directionalFactors(const ImmersionAngles& arc, double Kr) {
  auto at = [Kr](double p) {
    Eigen::Matrix2d a;
    const double s2 = std::sin(2 * p);
    const double c2 = std::cos(2 * p);
    a(0, 0) = 0.5 * (c2 - 2 * Kr * p + Kr * s2);
    a(0, 1) = 0.5 * (-s2 - 2 * p + Kr * c2);
    a(1, 0) = 0.5 * (-s2 + 2 * p + Kr * c2);
    a(1, 1) = 0.5 * (-c2 - 2 * Kr * p - Kr * s2);
    return a;
  };
  return at(arc.exit) - at(arc.start);
}

std::array<ChatterRoot, 2> chatterRoots(const ModalModel& dyn, const StabilityCut& cut,
                                        double omega_c) {
  const Eigs e = eigenvaluesAt(dyn, directionalFactors(cut.arc, cut.Kr), omega_c);
  return {rootOf(e[0], cut), rootOf(e[1], cut)};
}

StabilityLimit limitingDepth(const ModalModel& dyn, const StabilityCut& cut, double spindle_rpm) {
  return limitFromTable(rootTable(dyn, cut, spindle_rpm), cut, spindle_rpm);
}

std::vector<LobeSample> stabilityLobes(const ModalModel& dyn, const StabilityCut& cut,
                                       double rpm_lo, double rpm_hi, int steps) {
  const RootTable t = rootTable(dyn, cut, rpm_lo);
  std::vector<LobeSample> out;
  for (int i = 0; i < steps; ++i) {
    const double rpm = steps > 1 ? rpm_lo + (rpm_hi - rpm_lo) * i / (steps - 1) : rpm_lo;
    out.push_back({rpm, limitFromTable(t, cut, rpm)});
  }
  return out;
}

}  // namespace roprec
