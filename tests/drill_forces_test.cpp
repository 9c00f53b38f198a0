#include <gtest/gtest.h>

#include <cmath>

#include "compensator/process/drilling_forces.hpp"
#include "tests/support/counting_new.hpp"

namespace roprec {
namespace {

DrillGeometry drill(double D_mm) {
  DrillGeometry g;  // §2.3 geometry: 2p 118°, δ0 30°, 2w 0.16 Dc, ψ 125°
  g.diameter = D_mm * 1e-3;
  g.web_thickness = 0.16 * g.diameter;
  return g;
}

const DrillingCoefficients& al6061() { return findMaterial("Al 6061-T6")->drilling; }

DrillingModel model(double D_mm, double f_mm, double runout_um = 0) {
  DrillGeometry g = drill(D_mm);
  g.runout = runout_um * 1e-6;
  return makeDrillingModel(g, al6061(), AngleLaw::kGeometric, f_mm * 1e-3);
}

// docs/process.md §7.5, mechanistic column (lips + chisel): M / F_lips / Fz, ±1 %.
TEST(DrillForces, MechanisticTableRegression) {
  struct Row {
    double D, f, M, Flips, Fz;
  };
  const Row rows[] = {
      {8, 0.1, 1.13, 336, 740},   {8, 0.2, 1.89, 558, 1227},  {8, 0.3, 2.55, 745, 1639},
      {10, 0.1, 1.77, 421, 927},  {10, 0.2, 2.96, 701, 1542}, {10, 0.3, 4.00, 939, 2066},
      {12, 0.1, 2.54, 507, 1115}, {12, 0.2, 4.27, 844, 1857}, {12, 0.3, 5.77, 1134, 2494}};
  for (const Row& r : rows) {
    const DrillingForces F = drillingForces(model(r.D, r.f), r.f * 1e-3);
    EXPECT_NEAR(F.torque / r.M, 1.0, 0.01) << r.D << " " << r.f;
    EXPECT_NEAR(F.thrust_lips / r.Flips, 1.0, 0.01) << r.D << " " << r.f;
    EXPECT_NEAR(F.thrust / r.Fz, 1.0, 0.01) << r.D << " " << r.f;
  }
  // §2.1: per-lip totals at Dc 10 / f 0.2
  const DrillingForces F = drillingForces(model(10, 0.2), 0.2e-3);
  EXPECT_NEAR(F.lip[0].Ft, 529, 529 * 0.01);
  EXPECT_NEAR(F.lip[0].Frad, 236, 236 * 0.01);
  EXPECT_NEAR(F.thrust_chisel / F.thrust, 1.2 / 2.2, 1e-12);
}

// Independent integration: midpoint rule with 20000 elements over the closed-form angles of
// §1.2 and working rake from the §1.2 approximation is replaced by the static model here.
TEST(DrillForces, GaussLegendreMatchesFineMidpointRuleOnClosedForms) {
  const DrillGeometry g = drill(10);
  const DrillingCoefficients& c = al6061();
  const DrillingModel m = makeDrillingModel(g, c, AngleLaw::kGeometric, 0.0);
  const double f = 0.2e-3;
  const DrillingForces F = drillingForces(m, f);
  const double a = g.chiselHalfLength();
  const double R = g.radius();
  const int n = 20000;
  double Ft = 0, Fa = 0, M = 0, Frad = 0;
  for (int i = 0; i < n; ++i) {
    const double r = a + (R - a) * (i + 0.5) / n;
    const double dr = (R - a) / n;
    const EdgeAngles e = closedFormEdgeAngles(g, r);
    const double h = 0.5 * f * std::sin(e.kappa_r);
    const double kst = c.tangential.k0 * (c.tangential.a + c.tangential.b * e.gamma_n) *
                       std::pow(h / 1e-3, -c.tangential.m);
    const double ksa =
        c.axial.k0 * (c.axial.a + c.axial.b * e.gamma_n) * std::pow(h / 1e-3, -c.axial.m);
    const double db = dr / std::sin(e.kappa_r);
    Ft += kst * h * db;
    Fa += ksa * h * db;
    Frad += ksa * h * db / std::tan(e.kappa_r);
    M += kst * h * db * r;
  }
  EXPECT_NEAR(F.lip[0].Ft / Ft, 1.0, 2e-5);
  EXPECT_NEAR(F.lip[0].Fa / Fa, 1.0, 2e-5);
  EXPECT_NEAR(F.lip[0].Frad / Frad, 1.0, 2e-5);
  EXPECT_NEAR(F.lip[0].M / M, 1.0, 2e-5);
  // 24 Gauss points against 200: converged.
  const DrillingModel fine = makeDrillingModel(g, c, AngleLaw::kGeometric, 0.0, 200);
  EXPECT_NEAR(drillingForces(fine, f).torque / F.torque, 1.0, 1e-7);
}

TEST(DrillForces, RadialForceCancelsForASymmetricDrill) {
  for (double D : {6.0, 10.0, 12.0}) {
    const DrillingForces F = drillingForces(model(D, 0.2), 0.2e-3);
    EXPECT_LT(F.residual, 1e-9 * F.thrust);
    EXPECT_NEAR(F.lip[0].Frad, F.lip[1].Frad, 1e-9 * F.lip[0].Frad);
  }
}

// §2.1 runout table (rigid tool, f 0.2): integrated Fr within 3 %; and the linearised formula
// Fr ≈ (1−m)·8ρ cot p / f · √(Ft,lip² + Frad,lip²) within 5 %.
TEST(DrillForces, RunoutResidualForceTable) {
  const double table[3][3] = {{43, 87, 174}, {54, 108, 216}, {65, 129, 259}};
  const double Ds[] = {8, 10, 12};
  const double rhos[] = {5, 10, 20};
  for (int i = 0; i < 3; ++i) {
    const DrillingForces sym = drillingForces(model(Ds[i], 0.2), 0.2e-3);
    for (int j = 0; j < 3; ++j) {
      const DrillingForces F = drillingForces(model(Ds[i], 0.2, rhos[j]), 0.2e-3);
      EXPECT_NEAR(F.residual / table[i][j], 1.0, 0.03) << Ds[i] << " " << rhos[j];
      const double lin = 0.75 * 8 * rhos[j] * 1e-6 / std::tan(59 * kDeg) / 0.2e-3 *
                         std::hypot(sym.lip[0].Ft, sym.lip[0].Frad);
      EXPECT_NEAR(F.residual / lin, 1.0, 0.05);
      EXPECT_GT(F.lip[0].Ft, F.lip[1].Ft);
    }
  }
}

// §2.1 entry table, Dc 10 / f 0.2: M and Fz vs tip depth, ±2 %.
TEST(DrillForces, ProgressiveEntryTable) {
  const DrillingModel m = model(10, 0.2);
  DrillingData d(m);
  const double z[] = {0.2, 0.5, 1.0, 1.5, 2.0, 2.5};
  const double M[] = {0.14, 0.38, 0.90, 1.54, 2.27, 2.96};
  const double Fz[] = {258, 554, 931, 1211, 1417, 1542};
  for (int i = 0; i < 6; ++i) {
    const DrillingForces F = drillingForcesAtDepth(m, d, 0.2e-3, z[i] * 1e-3, 0.0);
    EXPECT_NEAR(F.torque / M[i], 1.0, 0.025) << z[i];
    EXPECT_NEAR(F.thrust / Fz[i], 1.0, 0.02) << z[i];
  }
  // Thrust rises faster than torque (relative to steady).
  const DrillingForces s = drillingForces(m, 0.2e-3);
  const DrillingForces e = drillingForcesAtDepth(m, d, 0.2e-3, 0.5e-3, 0.0);
  EXPECT_GT(e.thrust / s.thrust, e.torque / s.torque);
}

TEST(DrillForces, BreakthroughDropsThrustBeforeTorque) {
  const DrillingModel m = model(10, 0.2);
  DrillingData d(m);
  const double T = 12e-3;
  const DrillingForces s = drillingForces(m, 0.2e-3);
  const DrillingForces just_out = drillingForcesAtDepth(m, d, 0.2e-3, T + 0.05e-3, T);
  EXPECT_FALSE(just_out.chisel_engaged);
  EXPECT_LT(just_out.thrust, 0.5 * s.thrust);
  EXPECT_GT(just_out.torque, 0.95 * s.torque);
  const auto prof = drillingDepthProfile(m, d, 0.2e-3, T, true, 0.05e-3);
  EXPECT_NEAR(prof.front().forces.thrust, 0.0, 1e-12);
  EXPECT_NEAR(prof.back().forces.torque, 0.0, 1e-9);
  double maxM = 0;
  for (const auto& p : prof) maxM = std::max(maxM, p.forces.torque);
  EXPECT_NEAR(maxM, s.torque, 1e-9 * s.torque);
}

TEST(DrillForces, ToolWrenchSigns) {
  const DrillingForces F = drillingForces(model(10, 0.2, 10), 0.2e-3);
  const ToolWrench w0 = toolWrench(F, 0.0);
  EXPECT_DOUBLE_EQ(w0.force.z(), -F.thrust);
  EXPECT_DOUBLE_EQ(w0.torque.z(), -F.torque);
  EXPECT_NEAR(w0.force.head<2>().norm(), F.residual, 1e-9);
  const ToolWrench w90 = toolWrench(F, kPi / 2);
  EXPECT_NEAR(w90.force.x(), -w0.force.y(), 1e-9);
  EXPECT_NEAR(w90.force.y(), w0.force.x(), 1e-9);
  // Torque check against power: P = M ω with ω about +z, and the torque on the tool opposes it.
  EXPECT_LT(w0.torque.dot(Vec3::UnitZ()), 0.0);
}

TEST(DrillForces, ForcesGrowWithFeedAndDiameter) {
  double lastF = 0, lastM = 0;
  for (double f : {0.05, 0.1, 0.15, 0.2, 0.25, 0.3}) {
    const DrillingForces F = drillingForces(model(10, f), f * 1e-3);
    EXPECT_GT(F.thrust, lastF);
    EXPECT_GT(F.torque, lastM);
    lastF = F.thrust;
    lastM = F.torque;
  }
  // Dc scaling with a geometrically similar drill and static angles: thrust ∝ Dc, torque ∝ Dc²
  // exactly (working angles depend on f/(2πr) and break the similarity slightly).
  const DrillingForces a =
      drillingForces(makeDrillingModel(drill(8), al6061(), AngleLaw::kGeometric, 0.0), 0.2e-3);
  const DrillingForces b =
      drillingForces(makeDrillingModel(drill(12), al6061(), AngleLaw::kGeometric, 0.0), 0.2e-3);
  EXPECT_NEAR(b.thrust / a.thrust, 1.5, 1e-6);
  EXPECT_NEAR(b.torque / a.torque, 2.25, 1e-6);
}

TEST(DrillForces, PerHoleEvaluationDoesNotAllocate) {
  const DrillingModel m = model(10, 0.2, 10);
  DrillingForces F;
  const long allocations = test::allocationsOf([&] { F = drillingForces(m, 0.21e-3); });
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(F.thrust, 0);
}

TEST(DrillForces, PaperModeUnderPredictsInnerLipThrust) {
  const DrillGeometry g = drill(10);
  const DrillingModel geo = makeDrillingModel(g, al6061(), AngleLaw::kGeometric, 0.2e-3);
  const DrillingModel pap = makeDrillingModel(g, al6061(), AngleLaw::kPaperProportional, 0.2e-3);
  const DrillingForces a = drillingForces(geo, 0.2e-3);
  const DrillingForces b = drillingForces(pap, 0.2e-3);
  EXPECT_LT(b.thrust_lips, a.thrust_lips);  // §1.3 consequence 1
  EXPECT_LT((a.torque - b.torque) / a.torque, (a.thrust_lips - b.thrust_lips) / a.thrust_lips);
}

}  // namespace
}  // namespace roprec

namespace roprec {
namespace {

// Feed absorbed by an axial compliance (docs/process.md §2.1), one root per revolution.
TEST(DrillAxialCoupling, RigidLimitEqualsTheDepthProfile) {
  const DrillingModel m = model(10, 0.2);
  DrillingData d(m);
  const auto s = drillingAxialCoupling(m, d, 0.2e-3, 12e-3, true, 0.0);
  ASSERT_GT(s.size(), 60u);
  for (const auto& x : s) {
    EXPECT_TRUE(x.converged);
    EXPECT_DOUBLE_EQ(x.feed, 0.2e-3);
    EXPECT_DOUBLE_EQ(x.deflection, 0.0);
  }
  DrillingData d2(m);
  const DrillingForces F = drillingForcesAtDepth(m, d2, 0.2e-3, 5 * 0.2e-3, 12e-3);
  EXPECT_NEAR(s[4].forces.thrust, F.thrust, 1e-9 * F.thrust);
}

TEST(DrillAxialCoupling, CompliantRobotAbsorbsFeedOnEntryAndLungesAtBreakthrough) {
  const DrillingModel m = model(10, 0.2);
  DrillingData d(m);
  const double c = 0.5e-6;  // 0.5 µm/N: loop gain c ∂Fz/∂f ≈ 2.9 > 1
  const auto s = drillingAxialCoupling(m, d, 0.2e-3, 12e-3, true, c);
  const DrillingForces steady = drillingForces(m, 0.2e-3);
  double max_feed = 0;
  double prev_depth = 0;
  for (size_t k = 0; k < s.size(); ++k) {
    const auto& x = s[k];
    EXPECT_TRUE(x.converged) << x.revolution;
    EXPECT_LE(x.iterations, 10);
    EXPECT_NEAR(x.deflection, c * x.forces.thrust, 0.1e-6);
    max_feed = std::max(max_feed, x.feed);
    if (k + 1 < s.size()) {  // the last revolution is cut short at the exit
      // the tip advances by the actual feed; the spindle advanced (k+1)·f; the difference is the
      // deflection the robot holds
      EXPECT_NEAR(x.depth - prev_depth, x.feed, 1e-15);
      EXPECT_NEAR((k + 1) * 0.2e-3 - x.depth, x.deflection, 1e-12);
    }
    prev_depth = x.depth;
  }
  EXPECT_LT(s[0].feed, 0.7 * 0.2e-3);                        // entry: feed absorbed
  EXPECT_NEAR(s[50].deflection, c * steady.thrust, 0.5e-6);  // steady cut
  EXPECT_NEAR(s[50].feed, 0.2e-3, 1e-7);
  EXPECT_GT(max_feed, 2.0 * 0.2e-3);  // breakthrough lunge
}

}  // namespace
}  // namespace roprec
