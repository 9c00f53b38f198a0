#include "compensator/precision/uncertainty.hpp"

#include "compensator/precision/coverage_table95.hpp"

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

namespace {
/// Eigenvalues l1 ≤ l2 of a symmetric 2×2 matrix in closed form, clamped at 0.
void eigenvalues2(const Eigen::Matrix2d& S, double& l1, double& l2) {
  const double m = 0.5 * (S(0, 0) + S(1, 1));
  const double h = 0.5 * (S(0, 0) - S(1, 1));
  const double o = 0.5 * (S(0, 1) + S(1, 0));
  const double r = std::hypot(h, o);
  l2 = std::max(m + r, 0.0);
  l1 = std::max(m - r, 0.0);
}

/// P(R) − p and dP/dR in one pass over the nodes (the derivative shares the node's exp):
///   dP/dR = 2/√(2π) Σ wᵢ cᵢ [ e^{−a²sᵢ²/2}(1 − a²sᵢ²) erf(b cᵢ)/√l2
///                           + a e^{−a²sᵢ²/2} (2/√π) e^{−b²cᵢ²} cᵢ/√(2 l1) ].
double radialPAndSlope(double l1, double l2, double R, double& slope) {
  const QuarterNodes& q = quarterNodes();
  const double s2 = std::sqrt(l2);
  const double s1 = std::sqrt(2.0 * l1);
  const double a = R / s2;
  const double b = R / s1;
  double acc = 0.0;
  double dacc = 0.0;
  for (int i = 0; i < QuarterNodes::kN; ++i) {
    const double z = a * q.sin_t[i];
    const double e = std::exp(-0.5 * z * z);
    const double bc = b * q.cos_t[i];
    const double er = std::erf(bc);
    acc += q.w[i] * e * er * q.cos_t[i];
    dacc += q.w[i] * q.cos_t[i] * e *
            ((1.0 - z * z) * er / s2 +
             a * (2.0 / std::sqrt(kPi)) * std::exp(-bc * bc) * q.cos_t[i] / s1);
  }
  const double k = 2.0 / std::sqrt(2.0 * kPi);
  slope = k * dacc;
  return k * a * acc;
}
}  // namespace

double radialProbability(const Eigen::Matrix2d& Sigma, double R) {
  double l1 = 0.0;
  double l2 = 0.0;
  eigenvalues2(Sigma, l1, l2);
  if (l2 <= 0.0) return R > 0 ? 1.0 : 0.0;
  if (l1 <= 1e-14 * l2) return std::erf(R / std::sqrt(2.0 * l2));  // degenerate: 1-D normal
  return radialP(l1, l2, R);
}

namespace {
double solveCoverage(double l1, double l2, double p);

/// g(t) = R₉₅/√l2 at t = √(l1/l2) ∈ [0, 1] (kCoverageTable95, made by the Newton solver below),
/// read by 4-point cubic (Lagrange) interpolation, used for t ≥ 0.0316 (l1/l2 ≥ 1e-3) where it
/// is within 1e-10 of the solver (tests/coverage_table_test.cpp).
double coverageTable95At(double t) {
  constexpr int kN = kCoverageTable95Intervals;
  const double x = t * kN;
  int i = static_cast<int>(x);
  i = std::min(std::max(i - 1, 0), kN - 3);  // stencil i .. i+3 around x
  const double u = x - i;                    // in [0, 3]
  const double* y = &kCoverageTable95[static_cast<size_t>(i)];
  const double a = u * (u - 1) * (u - 2);
  return -y[0] * (u - 1) * (u - 2) * (u - 3) / 6.0 + y[1] * u * (u - 2) * (u - 3) / 2.0 -
         y[2] * u * (u - 1) * (u - 3) / 2.0 + y[3] * a / 6.0;
}
}  // namespace

double radialCoverage(const Eigen::Matrix2d& Sigma, double p) {
  double l1 = 0.0;
  double l2 = 0.0;
  eigenvalues2(Sigma, l1, l2);
  if (l2 <= 0.0) return 0.0;
  // below l1/l2 = 1e-3, g(t) bends too sharply for the table (the 1-D limit): solve there
  if (p == 0.95 && l1 >= 1e-3 * l2)
    return std::sqrt(l2) * coverageTable95At(std::sqrt(std::min(1.0, l1 / l2)));
  return solveCoverage(l1, l2, p);
}

double radialCoverageSolved(double l1, double l2, double p) { return solveCoverage(l1, l2, p); }

namespace {
double solveCoverage(double l1, double l2, double p) {
  const double s2 = std::sqrt(l2);
  // the 1-D quantile is a constant of p: computed once for the default p
  static const double kTwoSided95 = normalTwoSided(0.95);
  static const double kRayleigh95 = rayleighCoverageFactor(0.95);
  const double z1 = p == 0.95 ? kTwoSided95 : normalTwoSided(p);
  const double zr = p == 0.95 ? kRayleigh95 : rayleighCoverageFactor(p);
  if (l1 <= 1e-14 * l2) return z1 * s2;
  // r ≥ √l2 |z2| and r ≤ √l2 |z|: the radius lies between the 1-D and the Rayleigh quantile of
  // the major axis. Newton from the interpolation in √(l1/l2) (exact at both ends), kept inside
  // that bracket (bisection when a step leaves it); P is increasing in R.
  double lo = z1 * s2;
  double hi = zr * s2;
  double R = lo + (hi - lo) * std::sqrt(l1 / l2);
  for (int it = 0; it < 60; ++it) {
    double slope = 0.0;
    const double f = radialPAndSlope(l1, l2, R, slope) - p;
    if (f == 0) return R;
    (f < 0 ? lo : hi) = R;
    double next = slope > 0 ? R - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - R);
    R = next;
    if (step <= 1e-14 * R || hi - lo <= 1e-13 * hi) break;
  }
  return R;
}
}  // namespace

}  // namespace roprec
