#include "compensator/process/machining_deviation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compensator/process/drilling_forces.hpp"

namespace roprec {
namespace {

// GUM type-B divisors checked against sampled distributions (seeded Monte Carlo).
TEST(MachiningDeviation, StandardUncertaintyDivisorsMatchSampledDistributions) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> ph(0.0, 2 * kPi);
  const int n = 400000;
  double s_rect = 0, s_arc = 0, s_tri = 0;
  for (int i = 0; i < n; ++i) {
    const double r = u(rng);
    s_rect += r * r;
    const double a = std::sin(ph(rng));
    s_arc += a * a;
    const double t = 0.5 * (u(rng) + u(rng));
    s_tri += t * t;
  }
  EXPECT_NEAR(standardUncertainty(1.0, Distribution::kRectangular), std::sqrt(s_rect / n), 3e-3);
  EXPECT_NEAR(standardUncertainty(1.0, Distribution::kArcsine), std::sqrt(s_arc / n), 3e-3);
  EXPECT_NEAR(standardUncertainty(1.0, Distribution::kTriangular), std::sqrt(s_tri / n), 3e-3);
  EXPECT_DOUBLE_EQ(standardUncertainty(2.0, Distribution::kNormal), 2.0);
}

TEST(MachiningDeviation, CantileverAndCombination) {
  DrillGeometry g;
  g.diameter = 10e-3;
  MachiningDeviationParams p;
  p.axis_tilt = 0.1 * kDeg;
  p.axis_lever = 10e-3;
  p.runout = 10e-6;
  p.stickout = 40e-3;
  p.equivalent_diameter_ratio = 0.8;
  p.youngs_modulus = 600e9;
  p.spindle_compliance = 0.0;
  const MachiningDeviation d = machiningDeviation(p, g, 100.0, Eigen::Vector2d(50.0, 0.0));
  // Euler–Bernoulli tip deflection F L³/(3EI) with I = π (8 mm)⁴/64 = 201.06 mm⁴:
  // 100 N · 64000 mm³ / (3 · 600000 N/mm² · 201.06 mm⁴) = 0.017684 mm.
  EXPECT_NEAR(d.components[2].half_width, 17.684e-6, 0.002e-6);
  EXPECT_NEAR(d.delta_tool.x(), 0.5 * 17.684e-6, 0.001e-6);
  EXPECT_NEAR(d.components[0].half_width, 10e-3 * std::tan(0.1 * kDeg), 1e-15);
  EXPECT_EQ(d.components[0].distribution, Distribution::kRectangular);
  EXPECT_EQ(d.components[1].distribution, Distribution::kArcsine);
  EXPECT_EQ(d.components[2].distribution, Distribution::kArcsine);
  double s = 0;
  for (const auto& c : d.components) s += c.standard * c.standard;
  EXPECT_NEAR(d.u_c, std::sqrt(s), 1e-18);
  EXPECT_NEAR(d.k, 2.4477, 1e-4);  // 2-D radial 95 %: √(−2 ln 0.05)
  EXPECT_NEAR(d.U, std::sqrt(-2.0 * std::log(0.05)) * d.u_c, 1e-18);
}

double defaultUmach(double D_mm, double f_mm) {
  const MachiningDeviationParams p = defaultMachiningDeviation(D_mm * 1e-3);
  DrillGeometry g;
  g.diameter = D_mm * 1e-3;
  g.web_thickness = 0.16 * g.diameter;
  g.runout = p.runout;
  const DrillingModel m =
      makeDrillingModel(g, findMaterial("Al 6061-T6")->drilling, AngleLaw::kGeometric, f_mm * 1e-3);
  return 2.0 * machiningDeviation(p, g, drillingForces(m, f_mm * 1e-3).residual).u_c;
}

/// Fr of a Dc mm drill in Al 6061-T6 at feed f mm/rev with radial runout ρ mm.
double runoutForce(double D_mm, double f_mm, double rho_mm) {
  DrillGeometry g;
  g.diameter = D_mm * 1e-3;
  g.web_thickness = 0.16 * g.diameter;
  g.runout = rho_mm * 1e-3;
  const DrillingModel m =
      makeDrillingModel(g, findMaterial("Al 6061-T6")->drilling, AngleLaw::kGeometric, f_mm * 1e-3);
  return drillingForces(m, f_mm * 1e-3).residual;
}

// The feed dependence of the runout force is the Kienzle law's (docs/process.md §5.7): with both
// lips cutting (f/2 > dz = 2ρ/tan κ) the chip-thickness imbalance dominates and Fr ∝ f^(−m)
// (slowly falling, m = 0.25 here); once lip 2 no longer cuts (f/2 < dz) Fr ∝ f^(1−m) grows.
// Checked by the log-slope over f 0.1 → 0.3 mm/rev.
TEST(MachiningDeviation, RunoutForceFeedDependenceFollowsTheKienzleLaw) {
  const double m = findMaterial("Al 6061-T6")->drilling.tangential.m;
  auto slope = [](double D, double rho, double f0, double f1) {
    return std::log(runoutForce(D, f1, rho) / runoutForce(D, f0, rho)) / std::log(f1 / f0);
  };
  // default runout of a Dc 10 drill: ρ = 0.25 µm/mm × 30 mm = 7.5 µm → dz ≈ 9 µm < f/2
  const double s_two = slope(10, 0.0075, 0.1, 0.3);
  EXPECT_LT(s_two, 0.0);
  EXPECT_GT(s_two, -m - 0.05);
  // large runout: ρ = 0.1 mm → dz ≈ 0.12 mm > f/2 for f ≤ 0.2: one lip cuts, Fr ∝ f^(1−m)
  EXPECT_NEAR(slope(10, 0.1, 0.1, 0.2), 1.0 - m, 0.05);
}

// Defaults reproduce the band Ferreras-Higuero et al. report (±30 µm at Dc 8 to ±60 µm at Dc 12,
// a 1-D ±2σ figure, 2·u_c) within 10 %, and U_mach grows with the diameter.
TEST(MachiningDeviation, DefaultsReproduceThePaperBandAndGrowWithDiameter) {
  EXPECT_NEAR(defaultUmach(8, 0.2) / 30e-6, 1.0, 0.10);
  EXPECT_NEAR(defaultUmach(12, 0.2) / 60e-6, 1.0, 0.10);
  double last = 0;
  for (double D : {6.0, 8.0, 10.0, 12.0, 14.0}) {
    const double U = defaultUmach(D, 0.2);
    EXPECT_GT(U, last) << D;
    last = U;
  }
}

}  // namespace
}  // namespace roprec
