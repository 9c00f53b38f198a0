#include "compensator/precision/uncertainty.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "compensator/support/rotation.hpp"

namespace roprec {

namespace {
double rpFactor() {
  const double mean = 2.0 * std::sqrt(2.0 / kPi);
  const double sd = std::sqrt(3.0 - 8.0 / kPi);
  return mean + 3.0 * sd;
}
}  // namespace

double sigmaFromRp(double rp) { return rp / rpFactor(); }
double rpFromSigma(double sigma) { return sigma * rpFactor(); }

double rayleighCoverageFactor(double p) { return std::sqrt(-2.0 * std::log(1.0 - p)); }

namespace {
/// P(r ≤ R) and dP/dR for eigenvalues l1 ≤ l2. The integrand is smooth and π-periodic in φ, so
/// the trapezoid rule over a period is spectrally accurate: 48 nodes give ~1e-15 for l2/l1 < 1e3.
void radialPd(double l1, double l2, double R, double& P, double& dP) {
  constexpr int n = 48;
  const double h = kPi / n;
  double acc = 0.0;
  double dacc = 0.0;
  for (int i = 0; i < n; ++i) {
    const double phi = i * h;
    const double c = std::cos(phi);
    const double s = std::sin(phi);
    const double q = c * c / l1 + s * s / l2;
    const double e = std::exp(-0.5 * R * R * q);
    acc += (1.0 - e) / q;
    dacc += R * e;  // d/dR [(1 − e)/q] = R e
  }
  const double norm = h / (kPi * std::sqrt(l1 * l2));
  P = acc * norm;
  dP = dacc * norm;
}
}  // namespace

double radialProbability(const Eigen::Matrix2d& Sigma, double R) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(Sigma);
  const double l1 = std::max(es.eigenvalues()[0], 0.0);
  const double l2 = std::max(es.eigenvalues()[1], 0.0);
  if (l2 <= 0.0) return R > 0 ? 1.0 : 0.0;
  if (l1 <= 1e-6 * l2) return std::erf(R / std::sqrt(2.0 * l2));  // degenerate: 1-D normal
  double P = 0;
  double dP = 0;
  radialPd(l1, l2, R, P, dP);
  return P;
}

double radialCoverage(const Eigen::Matrix2d& Sigma, double p) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(Sigma);
  const double l1 = std::max(es.eigenvalues()[0], 0.0);
  const double l2 = std::max(es.eigenvalues()[1], 0.0);
  if (l2 <= 0.0) return 0.0;
  if (l1 <= 1e-6 * l2) {
    // 1-D: R = σ √2 erf⁻¹(p), by Newton on erf
    double x = 1.96;
    for (int i = 0; i < 50; ++i) {
      const double f = std::erf(x / std::sqrt(2.0)) - p;
      x -= f / (std::sqrt(2.0 / kPi) * std::exp(-0.5 * x * x));
      if (std::abs(f) < 1e-15) break;
    }
    return x * std::sqrt(l2);
  }
  // Newton from the isotropic (Rayleigh) radius of the mean variance, safeguarded by a bracket
  double R = rayleighCoverageFactor(p) * std::sqrt(0.5 * (l1 + l2));
  double lo = 0.0;
  double hi = 20.0 * std::sqrt(l2);
  for (int it = 0; it < 60; ++it) {
    double P = 0;
    double dP = 0;
    radialPd(l1, l2, R, P, dP);
    const double f = P - p;
    if (std::abs(f) < 1e-14) break;
    (f < 0 ? lo : hi) = R;
    double next = R - f / dP;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    R = next;
  }
  return R;
}

}  // namespace roprec
