#include "compensator/uncertainty.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "compensator/rotation.hpp"

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

double radialProbability(const Eigen::Matrix2d& Sigma, double R) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(Sigma);
  const double l1 = std::max(es.eigenvalues()[0], 0.0);
  const double l2 = std::max(es.eigenvalues()[1], 0.0);
  if (l2 <= 0.0) return R > 0 ? 1.0 : 0.0;
  if (l1 <= 1e-12 * l2) {  // degenerate: 1-D normal along the major axis
    return std::erf(R / std::sqrt(2.0 * l2));
  }
  // Composite Simpson over φ ∈ [0, π/2] (the integrand is symmetric in the four quadrants).
  const int n = 400;
  const double h = 0.5 * kPi / n;
  double acc = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double phi = i * h;
    const double c = std::cos(phi);
    const double s = std::sin(phi);
    const double q = c * c / l1 + s * s / l2;
    const double f = (1.0 - std::exp(-0.5 * R * R * q)) / (std::sqrt(l1 * l2) * q);
    acc += f * ((i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  return 4.0 * acc * h / 3.0 / (2.0 * kPi);
}

double radialCoverage(const Eigen::Matrix2d& Sigma, double p) {
  const double tr = Sigma.trace();
  if (tr <= 0.0) return 0.0;
  double lo = 0.0;
  double hi = 10.0 * std::sqrt(tr);
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (radialProbability(Sigma, mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace roprec
