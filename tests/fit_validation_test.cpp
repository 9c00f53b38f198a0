// The χ² check of an identification against independent references: the χ² quantile against
// tabulated values (NIST/SEMATECH e-Handbook, table 1.3.6.7.4), and the naming of the unmodelled
// effect on residuals made by hand from a known length scale, a known drift and pure noise.
#include "compensator/precision/fit_validation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace roprec {
namespace {

TEST(FitValidation, ChiSquareQuantileMatchesTheTable) {
  // upper 0.1 % critical values of χ²(ν)
  const std::vector<std::pair<int, double>> table{{5, 20.515},  {10, 29.588}, {20, 45.315},
                                                  {40, 73.402}, {60, 99.607}, {100, 149.449}};
  // Wilson–Hilferty: within 1.5 % at ν = 5, 1 % from ν = 10 on
  for (const auto& [dof, value] : table)
    EXPECT_NEAR(chiSquareQuantile(dof, 0.999), value, (dof < 10 ? 0.015 : 0.01) * value) << dof;
  // the median of χ²(ν) ≈ ν (1 − 2/(9ν))³
  EXPECT_NEAR(chiSquareQuantile(30, 0.5), 29.336, 0.01);
}

/// Holes on a grid of the three drilling directions around (1.4, 0, 0.3) m, σ = 5 µm, with
/// residual = effect(i, p) projected ⊥ the axis + noise.
struct Synthetic {
  std::vector<IdentificationHole> holes;
  IdentificationResult r;
};

Synthetic synthetic(const std::function<Vec3(size_t, const Vec3&)>& effect, double noise) {
  std::mt19937 g(7);
  std::normal_distribution<double> n(0.0, 1.0);
  Synthetic s;
  const std::vector<Mat3> frames{Mat3::Identity(),
                                 Mat3(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX())),
                                 Mat3(Eigen::AngleAxisd(0.25 * kPi, Vec3::UnitY()))};
  size_t i = 0;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      for (const Mat3& R : frames) {
        IdentificationHole h;
        h.id = "H" + std::to_string(i);
        h.T_W_hole.linear() = R;
        h.T_W_hole.translation() = Vec3(1.2 + 0.1 * a, -0.2 + 0.1 * b, 0.3);
        h.sigma = 5e-6;
        const Vec3 e = effect(i, h.T_W_hole.translation());
        Eigen::VectorXd r(2);
        r << R.col(0).dot(e) + noise * n(g), R.col(1).dot(e) + noise * n(g);
        s.r.residuals.push_back(r);
        s.r.chi2 += (r / h.sigma).squaredNorm();
        s.holes.push_back(h);
        ++i;
      }
    }
  }
  s.r.equations = static_cast<int>(2 * s.holes.size());
  s.r.dof = s.r.equations - 12;
  return s;
}

TEST(FitValidation, NoiseAtItsSigmaIsConsistent) {
  const Synthetic s = synthetic([](size_t, const Vec3&) -> Vec3 { return Vec3::Zero(); }, 5e-6);
  const FitCheck f = checkFit(s.r, s.holes);
  EXPECT_TRUE(f.consistent);
  EXPECT_LT(f.rms_normalized, 1.5);
  EXPECT_TRUE(f.explanation.empty());
}

TEST(FitValidation, ALengthScaleIsNamedWithItsValue) {
  // 0.2 mm/m about the base origin: 0.28 mm at 1.4 m
  const Synthetic s = synthetic([](size_t, const Vec3& p) -> Vec3 { return 0.2e-3 * p; }, 5e-6);
  const FitCheck f = checkFit(s.r, s.holes);
  EXPECT_FALSE(f.consistent);
  EXPECT_EQ(f.best.name, "length scale");
  EXPECT_GT(f.best.share, 0.95);
  EXPECT_NE(f.explanation.find("length scale of 0.2"), std::string::npos) << f.explanation;
}

TEST(FitValidation, ALengthScaleIsNamedOnTrackerPoints) {
  // tracker points as verify makes them (T_W_hole: the residual axes only, at the origin; the
  // point is where it was measured), all three components, 0.2 mm/m about the base origin
  std::mt19937 g(11);
  std::normal_distribution<double> n(0.0, 5e-6);
  Synthetic s;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      for (int c = 0; c < 3; ++c) {
        IdentificationHole h;
        h.point = true;
        h.p_W_measured = Vec3(1.2 + 0.1 * a, -0.2 + 0.1 * b, 0.2 + 0.15 * c);
        h.sigma = 5e-6;
        const Vec3 r = 0.2e-3 * h.p_W_measured + Vec3(n(g), n(g), n(g));
        s.r.residuals.emplace_back(r);
        s.r.chi2 += (r / h.sigma).squaredNorm();
        s.holes.push_back(h);
      }
    }
  }
  s.r.equations = static_cast<int>(3 * s.holes.size());
  s.r.dof = s.r.equations - 12;
  const FitCheck f = checkFit(s.r, s.holes);
  EXPECT_FALSE(f.consistent);
  EXPECT_EQ(f.best.name, "length scale");
  EXPECT_TRUE(std::isfinite(f.best.share));
  EXPECT_GT(f.best.share, 0.95);
  EXPECT_NE(f.explanation.find("length scale of 0.2"), std::string::npos) << f.explanation;
}

TEST(FitValidation, ADriftWithTimeIsNamed) {
  const Synthetic s = synthetic(
      [](size_t i, const Vec3&) -> Vec3 {
        return Vec3(0.0, 80e-6, -40e-6) * (static_cast<double>(i) / 47);
      },
      5e-6);
  const FitCheck f = checkFit(s.r, s.holes);
  EXPECT_FALSE(f.consistent);
  EXPECT_EQ(f.best.name, "drift with time");
  EXPECT_NE(f.explanation.find("drift with time"), std::string::npos) << f.explanation;
}

TEST(FitValidation, UnstructuredScatterIsNamedAsSuch) {
  const Synthetic s = synthetic([](size_t, const Vec3&) -> Vec3 { return Vec3::Zero(); }, 40e-6);
  const FitCheck f = checkFit(s.r, s.holes);
  EXPECT_FALSE(f.consistent);
  EXPECT_LT(f.best.share, 0.5);
  EXPECT_NE(f.explanation.find("scatter without the structure"), std::string::npos)
      << f.explanation;
}

}  // namespace
}  // namespace roprec
