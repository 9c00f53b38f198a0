#include "compensator/process/milling_mode_coupling.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

namespace roprec {

namespace {

/// The wall's normal into the material (milling.hpp): +Y up, −Y down, none for a slot.
Vec3 wallNormalOf(MillingMode mode) {
  if (mode == MillingMode::kUp) return Vec3::UnitY();
  if (mode == MillingMode::kDown) return -Vec3::UnitY();
  return Vec3::Zero();
}

constexpr double kAeStep = 1e-6;  // [m]

}  // namespace

ProcessGradient processGradient(const MillingModel& m, double fz, double ae, double ap) {
  ProcessGradient g;
  if (!(fz > 0) || !(ae > 0) || !(ap > 0)) return g;
  const double scale = ap / m.cut.ap;  // F̄ is linear in ap
  const Vec3 n = wallNormalOf(m.cut.mode);
  if (!n.isZero()) {
    const double lo = std::max(0.0, ae - kAeStep);
    const double hi = std::min(m.tool.diameter, ae + kAeStep);
    const Vec3 dF =
        (millingMeanForce(m, fz, hi) - millingMeanForce(m, fz, lo)) * (scale / (hi - lo));
    g.per_depth = dF * n.transpose();
  }
  const Vec3 F = millingMeanForce(m, fz, ae) * scale;
  g.fixed = -(F / ap) * Vec3::UnitZ().transpose();
  return g;
}

ModeCouplingState modeCouplingAt(const ModalModel& dyn, const Mat3& G) {
  ModeCouplingState st;
  const int n = static_cast<int>(dyn.modes.size());
  if (n == 0) return st;
  Eigen::MatrixXd U(3, n);
  for (int r = 0; r < n; ++r) U.col(r) = dyn.modes[static_cast<size_t>(r)].tcp;
  const Eigen::MatrixXd Kq = -(U.transpose() * G * U);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  for (int r = 0; r < n; ++r) {
    const VibrationMode& mo = dyn.modes[static_cast<size_t>(r)];
    A(n + r, r) = -mo.omega * mo.omega;
    A(n + r, n + r) = -2 * mo.zeta * mo.omega;
  }
  A.bottomLeftCorner(n, n) -= Kq;
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
  double best = -1e300;
  for (int i = 0; i < 2 * n; ++i) {
    const std::complex<double> s = es.eigenvalues()[i];
    if (s.real() > best) {
      best = s.real();
      st.frequency_hz = std::abs(s.imag()) / (2 * kPi);
    }
  }
  st.growth_rate = best;
  st.stable = best < 0;
  st.flutter = st.frequency_hz > 0;
  return st;
}

ModeCouplingLimit modeCouplingLimit(const ModalModel& dyn, const ProcessGradient& g, double ap) {
  ModeCouplingLimit out;
  out.at_cut = modeCouplingAt(dyn, g.at(1.0));
  const auto unstable = [&](double s) { return !modeCouplingAt(dyn, g.at(s)).stable; };
  double lo = 0;
  double hi = -1;
  for (int i = 0; i < kScanPoints; ++i) {
    const double s = kScanMin * std::pow(kScanMax / kScanMin, i / double(kScanPoints - 1));
    if (unstable(s)) {
      hi = s;
      break;
    }
    lo = s;
  }
  if (hi < 0) return out;
  while (hi - lo > 1e-4 * hi) {
    const double mid = 0.5 * (lo + hi);
    (unstable(mid) ? hi : lo) = mid;
  }
  const ModeCouplingState at = modeCouplingAt(dyn, g.at(hi));
  out.bounded = true;
  out.margin = hi;
  out.ap_lim = hi * ap;
  out.flutter = at.flutter;
  out.frequency_hz = at.frequency_hz;
  return out;
}

}  // namespace roprec
