// The tabulated 95 % radial coverage (uncertainty.hpp: R/√λ₂ tabulated in √(λ₁/λ₂) and
// interpolated) against the probability it must hit: P(r ≤ R) = 0.95 to 1e-10 for seeded random
// covariances of every aspect ratio and orientation (P by the 48-point quadrature of
// radialProbability), and the tabulated and the solved radius (p = 0.95 vs p = 0.95 + 1e-15,
// which takes the solver) agree to 1e-9 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compensator/precision/uncertainty.hpp"

namespace roprec {
namespace {

TEST(CoverageTable, HitsNinetyFivePercentForEveryAspectRatio) {
  std::mt19937 rng(95);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 300; ++n) {
    const double l2 = std::pow(10.0, -12 + 6 * u(rng));
    const double ratio = n < 20 ? std::pow(10.0, -13 + 0.6 * n) : u(rng) * u(rng);
    const double l1 = ratio * l2;
    const double a = 3.14159 * u(rng);
    Eigen::Matrix2d Q;
    Q << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    const Eigen::Matrix2d S = Q * Eigen::Vector2d(l1, l2).asDiagonal() * Q.transpose();
    const double R = radialCoverage(S, 0.95);
    EXPECT_NEAR(radialProbability(S, R), 0.95, 1e-10) << "ratio " << ratio;
    const double solved = radialCoverage(S, 0.95 + 1e-15);
    EXPECT_NEAR(R / solved, 1.0, 1e-9) << "ratio " << ratio;
  }
}

}  // namespace
}  // namespace roprec
