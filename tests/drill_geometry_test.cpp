#include "compensator/process/drill_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace roprec {
namespace {

DrillGeometry workedExample() {
  DrillGeometry g;  // docs/process.md §7.1: Dc 10, 2p 118°, δ0 30°, 2w 1.6 (0.16 Dc), ψ 125°
  g.diameter = 10e-3;
  g.point_angle = 118 * kDeg;
  g.helix_angle = 30 * kDeg;
  g.web_thickness = 1.6e-3;
  g.chisel_angle = 125 * kDeg;
  return g;
}

// The quaternion construction (§1.4) against the closed forms (§1.2), whole edge, both lips,
// a spread of seeded random geometries: agreement to 1e-9 rad.
TEST(DrillGeometry, QuaternionFrameMatchesClosedFormAlongTheWholeEdge) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> D(6e-3, 14e-3), pt(90 * kDeg, 150 * kDeg),
      hx(15 * kDeg, 40 * kDeg), web(0.05, 0.25), psi(110 * kDeg, 135 * kDeg);
  double worst = 0;
  for (int k = 0; k < 40; ++k) {
    DrillGeometry g = k == 0 ? workedExample() : DrillGeometry{};
    if (k > 0) {
      g.diameter = D(rng);
      g.point_angle = pt(rng);
      g.helix_angle = hx(rng);
      g.web_thickness = web(rng) * g.diameter;
      g.chisel_angle = psi(rng);
    }
    ASSERT_EQ(drillGeometryProblem(g), "");
    const double a = g.chiselHalfLength();
    const double R = g.radius();
    for (int i = 0; i <= 200; ++i) {
      const double r = a + (R - a) * i / 200.0;
      const EdgeAngles cf = closedFormEdgeAngles(g, r);
      for (int lip = 0; lip < 2; ++lip) {
        const EdgeFrame F = edgeFrame(g, r, lip);
        worst = std::max({worst, std::abs(F.gamma_n - cf.gamma_n),
                          std::abs(std::abs(F.lambda_s) - cf.lambda_s),
                          std::abs(F.kappa_r - cf.kappa_r)});
        EXPECT_LT(F.lambda_s, 0.0 + 1e-15)
            << "the edge trails the velocity going outward (§1.4 step 7)";
      }
    }
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(DrillGeometry, LipTwoIsLipOneTurnedByHalfARevolution) {
  const DrillGeometry g = workedExample();
  for (double r : {1.0e-3, 2.0e-3, 3.3e-3, 5.0e-3}) {
    const EdgeFrame f1 = edgeFrame(g, r, 0, 0.2e-3);
    const EdgeFrame f2 = edgeFrame(g, r, 1, 0.2e-3);
    EXPECT_NEAR(f1.gamma_n, f2.gamma_n, 1e-12);
    EXPECT_NEAR(f1.lambda_s, f2.lambda_s, 1e-12);
    EXPECT_NEAR(f1.kappa_r, f2.kappa_r, 1e-12);
    EXPECT_LT((f1.position.head<2>() + f2.position.head<2>()).norm(), 1e-15);
    EXPECT_NEAR(f1.position.z(), f2.position.z(), 1e-15);
  }
}

// Stabler's rule: the chip-flow direction lies in the rake face and makes the angle |λs| with the
// in-face direction normal to the edge.
TEST(DrillGeometry, ChipFlowFollowsStablersRule) {
  const DrillGeometry g = workedExample();
  for (double r : {1.2e-3, 2.5e-3, 5e-3}) {
    const EdgeFrame F = edgeFrame(g, r, 0);
    EXPECT_NEAR(F.chip_flow.dot(F.n_gamma), 0.0, 1e-12);
    EXPECT_NEAR(F.chip_flow.norm(), 1.0, 1e-12);
    const Vec3 u = F.n_gamma.cross(F.t).normalized();
    EXPECT_NEAR(std::acos(std::abs(F.chip_flow.dot(u))), std::abs(F.lambda_s), 1e-9);
    EXPECT_GT(F.chip_flow.dot(F.helix), 0.0);  // up the flute
  }
}

TEST(DrillGeometry, ZeroWebLimit) {
  DrillGeometry g = workedExample();
  g.web_thickness = 0;
  const double p = g.halfPoint();
  for (double r : {0.5e-3, 2e-3, 5e-3}) {
    const EdgeFrame F = edgeFrame(g, r, 0);
    const double delta = std::atan(r / g.radius() * std::tan(g.helix_angle));
    EXPECT_NEAR(F.gamma_n, std::atan(std::tan(delta) / std::sin(p)), 1e-12);
    EXPECT_NEAR(F.lambda_s, 0.0, 1e-12);
    EXPECT_NEAR(F.kappa_r, p, 1e-12);
  }
}

// h·db = (f/2)·dr where db is the edge element projected on the reference plane Pr (⊥ v):
// computed here from the quaternion frames and two neighbouring edge points.
TEST(DrillGeometry, ChipAreaIdentity) {
  const DrillGeometry g = workedExample();
  const double f = 0.2e-3;
  const double dr = 1e-7;
  for (double r = g.chiselHalfLength() + 1e-6; r < g.radius(); r += 0.37e-3) {
    const EdgeFrame A = edgeFrame(g, r, 0);
    const EdgeFrame B0 = edgeFrame(g, r - 0.5 * dr, 0);
    const EdgeFrame B1 = edgeFrame(g, r + 0.5 * dr, 0);
    const double dl = (B1.position - B0.position).norm();
    const Vec3 t_r = A.t - A.t.dot(A.v) * A.v;
    const double db = t_r.norm() * dl;
    const double h = 0.5 * f * std::sin(A.kappa_r);
    EXPECT_NEAR(h * db / (0.5 * f * dr), 1.0, 1e-6) << "r = " << r;
    EXPECT_NEAR(db, dr / std::sin(A.kappa_r), 1e-6 * dr);
  }
}

// Worked example table of docs/process.md §7.1 (values given to 0.1°) and its regression values.
TEST(DrillGeometry, WorkedExampleRegression) {
  const DrillGeometry g = workedExample();
  EXPECT_NEAR(g.chiselHalfLength(), 0.977e-3, 0.0005e-3);
  struct Row {
    double r_mm, gn, gn_work, lam, kap;
  };
  const Row rows[] = {{1.5, -7.7, -6.6, 27.2, 54.6},
                      {2.5, 8.8, 9.4, 15.9, 57.6},
                      {3.5, 19.0, 19.5, 11.3, 58.3},
                      {5.0, 30.4, 30.7, 7.9, 58.7}};
  for (const Row& row : rows) {
    const EdgeFrame s = edgeFrame(g, row.r_mm * 1e-3, 0);
    const EdgeFrame w = edgeFrame(g, row.r_mm * 1e-3, 0, 0.2e-3);
    EXPECT_NEAR(s.gamma_n / kDeg, row.gn, 0.051) << row.r_mm;
    EXPECT_NEAR(w.gamma_n / kDeg, row.gn_work, 0.051) << row.r_mm;
    EXPECT_NEAR(std::abs(s.lambda_s) / kDeg, row.lam, 0.051) << row.r_mm;
    EXPECT_NEAR(s.kappa_r / kDeg, row.kap, 0.051) << row.r_mm;
  }
  const EdgeFrame inner = edgeFrame(g, g.chiselHalfLength(), 0);
  EXPECT_NEAR(inner.gamma_n / kDeg, -31.7, 0.1);
  EXPECT_NEAR(std::abs(inner.lambda_s) / kDeg, 44.5, 0.15);
  EXPECT_NEAR(inner.kappa_r / kDeg, 43.7, 0.05);
  // §7: γn(R) = 30.37°, λs(R) = 7.88°
  const EdgeFrame corner = edgeFrame(g, g.radius(), 0);
  EXPECT_NEAR(corner.gamma_n / kDeg, 30.37, 0.005);
  EXPECT_NEAR(std::abs(corner.lambda_s) / kDeg, 7.88, 0.005);
  // 140° point, 2w = 2 mm (same δ0): γn and λs at r/R = 0.3 / 0.5 / 0.7 / 1.0
  DrillGeometry c = g;
  c.point_angle = 140 * kDeg;
  c.web_thickness = 2e-3;
  const double gn[] = {-8.8, 7.9, 17.5, 28.2};
  const double ls[] = {38.8, 22.1, 15.6, 10.8};
  const double rr[] = {0.3, 0.5, 0.7, 1.0};
  for (int i = 0; i < 4; ++i) {
    const EdgeFrame F = edgeFrame(c, rr[i] * c.radius(), 0);
    EXPECT_NEAR(F.gamma_n / kDeg, gn[i], 0.051);
    EXPECT_NEAR(std::abs(F.lambda_s) / kDeg, ls[i], 0.051);
  }
}

// Working angle: γne ≈ γn + η_f sin κr / cos λs within 0.05° at f = 0.2 mm (docs/process.md §1.2).
TEST(DrillGeometry, WorkingRakeApproximation) {
  const DrillGeometry g = workedExample();
  const double f = 0.2e-3;
  for (double r = g.chiselHalfLength(); r <= g.radius(); r += 0.25e-3) {
    const EdgeFrame s = edgeFrame(g, r, 0);
    const EdgeFrame w = edgeFrame(g, r, 0, f);
    const double eta = std::atan(f / (2 * kPi * r));
    const double approx = s.gamma_n + eta * std::sin(s.kappa_r) / std::cos(s.lambda_s);
    EXPECT_NEAR(w.gamma_n / kDeg, approx / kDeg, 0.05) << r;
    EXPECT_GT(w.gamma_n, s.gamma_n);
  }
}

// §1.3 table: the proportional laws against the geometry.
TEST(DrillGeometry, PaperProportionalLawTable) {
  const DrillGeometry g = workedExample();
  // the first row is the inner lip end, r/R = a/R = 0.195 ("0.20" in the note's table)
  const double rr[] = {g.chiselHalfLength() / g.radius(), 0.3, 0.5, 0.7, 1.0};
  const double gn[] = {6.5, 10.0, 16.3, 22.3, 30.4};
  const double ls[] = {1.6, 2.4, 4.0, 5.5, 7.9};
  for (int i = 0; i < 5; ++i) {
    const EdgeAngles e = edgeAngles(g, AngleLaw::kPaperProportional, rr[i] * g.radius());
    EXPECT_NEAR(e.gamma_n / kDeg, gn[i], 0.06);
    EXPECT_NEAR(e.lambda_s / kDeg, ls[i], 0.06);
    EXPECT_NEAR(e.kappa_r, g.halfPoint(), 1e-15);
  }
  // Near the web the law keeps a positive rake where the geometry is strongly negative.
  EXPECT_GT(edgeAngles(g, AngleLaw::kPaperProportional, 1.0e-3).gamma_n, 0.0);
  EXPECT_LT(edgeAngles(g, AngleLaw::kGeometric, 1.0e-3).gamma_n, -25 * kDeg);
}

TEST(DrillGeometry, RejectsBadGeometry) {
  DrillGeometry g = workedExample();
  g.point_angle = 55 * kDeg;
  EXPECT_NE(drillGeometryProblem(g).find("point angle"), std::string::npos);
  g.point_angle = 180 * kDeg;
  EXPECT_NE(drillGeometryProblem(g).find("point angle"), std::string::npos);
  g = workedExample();
  g.web_thickness = 11e-3;
  EXPECT_NE(drillGeometryProblem(g).find("wider than the drill"), std::string::npos);
  g.web_thickness = 9e-3;
  EXPECT_NE(drillGeometryProblem(g).find("web is too wide"), std::string::npos);
}

TEST(DrillGeometry, ProblemMessagesUseBoundedNumbers) {
  DrillGeometry g;
  g.point_angle = 1e300;
  std::string why = drillGeometryProblem(g);
  EXPECT_NE(why.find("5.72958e+301"), std::string::npos) << why;  // not 300 digits
  EXPECT_LT(why.size(), 120u) << why;
  g = DrillGeometry{};
  g.web_thickness = 1e300;
  why = drillGeometryProblem(g);
  EXPECT_LT(why.size(), 120u) << why;
  EXPECT_EQ(why.find("nan"), std::string::npos) << why;
}

}  // namespace
}  // namespace roprec
