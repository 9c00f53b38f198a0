// GUM arithmetic of the per-hole budget against closed forms, hand-computed cases and seeded
// simulation: ISO 9283 RP -> σ, 2-D radial coverage factors, the ISO 14253-1 verdict, and the
// budget of a real hole (bundled KUKA, no process) recomputed by hand.
#include "compensator/precision/uncertainty.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "compensator/precision/identification.hpp"
#include "compensator/precision/prediction.hpp"
#include "compensator/support/rotation.hpp"

namespace roprec {
namespace {

TEST(Uncertainty, RpToSigmaMatchesChiDistributionAndSimulation) {
  // closed form: l̄ = 2√(2/π) σ, S_l = √(3 − 8/π) σ
  EXPECT_NEAR(rpFromSigma(1.0), 2 * std::sqrt(2 / kPi) + 3 * std::sqrt(3 - 8 / kPi), 1e-15);
  EXPECT_NEAR(rpFromSigma(1.0), 3.6161, 1e-4);  // docs/process.md §5.2: RP = 3.616 σ
  EXPECT_NEAR(sigmaFromRp(0.04e-3), 11.06e-6,
              0.01e-6);  // docs/process.md §5.2: ±0.04 mm -> σ ≈ 11 µm
  // ISO 9283 test simulated: 30 cycles, RP = l̄ + 3 S_l about the barycentre; averaged over runs
  std::mt19937 rng(9283);
  std::normal_distribution<double> n(0.0, 1.0);
  double rp_sum = 0;
  const int runs = 4000;
  for (int r = 0; r < runs; ++r) {
    std::vector<Eigen::Vector3d> x(30);
    Eigen::Vector3d bar = Eigen::Vector3d::Zero();
    for (auto& v : x) {
      v = Eigen::Vector3d(n(rng), n(rng), n(rng));
      bar += v;
    }
    bar /= 30;
    std::vector<double> l;
    for (const auto& v : x) l.push_back((v - bar).norm());
    double mean = 0;
    for (double d : l) mean += d;
    mean /= 30;
    double s2 = 0;
    for (double d : l) s2 += (d - mean) * (d - mean);
    rp_sum += mean + 3 * std::sqrt(s2 / 29);
  }
  // barycentre estimation shrinks l by √(29/30); the test's RP/σ is therefore ≈ 3.616·√(29/30)
  EXPECT_NEAR(rp_sum / runs, rpFromSigma(1.0) * std::sqrt(29.0 / 30.0), 0.02);
}

TEST(Uncertainty, RadialCoverageFactors) {
  EXPECT_NEAR(rayleighCoverageFactor(0.95), 2.4477, 1e-4);
  EXPECT_NEAR(rayleighCoverageFactor(0.9973), 3.4393,
              1e-3);  // docs/process.md §5.1: 99.73 % -> 3.439
  const Eigen::Matrix2d iso = Eigen::Matrix2d::Identity() * 1e-10;  // u = 10 µm
  EXPECT_NEAR(radialCoverage(iso), 2.4477e-5, 1e-9);
  EXPECT_NEAR(radialProbability(iso, 2.4477e-5), 0.95, 1e-4);
  // degenerate (1-D): 95 % two-sided -> 1.96 σ
  Eigen::Matrix2d line = Eigen::Matrix2d::Zero();
  line(1, 1) = 1.0;
  EXPECT_NEAR(radialCoverage(line), 1.959964, 1e-5);
  // anisotropic: against a seeded simulation
  Eigen::Matrix2d S;
  S << 4.0, 1.2, 1.2, 1.0;
  const double R = radialCoverage(S);
  std::mt19937 rng(1);
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Matrix2d L = S.llt().matrixL();
  int inside = 0;
  const int N = 400000;
  for (int i = 0; i < N; ++i) inside += (L * Eigen::Vector2d(n(rng), n(rng))).norm() <= R ? 1 : 0;
  EXPECT_NEAR(static_cast<double>(inside) / N, 0.95, 0.002);
}

/// The verdict's U₉₅ (radialCoverage) against the empirical 95 % quantile of |r| of 10⁶ seeded
/// samples of the 2-D normal, from isotropic to a nearly one-dimensional scatter: ≤ 0.5 %
/// (the quantile's own sampling error at 10⁶ samples is ~0.1 %). The isotropic RSS radius
/// k·√(tr Σ/2) is ≤ U₉₅ and up to ~11 % smaller (1-D limit: 1.960·√2 vs 2.448).
TEST(Uncertainty, AnisotropicRadiusMatchesMonteCarloMillionSamples) {
  const std::array<std::array<double, 3>, 5> cases{{
      {1.0, 0.0, 1.0},    // isotropic
      {4.0, 1.2, 1.0},    // elongated and correlated
      {9.0, 0.0, 1.0},    // 3:1 axes
      {100.0, 0.0, 1.0},  // 10:1 axes
      {1.0, 0.999, 1.0},  // nearly one-dimensional along (1, 1)
  }};
  std::mt19937_64 rng(20261123);
  std::normal_distribution<double> n(0.0, 1.0);
  const int N = 1000000;
  std::vector<double> r(N);
  for (const auto& c : cases) {
    Eigen::Matrix2d S;
    S << c[0], c[1], c[1], c[2];
    const Eigen::Matrix2d L = S.llt().matrixL();
    for (double& ri : r) ri = (L * Eigen::Vector2d(n(rng), n(rng))).norm();
    const auto q = r.begin() + static_cast<std::ptrdiff_t>(0.95 * N);
    std::nth_element(r.begin(), q, r.end());
    const double R = radialCoverage(S);
    EXPECT_NEAR(R / *q, 1.0, 5e-3)
        << "Sigma = [" << c[0] << " " << c[1] << "; " << c[1] << " " << c[2] << "]";
    const double iso = rayleighCoverageFactor() * std::sqrt(0.5 * S.trace());
    EXPECT_LE(iso, R * (1 + 1e-9));
    EXPECT_GE(iso, R * 0.88);
  }
}

TEST(Uncertainty, Iso14253VerdictHandCases) {
  const double t = 0.2e-3;  // ⌀0.20 mm
  // docs/process.md §5.4 example: e = 40 µm, U = 30 µm -> 2(40 + 30) = 140 ≤ 200 µm: conforms
  EXPECT_EQ(verdictFor(40e-6, 30e-6, t), Verdict::kConforms);
  EXPECT_EQ(verdictFor(80e-6, 30e-6, t),
            Verdict::kConformsAfterCompensation);                // 110 > 100, 30 ≤ 100
  EXPECT_EQ(verdictFor(5e-6, 101e-6, t), Verdict::kNotCapable);  // scatter alone too large
  EXPECT_EQ(verdictFor(70e-6, 30e-6, t), Verdict::kConforms);    // exactly on the guard band
  // limits are inclusive (ISO 1101): U = t/2 with e = 0 conforms, U = t/2 with e > 0 is capable
  EXPECT_EQ(verdictFor(0.0, 100e-6, t), Verdict::kConforms);
  EXPECT_EQ(verdictFor(1e-6, 100e-6, t), Verdict::kConformsAfterCompensation);
  EXPECT_STREQ(verdictName(Verdict::kNotCapable), "not-capable");
}

TEST(Uncertainty, Iso14253MeasuredDecisionBorderline) {
  const double t = 0.2e-3;
  EXPECT_EQ(measuredDecision(70e-6, 30e-6, t), MeasuredDecision::kConformanceProven);  // = t/2
  EXPECT_EQ(measuredDecision(71e-6, 30e-6, t), MeasuredDecision::kNoDecision);
  EXPECT_EQ(measuredDecision(130e-6, 30e-6, t), MeasuredDecision::kNoDecision);  // on the limit
  EXPECT_EQ(measuredDecision(131e-6, 30e-6, t), MeasuredDecision::kNonConformanceProven);
}

}  // namespace
}  // namespace roprec
