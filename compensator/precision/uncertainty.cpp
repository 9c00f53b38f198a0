#include "compensator/precision/uncertainty.hpp"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <vector>

#include "compensator/support/quadrature.hpp"
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
/// Gauss–Legendre nodes and weights on [0, π/2], computed once (no allocation per call).
struct QuarterNodes {
  static constexpr int kN = 48;
  std::array<double, kN> cos_t{}, sin_t{}, w{};
};
const QuarterNodes& quarterNodes() {
  static const QuarterNodes q = [] {
    QuarterNodes n;
    std::vector<double> x;
    std::vector<double> w;
    gaussLegendre(QuarterNodes::kN, x, w);
    for (int i = 0; i < QuarterNodes::kN; ++i) {
      const double t = 0.25 * kPi * (x[i] + 1.0);
      n.cos_t[i] = std::cos(t);
      n.sin_t[i] = std::sin(t);
      n.w[i] = 0.25 * kPi * w[i];
    }
    return n;
  }();
  return q;
}

/// P(r ≤ R) for eigenvalues 0 < l1 ≤ l2, r² = l1 z1² + l2 z2², z standard normal. With the major
/// coordinate z2 = a sin t, a = R/√l2, the inner probability P(|z1| ≤ √((R² − l2 z2²)/l1)) is
/// erf(R cos t/√(2 l1)) and
///   P = 2 ∫₀^{π/2} φ(a sin t) erf(R cos t/√(2 l1)) a cos t dt,   φ the standard normal density,
/// smooth in t for any aspect ratio (the erf's boundary layer at t → π/2 carries a weight
/// ~ φ(a) a · 2 l1/R², negligible), integrated by 48-point Gauss–Legendre.
double radialP(double l1, double l2, double R) {
  const QuarterNodes& q = quarterNodes();
  const double a = R / std::sqrt(l2);
  const double b = R / std::sqrt(2.0 * l1);
  double acc = 0.0;
  for (int i = 0; i < QuarterNodes::kN; ++i) {
    const double z = a * q.sin_t[i];
    acc += q.w[i] * std::exp(-0.5 * z * z) * std::erf(b * q.cos_t[i]) * q.cos_t[i];
  }
  return 2.0 * a * acc / std::sqrt(2.0 * kPi);
}

/// x with erf(x/√2) = p (the two-sided 1-D normal quantile), by Newton.
double normalTwoSided(double p) {
  double x = 1.96;
  for (int i = 0; i < 50; ++i) {
    const double f = std::erf(x / std::sqrt(2.0)) - p;
    x -= f / (std::sqrt(2.0 / kPi) * std::exp(-0.5 * x * x));
    if (std::abs(f) < 1e-15) break;
  }
  return x;
}
}  // namespace

double radialProbability(const Eigen::Matrix2d& Sigma, double R) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(Sigma);
  const double l1 = std::max(es.eigenvalues()[0], 0.0);
  const double l2 = std::max(es.eigenvalues()[1], 0.0);
  if (l2 <= 0.0) return R > 0 ? 1.0 : 0.0;
  if (l1 <= 1e-14 * l2) return std::erf(R / std::sqrt(2.0 * l2));  // degenerate: 1-D normal
  return radialP(l1, l2, R);
}

double radialCoverage(const Eigen::Matrix2d& Sigma, double p) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(Sigma);
  const double l1 = std::max(es.eigenvalues()[0], 0.0);
  const double l2 = std::max(es.eigenvalues()[1], 0.0);
  if (l2 <= 0.0) return 0.0;
  const double s2 = std::sqrt(l2);
  if (l1 <= 1e-14 * l2) return normalTwoSided(p) * s2;
  // r ≥ √l2 |z2| and r ≤ √l2 |z|: the radius lies between the 1-D and the Rayleigh quantile of
  // the major axis. Regula falsi (Illinois) on that bracket; P is increasing in R.
  double lo = normalTwoSided(p) * s2;
  double hi = rayleighCoverageFactor(p) * s2;
  double flo = radialP(l1, l2, lo) - p;
  double fhi = radialP(l1, l2, hi) - p;
  if (flo >= 0) return lo;
  if (fhi <= 0) return hi;
  double R = hi;
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-13 * hi; ++it) {
    R = (lo * fhi - hi * flo) / (fhi - flo);
    const double f = radialP(l1, l2, R) - p;
    if (f == 0) return R;
    if (f < 0) {
      lo = R;
      flo = f;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = R;
      fhi = f;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
  return R;
}

}  // namespace roprec
