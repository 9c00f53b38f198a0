#include "compensator/process/milling.hpp"
#include "compensator/process/milling_consistent.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace roprec {
namespace {

MillingCoefficients kienzle800() {
  MillingCoefficients c;  // docs/process.md §7.6 Kienzle column: kc1.1 800, mc 0.25, Fr = 0.35 Ft
  c.kc11 = 800e6;
  c.mc = 0.25;
  c.radial_ratio = 0.35;
  return c;
}

MillingModel model(double ae_mm, double fz_mm, MillingMode mode, double runout_um = 0,
                   int steps = 720) {
  MillingTool t;  // D 10, Nt 3, β 30°
  t.runout = runout_um * 1e-6;
  MillingCut c;
  c.ap = 5e-3;
  c.ae = ae_mm * 1e-3;
  c.fz = fz_mm * 1e-3;
  c.mode = mode;
  return makeMillingModel(t, c, kienzle800(), steps, 20);
}

TEST(Milling, EntryExitAngles) {
  const ImmersionAngles up = immersionAngles(10e-3, 2e-3, MillingMode::kUp);
  EXPECT_NEAR(up.start, 0.0, 1e-15);
  EXPECT_NEAR(up.exit / kDeg, 53.1301, 1e-4);  // acos(0.6)
  const ImmersionAngles dn = immersionAngles(10e-3, 2e-3, MillingMode::kDown);
  EXPECT_NEAR(dn.start / kDeg, 126.8699, 1e-4);
  EXPECT_NEAR(dn.exit, kPi, 1e-15);
  const ImmersionAngles half = immersionAngles(10e-3, 5e-3, MillingMode::kUp);
  EXPECT_NEAR(half.exit, kPi / 2, 1e-15);
  const ImmersionAngles slot = immersionAngles(10e-3, 10e-3, MillingMode::kSlot);
  EXPECT_NEAR(slot.start, 0.0, 1e-15);
  EXPECT_NEAR(slot.exit, kPi, 1e-15);
  // Geometric check: the radial depth covered by the arc is ae (y from R cos φex to R).
  for (double ae : {0.3e-3, 1e-3, 2e-3, 4.9e-3}) {
    const ImmersionAngles a = immersionAngles(10e-3, ae, MillingMode::kUp);
    EXPECT_NEAR(5e-3 - 5e-3 * std::cos(a.exit), ae, 1e-15);
    const ImmersionAngles d = immersionAngles(10e-3, ae, MillingMode::kDown);
    EXPECT_NEAR(5e-3 * std::cos(d.start) + 5e-3, ae, 1e-15);
  }
}

TEST(Milling, MeanChipThicknessFormulaAndLimits) {
  const double fz = 0.1e-3;
  const double D = 10e-3;
  for (double ae : {0.2e-3, 1e-3, 2e-3, 5e-3, 8e-3}) {
    for (MillingMode mode : {MillingMode::kUp, MillingMode::kDown}) {
      const ImmersionAngles a = immersionAngles(D, ae, mode);
      // numerical average of fz sin φ over the arc
      double s = 0;
      const int n = 100000;
      for (int i = 0; i < n; ++i) s += fz * std::sin(a.start + (a.exit - a.start) * (i + 0.5) / n);
      EXPECT_NEAR(meanChipThickness(fz, a), s / n, 1e-12);
      EXPECT_NEAR(meanChipThickness(fz, a), 2 * fz * ae / D / std::acos(1 - 2 * ae / D), 1e-15);
    }
  }
  EXPECT_NEAR(meanChipThickness(fz, immersionAngles(D, D, MillingMode::kSlot)), 2 * fz / kPi,
              1e-18);
  // small-immersion limit fz √(ae/D)
  const double ae = 0.05e-3;
  EXPECT_NEAR(
      meanChipThickness(fz, immersionAngles(D, ae, MillingMode::kUp)) / (fz * std::sqrt(ae / D)),
      1.0, 0.01);
}

// docs/process.md §7.6, Kienzle column: F̄x / F̄y / peak |F| (N), ±1 % (±1.5 N on small components).
TEST(Milling, Section42TableRegression) {
  struct Row {
    MillingMode mode;
    double ae, fz, Fx, Fy, peak;
  };
  const Row rows[] = {
      {MillingMode::kUp, 1, 0.05, -54, 4, 199},    {MillingMode::kUp, 2, 0.10, -162, 41, 500},
      {MillingMode::kUp, 5, 0.10, -292, 213, 714}, {MillingMode::kDown, 2, 0.10, 101, 133, 501},
      {MillingMode::kDown, 5, 0.10, 96, 349, 714}, {MillingMode::kSlot, 10, 0.10, -196, 561, 736}};
  for (const Row& r : rows) {
    const MillingProfile P = millingForceProfile(model(r.ae, r.fz, r.mode));
    EXPECT_NEAR(P.mean.x(), r.Fx, std::max(1.5, 0.01 * std::abs(r.Fx))) << r.ae;
    EXPECT_NEAR(P.mean.y(), r.Fy, std::max(1.5, 0.01 * std::abs(r.Fy))) << r.ae;
    EXPECT_NEAR(P.peak_xy, r.peak, 0.01 * r.peak) << r.ae;
    // The Gauss–Legendre arc average used by the coupling equals the profile mean.
    const MillingModel m = model(r.ae, r.fz, r.mode);
    const Vec3 avg = millingMeanForce(m, m.cut.fz, m.cut.ae);
    EXPECT_NEAR(avg.x(), P.mean.x(), 4e-3 * P.mean.norm());
    EXPECT_NEAR(avg.y(), P.mean.y(), 4e-3 * P.mean.norm());
  }
}

// Power identity F̄t vc = kc(h_m) ap ae vf for the mean-chip law, and the §4.4 size effect:
// +10 % fz → +7.41 % (1.1^0.75), +10 % ae → ≈ 1.1^0.875 for small ae/D.
TEST(Milling, MeanChipLawScaling) {
  MillingModel m = model(2, 0.1, MillingMode::kUp);
  m.mean_law = MeanForceLaw::kMeanChip;
  const Vec3 F0 = millingMeanForce(m, 0.1e-3, 2e-3);
  const Vec3 F1 = millingMeanForce(m, 0.11e-3, 2e-3);
  EXPECT_NEAR(F1.norm() / F0.norm(), std::pow(1.1, 0.75), 1e-12);
  // power: tangential mean over the arc, from Fz = −ca F̄t
  const ImmersionAngles a = immersionAngles(10e-3, 2e-3, MillingMode::kUp);
  const double hm = meanChipThickness(0.1e-3, a);
  const double Ft_bar = -F0.z() / m.coeff.axial_ratio;
  const double n = 1.0;  // rev/s
  const double vc = kPi * 10e-3 * n;
  const double vf = 3 * 0.1e-3 * n;
  const double kc = 800e6 * std::pow(hm / 1e-3, -0.25);
  EXPECT_NEAR(Ft_bar * vc / (kc * 5e-3 * 2e-3 * vf), 1.0, 1e-12);
  MillingModel small = model(0.1, 0.1, MillingMode::kUp);
  small.mean_law = MeanForceLaw::kMeanChip;
  const double r =
      millingMeanForce(small, 0.1e-3, 0.11e-3).z() / millingMeanForce(small, 0.1e-3, 0.1e-3).z();
  EXPECT_NEAR(r, std::pow(1.1, 0.875), 0.002);
}

// Runout: a tooth whose radius is smaller than the previous one's by more than fz sin φ cuts
// nothing, and the next tooth then removes what it left: chip = 2 fz sin φ + (R_j − R_{j−2}).
TEST(Milling, ChipThicknessRemembersWhatThePreviousEdgeDidNotCut) {
  MillingTool t;
  t.teeth = 3;
  t.runout = 0.06e-3;
  t.runout_angle = 0.0;  // R_0 = R + ρ, R_1 = R_2 = R − ρ/2
  MillingCut c;
  c.fz = 0.05e-3;
  c.ae = 10e-3;
  c.mode = MillingMode::kSlot;
  const MillingModel m = makeMillingModel(t, c, kienzle800());
  const double phi = 80 * kDeg;
  const double s = std::sin(phi);
  const double R0 = m.tooth_radius[0], R1 = m.tooth_radius[1], R2 = m.tooth_radius[2];
  // tooth 0 (largest): chip from tooth 2 is fz s + R0 − R2
  EXPECT_NEAR(toothChipThickness(m, 0, phi, c.fz), c.fz * s + R0 - R2, 1e-15);
  // tooth 1: fz s + R1 − R0 = 0.0492 − 0.09 < 0 → no chip
  EXPECT_LT(c.fz * s + R1 - R0, 0.0);
  EXPECT_DOUBLE_EQ(toothChipThickness(m, 1, phi, c.fz), 0.0);
  // tooth 2: against tooth 1 it would be fz s (R2 = R1) but tooth 1 did not cut: against tooth 0,
  // 2 fz s + R2 − R0, which is smaller and therefore the real surface.
  EXPECT_NEAR(toothChipThickness(m, 2, phi, c.fz), 2 * c.fz * s + R2 - R0, 1e-15);
  // Over one revolution the teeth share exactly Nt·fz of feed on average: the max chips reflect it.
  const MillingProfile P = millingForceProfile(m);
  EXPECT_DOUBLE_EQ(P.max_chip[1], 0.0);
  // Deflection history: a tool that moved by δ along n(φ) since the last pass cuts δ more.
  const Eigen::Vector2d hist[4] = {Eigen::Vector2d(std::sin(phi), std::cos(phi)) * 2e-6,
                                   Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(),
                                   Eigen::Vector2d::Zero()};
  EXPECT_NEAR(toothChipThickness(m, 0, phi, c.fz, hist), c.fz * s + R0 - R2 + 2e-6, 1e-15);
}

// Small runout (every tooth still cuts, Kline & DeVor 1983): in a slot the largest chip of tooth j
// over the revolution is fz + R_j − R_{j−1} at φ = 90° (the chips sum to Nt·fz).
TEST(Milling, SmallRunoutRedistributesTheChipsBetweenTeeth) {
  MillingTool t;
  t.teeth = 4;
  t.helix_angle = 0.0;
  t.runout = 0.01e-3;
  t.runout_angle = 20 * kDeg;
  MillingCut c;
  c.fz = 0.1e-3;
  c.ae = 10e-3;
  c.mode = MillingMode::kSlot;
  const MillingModel m = makeMillingModel(t, c, kienzle800(), 3600, 1);
  const MillingProfile P = millingForceProfile(m);
  double sum = 0;
  for (int j = 0; j < 4; ++j) {
    const double expect = c.fz + m.tooth_radius[static_cast<size_t>(j)] -
                          m.tooth_radius[static_cast<size_t>((j + 3) % 4)];
    EXPECT_NEAR(P.max_chip[static_cast<size_t>(j)], expect, 1e-9) << j;
    sum += P.max_chip[static_cast<size_t>(j)];
  }
  EXPECT_NEAR(sum, 4 * c.fz, 1e-9);
  // The largest tooth sets the peak: above the runout-free peak of the same cut.
  MillingTool t0 = t;
  t0.runout = 0.0;
  EXPECT_GT(P.peak_xy, millingForceProfile(makeMillingModel(t0, c, kienzle800(), 3600, 1)).peak_xy);
}

CouplingResult steadyPoint(const MillingModel& m, const Mat3& C, const CouplingOptions& o,
                           int points = 8) {
  const std::vector<ComplianceFunction> path(static_cast<size_t>(points), linearCompliance(C));
  return coupleMillingPath(m, path, o).back();
}

// §4.4 typical case: up-milling ae 2, fz 0.1, robot compliance 0.5–2 µm/N → loop gain 0.04–0.15,
// converges (0.1 µm) in ≤ 10 iterations at every path point.
TEST(Milling, CoupledIterationConvergesForTypicalCases) {
  for (MillingMode mode : {MillingMode::kUp, MillingMode::kDown}) {
    for (double c_um : {0.5, 1.0, 2.0}) {
      const MillingModel m = model(2, 0.1, mode);
      const Mat3 C = Mat3::Identity() * c_um * 1e-6;
      const std::vector<ComplianceFunction> path(12, linearCompliance(C));
      const std::vector<CouplingResult> res = coupleMillingPath(m, path, CouplingOptions{});
      for (const CouplingResult& r : res) {
        EXPECT_TRUE(r.converged) << c_um;
        EXPECT_LE(r.iterations, 10);
        EXPECT_LE(r.residual, 0.1e-6);
        EXPECT_LT(r.loop_gain, 0.3);
      }
      // Fixed point: δ = C F(δ) at the converged point.
      const CouplingResult& last = res.back();
      EXPECT_LT((last.delta - C * last.force).norm(), 0.2e-6);
      // The wall-normal loop gain alone is c · ∂F/∂ae ≈ c · F(1−mc/2)/ae (order of §4.4's
      // 0.04–0.15).
      EXPECT_GT(last.loop_gain, 0.01);
    }
  }
}

CouplingOptions fixedPoint(double relaxation = 1.0, int max_iterations = 50) {
  CouplingOptions o;
  o.method = CouplingMethod::kFixedPoint;
  o.relaxation = relaxation;
  o.max_iterations = max_iterations;
  return o;
}

double dFyDae(const MillingModel& m) {
  return (millingMeanForce(m, 0.1e-3, 2.001e-3).y() - millingMeanForce(m, 0.1e-3, 1.999e-3).y()) /
         2e-6;
}

// Up-milling, compliance along Y with gain 0.5 (positive feedback): both solvers converge to the
// same point; the plain iteration needs many more steps.
TEST(Milling, NewtonAndPlainIterationAgreeBelowGainOne) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp);
  Mat3 C = Mat3::Zero();
  C(1, 1) = 0.5 / dFyDae(m);
  const CouplingResult plain =
      coupleMillingPoint(m, linearCompliance(C), CouplingState{}, fixedPoint(1.0, 200));
  const CouplingResult newton = coupleMillingPoint(m, linearCompliance(C), CouplingState{});
  ASSERT_TRUE(plain.converged);
  ASSERT_TRUE(newton.converged);
  EXPECT_LT(newton.loop_gain, 1.0);
  EXPECT_LE(newton.residual, 0.1e-6);
  EXPECT_LT(newton.iterations, plain.iterations);
  EXPECT_LT((newton.delta - plain.delta).norm(), 0.5e-6);
}

// The mean-force memo returns millingMeanForce's own bits, also after its 8 entries were
// replaced (eviction) and after reset().
TEST(Milling, MeanForceMemoReturnsTheSameBits) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp, 5);
  MeanForceMemo memo;
  for (int round = 0; round < 3; ++round) {
    for (int k = 0; k < 12; ++k) {
      const double fz = (0.05 + 0.01 * k) * 1e-3;
      const double ae = (1.5 + 0.1 * (k % 5)) * 1e-3;
      const Vec3 direct = millingMeanForce(m, fz, ae);
      EXPECT_EQ(memo(m, fz, ae), direct) << k;
      EXPECT_EQ(memo(m, fz, ae), direct) << k;  // remembered
    }
    if (round == 1) memo.reset();
  }
}

// A solve with the memo and without the loop gain has the same δ, force and iterations as the
// plain solve, and couplingLoopGain gives the plain solve's loop gain to the bit (Newton, runout,
// the path's memory).
TEST(Milling, LoopGainAfterTheSolveIsTheSolvesOwn) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp, 5);
  Mat3 C = Mat3::Zero();
  C(1, 1) = 0.5 / dFyDae(m);
  const ComplianceFunction f = linearCompliance(C);
  CouplingState st;
  st.delta_prev = Vec3(3e-6, 1e-6, 0);
  const CouplingResult plain = coupleMillingPoint(m, f, st);
  ASSERT_TRUE(plain.converged) << couplingStatusName(plain.status);
  ASSERT_GE(plain.iterations, 1);
  CouplingOptions o;
  o.loop_gain = false;
  MeanForceMemo memo;
  for (int k = 0; k < 2; ++k) {  // the second solve starts with a filled memo
    const CouplingResult r = coupleMillingPoint(m, f, st, o, &memo);
    EXPECT_EQ(r.delta, plain.delta);
    EXPECT_EQ(r.force, plain.force);
    EXPECT_EQ(r.force_nominal, plain.force_nominal);
    EXPECT_EQ(r.iterations, plain.iterations);
    EXPECT_EQ(r.loop_gain, 0.0);
    EXPECT_EQ(couplingLoopGain(m, f, st, o, r, &memo), plain.loop_gain);
    EXPECT_EQ(couplingLoopGain(m, f, st, o, r), plain.loop_gain);
  }
  EXPECT_GT(plain.loop_gain, 0.3);
}

// An oscillating loop (negative feedback, gain 1.4, down-milling pushed away from the wall): the
// plain iteration fails, under-relaxation ω = 0.3 rescues it, Newton converges directly to the
// same static equilibrium δ = C F(δ).
TEST(Milling, OscillatingLoopPlainFailsNewtonConverges) {
  const MillingModel m = model(2, 0.1, MillingMode::kDown);
  Mat3 C = Mat3::Zero();
  C(1, 1) = 1.4 / std::abs(dFyDae(m));
  const CouplingResult plain =
      coupleMillingPoint(m, linearCompliance(C), CouplingState{}, fixedPoint());
  EXPECT_FALSE(plain.converged);
  const CouplingResult relaxed =
      coupleMillingPoint(m, linearCompliance(C), CouplingState{}, fixedPoint(0.3, 300));
  EXPECT_TRUE(relaxed.converged);
  const CouplingResult newton = coupleMillingPoint(m, linearCompliance(C), CouplingState{});
  ASSERT_TRUE(newton.converged) << couplingStatusName(newton.status);
  EXPECT_GT(newton.loop_gain, 1.0);
  EXPECT_LE(newton.iterations, 10);
  EXPECT_LT((newton.delta - C * newton.force).norm(), 0.1e-6);
  EXPECT_LT((relaxed.delta - newton.delta).norm(), 1e-6);
}

// ---- independent reference: the revolution-mean Kienzle force by composite midpoint quadrature
// of the instantaneous law (written here, not the library's Gauss–Legendre), and the fixed point
// by nested bisection.

/// (1/2π) Σ_j ∫ over [φst, φex] of kc1.1 ap h0 (h_j/h0)^(1−mc) (−cos φ − cr sin φ,
/// sin φ − cr cos φ, −ca) dφ with tooth j's chip h_j = min_k [k fz sin φ + R_j − R_{j−k}] (the full
/// memory of the earlier teeth, R_j = R + ρ cos(j 2π/3)); chips below h_min are not cut.
Vec3 referenceMeanForce(MillingMode mode, double fz, double ae, double ap = 5e-3,
                        double runout = 0) {
  if (!(fz > 0) || !(ae > 0)) return Vec3::Zero();
  const double D = 10e-3, kc = 800e6, mc = 0.25, cr = 0.35, ca = 0.2, hmin = 2e-6;
  const double arc = std::acos(1.0 - 2.0 * std::min(ae, D) / D);
  const double a = mode == MillingMode::kUp ? 0.0 : kPi - arc;
  const double b = mode == MillingMode::kUp ? arc : kPi;
  const int n = 6000;
  double R[3];
  for (int j = 0; j < 3; ++j) R[j] = runout * std::cos(j * 2 * kPi / 3);
  Vec3 F = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < n; ++i) {
      const double phi = a + (b - a) * (i + 0.5) / n;
      double h = 1e9;
      for (int k = 1; k <= 3; ++k)
        h = std::min(h, k * fz * std::sin(phi) + R[j] - R[(j + 3 - k) % 3]);
      if (h < hmin) continue;
      const double Ft = kc * ap * 1e-3 * std::pow(h / 1e-3, 1.0 - mc) * (b - a) / n;
      F += Vec3(-Ft * std::cos(phi) - cr * Ft * std::sin(phi),
                Ft * std::sin(phi) - cr * Ft * std::cos(phi), -ca * Ft);
    }
  }
  return F / (2.0 * kPi);
}

/// Bisection for the root of an increasing function on [lo, hi].
template <class G>
double bisect(const G& g, double lo, double hi) {
  for (int i = 0; i < 45; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

/// δ = diag(c) F(fz + δx/n, ae + δ·n_wall, ap − δz) with δ_{i−1} = 0: outer bisection on δy,
/// inner on δx (both residuals increase monotonically: the feedback is negative in X for Fx < 0,
/// and in Y for down-milling; for up-milling the Y gain is kept below 1); δz in closed form (F is
/// linear in ap: δz = cz Fz(ap − δz)/ap).
struct ReferencePoint {
  Vec3 delta, force;
};
ReferencePoint referenceFixedPoint(MillingMode mode, const Vec3& c, int n, double runout,
                                   double dprev_x = 0, double uncut = 0) {
  const double wall = mode == MillingMode::kUp ? 1.0 : -1.0;
  const double ap = 5e-3;
  const auto forceAt = [&](double dx, double dy) {
    const Vec3 F1 =
        referenceMeanForce(mode, 0.1e-3 + (dx - dprev_x) / n + uncut, 2e-3 + wall * dy, ap, runout);
    const double dz = c.z() * F1.z() / (1 + c.z() * F1.z() / ap);
    return Vec3(F1 * ((ap - dz) / ap));
  };
  const auto deltaX = [&](double dy) {
    return bisect([&](double dx) { return dx - c.x() * forceAt(dx, dy).x(); }, -2e-3, 2e-3);
  };
  const double dy =
      bisect([&](double y) { return y - c.y() * forceAt(deltaX(y), y).y(); }, -1.9e-3, 1.9e-3);
  const double dx = deltaX(dy);
  const Vec3 F = forceAt(dx, dy);
  return {Vec3(dx, dy, c.z() * F.z()), F};
}

// The coupled solve against the independent reference (with the ap feedback; the last two cases
// with runout and a soft Z): δ and F within 0.5 % (of |δ|, |F|), for a
// robot-like compliance (gain < 1) and soft ones with negative feedback (gain > 1, where the plain
// iteration fails): up-milling soft along the feed (Fx < 0: the deflection lowers fz), down-milling
// soft along the wall normal (the deflection lowers ae).
TEST(Milling, FixedPointMatchesIndependentKienzleQuadrature) {
  struct Case {
    MillingMode mode;
    Vec3 c_um_per_N;
    bool soft;
    double runout_um;
  };
  const Case cases[] = {
      {MillingMode::kUp, {2, 1, 0.5}, false, 0}, {MillingMode::kDown, {2, 1, 0.5}, false, 0},
      {MillingMode::kUp, {60, 3, 1}, true, 0},   {MillingMode::kDown, {2, 30, 1}, true, 0},
      {MillingMode::kUp, {2, 1, 20}, false, 5},  {MillingMode::kDown, {2, 1, 20}, false, 10}};
  for (const Case& k : cases) {
    const MillingModel m = model(2, 0.1, k.mode, k.runout_um);
    const Vec3 c = k.c_um_per_N * 1e-6;
    const Mat3 C = c.asDiagonal();
    CouplingOptions o;
    o.teeth_between_points = 10;
    const CouplingResult r = coupleMillingPoint(m, linearCompliance(C), CouplingState{}, o);
    ASSERT_TRUE(r.converged) << couplingStatusName(r.status);
    EXPECT_LE(r.residual, o.tolerance);
    const ReferencePoint ref = referenceFixedPoint(k.mode, c, 10, k.runout_um * 1e-6);
    EXPECT_LE((r.delta - ref.delta).norm(), 0.005 * ref.delta.norm())
        << r.delta.transpose() << " | " << ref.delta.transpose();
    EXPECT_LE((r.force - ref.force).norm(), 0.005 * ref.force.norm())
        << r.force.transpose() << " | " << ref.force.transpose();
    EXPECT_NEAR(r.ap_effective, 5e-3 - r.delta.z(), 1e-12);
    if (k.soft) {
      EXPECT_GT(r.loop_gain, 1.0);
      const CouplingResult plain =
          coupleMillingPoint(m, linearCompliance(C), CouplingState{}, fixedPoint());
      EXPECT_FALSE(plain.converged) << "plain iteration at loop gain " << r.loop_gain;
    }
  }
}

// The path's memory in the coupled solve: the previous point's deflection δ_{i−1} (the feed term
// (δ − δ_{i−1})·X/n) and the chip the previous edge left (δprev), with the ap feedback (soft Z)
// and runout, against the independent quadrature + nested bisection with the same memory: δ and F
// within 0.5 %. The edge-consistent solve without modes (its law is the rigid revolution's mean,
// 360 samples) agrees with the same reference; the memory moves the fixed point by far more
// than the tolerance (the test can fail).
TEST(Milling, FixedPointWithThePathsMemoryMatchesIndependentQuadrature) {
  struct Case {
    MillingMode mode;
    double runout_um, dprev_x_um, uncut_um;
  };
  for (const Case& k : {Case{MillingMode::kUp, 5, -40, -20}, Case{MillingMode::kDown, 10, 30, -30},
                        Case{MillingMode::kUp, 0, 60, 0}}) {
    const MillingModel m = model(2, 0.1, k.mode, k.runout_um, 360);
    const Vec3 c = Vec3(2, 1, 20) * 1e-6;
    CouplingOptions o;
    o.teeth_between_points = 4;
    CouplingState st;
    st.delta_prev = Vec3(k.dprev_x_um * 1e-6, 3e-6, -2e-6);
    st.uncut_prev = k.uncut_um * 1e-6;
    const ComplianceFunction C = linearCompliance(c.asDiagonal());
    const CouplingResult r = coupleMillingPoint(m, C, st, o);
    ASSERT_TRUE(r.converged) << couplingStatusName(r.status);
    const ReferencePoint ref =
        referenceFixedPoint(k.mode, c, 4, k.runout_um * 1e-6, st.delta_prev.x(), st.uncut_prev);
    const ReferencePoint fresh = referenceFixedPoint(k.mode, c, 4, k.runout_um * 1e-6);
    EXPECT_GT((ref.force - fresh.force).norm(), 0.03 * ref.force.norm());
    EXPECT_LE((r.delta - ref.delta).norm(), 0.005 * ref.delta.norm())
        << r.delta.transpose() << " | " << ref.delta.transpose();
    EXPECT_LE((r.force - ref.force).norm(), 0.005 * ref.force.norm())
        << r.force.transpose() << " | " << ref.force.transpose();
    const EdgeRevolutionFunction rigid = [&](double fz, double ae, double ap) {
      return edgeRevolution(m, ModalModel{}, fz, ae, ap);
    };
    const ConsistentCoupling e = coupleMillingPointConsistent(m, C, rigid, st, o);
    ASSERT_TRUE(e.converged()) << e.rounds << " " << e.edge_residual;
    EXPECT_LE(e.edge_residual, o.tolerance);
    EXPECT_LE((e.point.delta - ref.delta).norm(), 0.005 * ref.delta.norm());
    EXPECT_LE((e.point.force - ref.force).norm(), 0.005 * ref.force.norm());
    EXPECT_LT((e.point.force - e.edges.mean).norm(), 1e-12);
  }
}

// The warm start of a path's next point (the previous point's δ and G, as the milling path's
// uncompensated chain does) against cold solves from the same memory, along 20 points whose
// compliance drifts, one tooth pass apart (loop gain above 1: the plain iteration diverges): each
// warm solve ends at |r| <= tolerance / 10⁴, at the cold fixed point within what the residuals
// allow, ‖(I − G)⁻¹‖ (|r_warm| + |r_cold|), and the last one agrees with the independent
// quadrature + bisection (0.5 %); the warm path needs under half the compliance evaluations.
TEST(Milling, WarmStartedSolvesReachTheColdFixedPointsWithFewerEvaluations) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp, 5, 360);
  CouplingOptions o;
  o.teeth_between_points = 1;
  CouplingState st;
  std::optional<Mat3> gain;
  int cold_evaluations = 0;
  int warm_evaluations = 0;
  Vec3 c = Vec3::Zero();
  for (int i = 0; i < 20; ++i) {
    c = Vec3(2, 1, 20) * 1e-6 * (1 + 0.01 * i);
    const ComplianceFunction C = linearCompliance(c.asDiagonal());
    const CouplingResult cold = coupleMillingPoint(m, C, st, o);
    ASSERT_TRUE(cold.converged) << i << " " << couplingStatusName(cold.status);
    ASSERT_TRUE(cold.gain.has_value());
    EXPECT_GT(cold.loop_gain, 1.0);
    cold_evaluations += cold.evaluations;
    if (gain) {
      CouplingOptions warm_options = o;
      warm_options.start = st.delta_prev;
      warm_options.start_gain = gain;
      const CouplingResult warm = coupleMillingPoint(m, C, st, warm_options);
      ASSERT_TRUE(warm.converged) << i << " " << couplingStatusName(warm.status);
      EXPECT_LE(warm.residual, 1e-4 * o.tolerance) << i;
      const double bound =
          (Mat3::Identity() - *cold.gain).inverse().norm() * (warm.residual + cold.residual);
      EXPECT_LE((warm.delta - cold.delta).norm(), bound) << i;
      EXPECT_LE(warm.iterations, cold.iterations) << i;
      warm_evaluations += warm.evaluations;
      if (i == 19) {
        const ReferencePoint ref =
            referenceFixedPoint(MillingMode::kUp, c, 1, 5e-6, st.delta_prev.x(), st.uncut_prev);
        EXPECT_LE((warm.delta - ref.delta).norm(), 0.005 * ref.delta.norm())
            << warm.delta.transpose() << " | " << ref.delta.transpose();
        EXPECT_LE((warm.force - ref.force).norm(), 0.005 * ref.force.norm());
      }
    } else {
      warm_evaluations += cold.evaluations;
    }
    gain = cold.gain;
    st = cold.next;
  }
  EXPECT_LT(2 * warm_evaluations, cold_evaluations) << warm_evaluations << " " << cold_evaluations;
}

// Genuinely non-convergent cases are values, never a throw, NaN or inf: (1) up-milling pulled into
// the wall so hard that the only fixed point lies beyond ae = D; (2) a runaway feed (fz_eff > 0.2
// D); (3) a compliance with a jump and no fixed point; (4) a compliance that fails (throws).
TEST(Milling, NonConvergenceIsReportedAsAStatus) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp);
  const auto finite = [](const CouplingResult& r) {
    return r.delta.allFinite() && r.force.allFinite() && std::isfinite(r.residual) &&
           std::isfinite(r.loop_gain) && std::isfinite(r.fz_effective) &&
           std::isfinite(r.ae_effective);
  };
  Mat3 C = Mat3::Zero();
  C(1, 1) = 5.0 / dFyDae(m);
  const CouplingResult pulled = coupleMillingPoint(m, linearCompliance(C), CouplingState{});
  EXPECT_FALSE(pulled.converged);
  EXPECT_TRUE(pulled.status == CouplingStatus::kOutOfRange ||
              pulled.status == CouplingStatus::kNoDescent)
      << couplingStatusName(pulled.status);
  EXPECT_TRUE(finite(pulled));
  // down-milling (F̄x > 0) on a robot 60 µm/N soft along the feed: the deflection raises fz, which
  // raises F̄x (positive feedback, gain ≈ 4): no physical fixed point (the model's one is a runaway
  // fz_eff > 0.2 D); reported as out of range or no descent.
  const MillingModel dm = model(2, 0.1, MillingMode::kDown);
  const CouplingResult runaway = coupleMillingPoint(
      dm, linearCompliance(Vec3(60e-6, 1e-6, 0.5e-6).asDiagonal()), CouplingState{});
  EXPECT_FALSE(runaway.converged);
  EXPECT_TRUE(runaway.status == CouplingStatus::kOutOfRange ||
              runaway.status == CouplingStatus::kNoDescent)
      << couplingStatusName(runaway.status);
  EXPECT_TRUE(finite(runaway));
  const ComplianceFunction jump = [](const Vec3& F) {
    return Vec3(0, F.y() > 41.0 ? -20e-6 : 20e-6, 0);  // the wall-normal force crosses 41 N
  };
  const CouplingResult none = coupleMillingPoint(m, jump, CouplingState{});
  EXPECT_FALSE(none.converged);
  EXPECT_NE(none.status, CouplingStatus::kConverged);
  EXPECT_GT(none.residual, 1e-6);
  EXPECT_TRUE(finite(none));
  const ComplianceFunction failing = [](const Vec3&) -> Vec3 {
    throw std::runtime_error("equilibrium did not converge");
  };
  const CouplingResult failed = coupleMillingPoint(m, failing, CouplingState{});
  EXPECT_EQ(failed.status, CouplingStatus::kComplianceFailed);
  EXPECT_TRUE(finite(failed));
}

// Up- vs down-milling (docs/process.md §4.4): the mean wall-normal force F̄·n_wall is > 0 in
// up-milling (F̄y > 0, n_wall = +Y) and < 0 in down-milling (F̄y > 0, n_wall = −Y), so with an
// isotropic compliance c the deflection raises ae in up-milling (pulled into the wall) and lowers
// it in down-milling (pushed away): Δae = c F̄y·(±1), the corrected force grows resp. shrinks,
// and |Δae| grows with c.
TEST(Milling, UpMillingPullsIntoTheWallDownMillingPushesAway) {
  for (double ae : {1.0, 2.0, 4.0}) {
    double last_up = 0;
    double last_down = 0;
    for (double c_um : {0.5, 1.0, 2.0, 4.0}) {
      const Mat3 C = Mat3::Identity() * c_um * 1e-6;
      const MillingModel up = model(ae, 0.1, MillingMode::kUp);
      const MillingModel down = model(ae, 0.1, MillingMode::kDown);
      ASSERT_GT(millingMeanForce(up, 0.1e-3, ae * 1e-3).y(), 0.0);
      ASSERT_GT(millingMeanForce(down, 0.1e-3, ae * 1e-3).y(), 0.0);
      const CouplingResult u = steadyPoint(up, C, CouplingOptions{});
      const CouplingResult d = steadyPoint(down, C, CouplingOptions{});
      ASSERT_TRUE(u.converged && d.converged);
      const double dae_up = u.ae_effective - ae * 1e-3;
      const double dae_down = d.ae_effective - ae * 1e-3;
      EXPECT_GT(dae_up, 0.0) << ae << " " << c_um;
      EXPECT_LT(dae_down, 0.0) << ae << " " << c_um;
      EXPECT_NEAR(dae_up, u.delta.y(), 1e-12);
      EXPECT_NEAR(dae_down, -d.delta.y(), 1e-12);
      EXPECT_NEAR(u.delta.y(), c_um * 1e-6 * u.force.y(), 0.1e-6);
      EXPECT_NEAR(d.delta.y(), c_um * 1e-6 * d.force.y(), 0.1e-6);
      EXPECT_GT(u.force.norm(), u.force_nominal.norm());
      EXPECT_LT(d.force.norm(), d.force_nominal.norm());
      EXPECT_GT(dae_up, last_up);
      EXPECT_LT(dae_down, last_down);
      last_up = dae_up;
      last_down = dae_down;
    }
  }
}

// The corrected revolution: the nominal column is the rigid profile, the corrected one the profile
// at (fz_eff, ae_eff) whose mean is the coupled mean force (±0.4 %), and the TCP movement is the
// coupled static deflection plus the periodic response of the modal model: with no modes it is the
// static deflection at every angle; with one stiff mode (fn 500 kHz, far above the harmonics) it
// approaches the quasi-static C (F(φ) − F̄) around it (1 % of the vibration's range).
TEST(Milling, CorrectedRevolution) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp);
  const Mat3 C = Vec3(2e-6, 1e-6, 0.5e-6).asDiagonal();
  const CouplingResult r = steadyPoint(m, C, CouplingOptions{});
  ASSERT_TRUE(r.converged);
  const CorrectedRevolution rev = correctedRevolution(m, ModalModel{}, r);
  const MillingProfile P = millingForceProfile(m);
  ASSERT_EQ(rev.samples.size(), P.samples.size());
  Vec3 mean = Vec3::Zero();
  for (size_t i = 0; i < P.samples.size(); ++i) {
    EXPECT_LT((rev.samples[i].nominal - P.samples[i].force).norm(), 1e-9);
    EXPECT_EQ(rev.samples[i].tcp_movement, r.delta);
    mean += rev.samples[i].corrected;
  }
  mean /= static_cast<double>(P.samples.size());
  EXPECT_LT((mean - r.force).norm(), 4e-3 * r.force.norm());
  EXPECT_EQ(rev.movement_range, 0.0);

  ModalModel stiff;
  ToolModeSpec t;
  t.frequency_hz = 500000;
  t.stiffness = 1e6;  // 1 um/N in X and Y
  t.damping_ratio = 0.02;
  addToolMode(stiff, t);
  const CorrectedRevolution q = correctedRevolution(m, stiff, r);
  ASSERT_EQ(q.samples.size(), P.samples.size());
  Vec3 fmean = Vec3::Zero();
  for (const CorrectedSample& s : q.samples) fmean += s.corrected;
  fmean /= static_cast<double>(q.samples.size());
  for (const CorrectedSample& s : q.samples) {
    const Vec3 quasi =
        r.delta + 1e-6 * Vec3(s.corrected.x() - fmean.x(), s.corrected.y() - fmean.y(), 0.0);
    EXPECT_LT((s.tcp_movement - quasi).norm(), 0.01 * q.vibration_peak_to_peak.norm());
  }
  EXPECT_GT(q.vibration_peak_to_peak.norm(), 1e-6);
}

// Qualitative (paper): the deviation grows with the feed because the force does.
TEST(Milling, DeflectionGrowsWithFeed) {
  double last = 0;
  for (double fz : {0.03, 0.05, 0.08, 0.1, 0.15}) {
    const CouplingResult r =
        steadyPoint(model(2, fz, MillingMode::kUp), Mat3::Identity() * 1e-6, CouplingOptions{});
    ASSERT_TRUE(r.converged);
    EXPECT_GT(r.delta.norm(), last);
    last = r.delta.norm();
  }
}

// The feed term: a deflection along the feed that grows between points raises fz_i; the uncut
// remainder δprev of a tooth that did not reach the surface is carried to the next point.
TEST(Milling, FeedTermAndUncutCarry) {
  const MillingModel m = model(2, 0.1, MillingMode::kUp);
  const auto zero = [](const Vec3&) { return Vec3::Zero(); };
  CouplingOptions o;
  o.teeth_between_points = 1;  // path points one tooth apart
  CouplingState st;
  st.delta_prev = Vec3(-0.15e-3, 0, 0);  // the previous point lagged 0.15 mm along the feed
  const CouplingResult r = coupleMillingPoint(m, zero, st, o);
  EXPECT_NEAR(r.fz_effective, 0.1e-3 + 0.15e-3, 1e-15);
  st.delta_prev = Vec3(0.15e-3, 0, 0);  // it ran ahead: this tooth misses the surface
  const CouplingResult miss = coupleMillingPoint(m, zero, st, o);
  EXPECT_NEAR(miss.fz_effective, -0.05e-3, 1e-15);
  EXPECT_EQ(miss.force.norm(), 0.0);
  EXPECT_NEAR(miss.next.uncut_prev, -0.05e-3, 1e-15);
  const CouplingResult after = coupleMillingPoint(m, zero, miss.next, o);
  EXPECT_NEAR(after.fz_effective, 0.05e-3, 1e-15);  // x_{i+1} − s = 0.2 − 0.15 mm
}

// ---- the revolution resolved by edge angle (edgeRevolution)

/// A tool mode in X and Y (k [N/µm], f [Hz], ζ).
ModalModel toolMode(double k_N_per_um, double f_hz, double zeta) {
  ModalModel d;
  ToolModeSpec t;
  t.stiffness = k_N_per_um * 1e6;
  t.frequency_hz = f_hz;
  t.damping_ratio = zeta;
  addToolMode(d, t);
  return d;
}

// Without modes the resolved revolution is the rigid profile (millingForceProfile) at the same
// cut, each tooth's chip-area feed is fz without runout (to 1e-12 relative) and, with runout,
// differs per tooth by about the radius step while the teeth together remove Nt·fz.
TEST(Milling, EdgeRevolutionWithoutModesIsTheRigidProfile) {
  for (double runout_um : {0.0, 10.0}) {
    const MillingModel m = model(2, 0.1, MillingMode::kUp, runout_um, 360);
    const MillingProfile P = millingForceProfile(m);
    const EdgeRevolution r = edgeRevolution(m, ModalModel{}, 0.1e-3, 2e-3, 5e-3);
    ASSERT_TRUE(r.converged);
    ASSERT_EQ(r.force.size(), P.samples.size());
    for (size_t i = 0; i < r.force.size(); ++i)
      EXPECT_LT((r.force[i] - P.samples[i].force).norm(), 1e-9) << i;
    EXPECT_LT((r.mean - P.mean).norm(), 1e-9);
    double sum = 0;
    for (int j = 0; j < 3; ++j) {
      const double fj = r.tooth_feed[static_cast<size_t>(j)];
      sum += fj;
      if (runout_um == 0) {
        EXPECT_NEAR(fj, 0.1e-3, 1e-16);
      }
      EXPECT_NEAR(r.max_chip[static_cast<size_t>(j)], P.max_chip[static_cast<size_t>(j)], 1e-15);
    }
    EXPECT_NEAR(sum / 3, 0.1e-3, 1e-9);
    if (runout_um > 0) {
      const auto [lo, hi] = std::minmax_element(r.tooth_feed.begin(), r.tooth_feed.end());
      EXPECT_GT(*hi - *lo, 10e-6);  // the runout signature: the radius steps are ±15 µm
    }
  }
}

/// Independent reference: the regenerative cut marched in time. The tool centre is one mode in X
/// and one in Y (m ẍ + c ẋ + k x = F), integrated by RK4 on a grid 10× finer than the revolution's
/// samples with the force held over each step; every tooth's chip is computed against the tool
/// positions stored one, two, … tooth periods earlier (the surface the previous edges left); the
/// run starts at rest and lasts 40 revolutions (the transient decays as e^(−ζωt), < 1e-9 after 15).
/// Returns the force and dynamic displacement (mean removed) at the revolution's samples.
struct TimeDomainRevolution {
  std::vector<Vec3> force, vibration;
  Vec3 mean{Vec3::Zero()};  ///< the static deflection (the coupling's δ)
};
TimeDomainRevolution timeDomainRevolution(const MillingModel& m, double k, double f_hz, double zeta,
                                          int samples) {
  const int Nt = m.tool.teeth, sub = 10, Nf = samples * sub;
  const double wn = 2 * kPi * f_hz, mass = k / (wn * wn), c = 2 * zeta * std::sqrt(k * mass);
  const double Omega = 2 * kPi * m.cut.spindle_rpm / 60.0, dt = 2 * kPi / Omega / Nf;
  const double R = 0.5 * m.tool.diameter, e = 1.0 - m.coeff.mc;
  const double wall = m.cut.mode == MillingMode::kUp ? 1.0 : -1.0;
  std::vector<Eigen::Vector2d> hist(static_cast<size_t>(Nf), Eigen::Vector2d::Zero());
  Eigen::Vector4d s = Eigen::Vector4d::Zero();  // x, y, vx, vy
  const auto force = [&](long step, const Eigen::Vector2d& x) {
    const double ae = std::clamp(m.cut.ae + wall * x.y(), 0.0, m.tool.diameter);
    const double arc = std::acos(1.0 - 2.0 * ae / m.tool.diameter);
    const double a = m.cut.mode == MillingMode::kUp ? 0.0 : kPi - arc;
    const double b = m.cut.mode == MillingMode::kUp ? arc : kPi;
    const double dz = m.cut.ap / m.slices;
    Vec3 F = Vec3::Zero();
    for (int j = 0; j < Nt; ++j) {
      for (int sl = 0; sl < m.slices; ++sl) {
        const double zc = (sl + 0.5) * dz;
        double phi = Omega * dt * static_cast<double>(step) + j * 2 * kPi / Nt -
                     zc * std::tan(m.tool.helix_angle) / R;
        phi = std::fmod(std::fmod(phi, 2 * kPi) + 2 * kPi, 2 * kPi);
        if (phi < a || phi > b) continue;
        const Eigen::Vector2d n(std::sin(phi), std::cos(phi));
        double h = 1e9;
        for (int kk = 1; kk <= Nt; ++kk) {
          const long back = step - static_cast<long>(kk) * Nf / Nt;
          const Eigen::Vector2d xp =
              back < 0 ? Eigen::Vector2d::Zero() : hist[static_cast<size_t>(back % Nf)];
          const double Rj = R + m.tool.runout * std::cos(m.tool.runout_angle - j * 2 * kPi / Nt);
          const int jp = ((j - kk) % Nt + Nt) % Nt;
          const double Rp = R + m.tool.runout * std::cos(m.tool.runout_angle - jp * 2 * kPi / Nt);
          h = std::min(h, kk * m.cut.fz * n.x() + Rj - Rp + (x - xp).dot(n));
        }
        if (h < m.coeff.h_min) continue;
        const double Ft = m.coeff.kc11 * dz * 1e-3 * std::pow(h / 1e-3, e);
        const double Fr = m.coeff.radial_ratio * Ft;
        F += Vec3(-Ft * n.y() - Fr * n.x(), Ft * n.x() - Fr * n.y(), -m.coeff.axial_ratio * Ft);
      }
    }
    return F;
  };
  const auto rhs = [&](const Eigen::Vector4d& y, const Vec3& F) {
    Eigen::Vector4d d;
    d << y(2), y(3), (F.x() - c * y(2) - k * y(0)) / mass, (F.y() - c * y(3) - k * y(1)) / mass;
    return d;
  };
  const long steps = 40L * Nf;
  TimeDomainRevolution out;
  std::vector<Vec3> x_last;
  for (long step = 0; step < steps; ++step) {
    const Eigen::Vector2d x = s.head<2>();
    hist[static_cast<size_t>(step % Nf)] = x;
    const Vec3 F = force(step, x);
    if (step >= steps - Nf && (step % sub) == 0) {
      out.force.push_back(F);
      x_last.push_back(Vec3(x.x(), x.y(), 0.0));
    }
    const Eigen::Vector4d k1 = rhs(s, F), k2 = rhs(s + 0.5 * dt * k1, F),
                          k3 = rhs(s + 0.5 * dt * k2, F), k4 = rhs(s + dt * k3, F);
    s += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : x_last) mean += v;
  mean /= static_cast<double>(x_last.size());
  for (const Vec3& v : x_last) out.vibration.push_back(v - mean);
  out.mean = mean;
  return out;
}

/// The cut the time-domain comparisons march: ap 1 mm, ae 2 mm, fz 0.1 mm at 12000 rpm.
MillingCut regenerativeCut(MillingMode mode) {
  MillingCut c;
  c.ap = 1e-3;
  c.ae = 2e-3;
  c.fz = 0.1e-3;
  c.mode = mode;
  c.spindle_rpm = 12000;
  return c;
}

/// Its model: 10 µm runout at 30°, 360 edge-angle steps.
MillingModel regenerativeCutModel(const MillingCut& c) {
  MillingTool t;
  t.runout = 10e-6;
  t.runout_angle = 30 * kDeg;
  return makeMillingModel(t, c, kienzle800(), 360, 5);
}

// The regenerative steady state against the time-domain march: a compliant tool mode (20 N/µm,
// 1500 Hz, ζ 0.05), up- and down-milling with 10 µm runout, ap 1 mm (below the chatter limit):
// forces within 2 % of the peak and the vibration within 3 % of its peak-to-peak at every sample
// (ae moved by the static deflection, which the coupling solves); the rigid profile at the same
// cut differs by far more (the test can fail).
TEST(Milling, EdgeRevolutionMatchesTimeDomainRegenerativeCut) {
  for (MillingMode mode : {MillingMode::kUp, MillingMode::kDown}) {
    const MillingCut c = regenerativeCut(mode);
    const MillingModel m = regenerativeCutModel(c);
    const TimeDomainRevolution ref = timeDomainRevolution(m, 20e6, 1500, 0.05, 360);
    // the static deflection moves the wall (the coupling's ae_eff); the rest is the vibration
    const double ae = c.ae + (mode == MillingMode::kUp ? 1 : -1) * ref.mean.y();
    const EdgeRevolution r = edgeRevolution(m, toolMode(20, 1500, 0.05), c.fz, ae, c.ap);
    ASSERT_TRUE(r.converged) << r.iterations << " " << r.update;
    ASSERT_EQ(ref.force.size(), r.force.size());
    const EdgeRevolution rigid = edgeRevolution(m, ModalModel{}, c.fz, ae, c.ap);
    Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
    for (const Vec3& v : ref.vibration) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    const double pp = (hi - lo).head<2>().norm();
    double df = 0, dx = 0, drigid = 0;
    for (size_t i = 0; i < r.force.size(); ++i) {
      df = std::max(df, (r.force[i] - ref.force[i]).norm());
      dx = std::max(dx, (r.vibration[i] - ref.vibration[i]).head<2>().norm());
      drigid = std::max(drigid, (rigid.force[i] - ref.force[i]).norm());
    }
    EXPECT_GT(pp, 2e-6);
    EXPECT_LT(df, 0.02 * r.peak_xy) << df << " N";
    EXPECT_LT(dx, 0.03 * pp) << dx * 1e6 << " um of " << pp * 1e6;
    EXPECT_GT(drigid, 5 * df);
  }
}

// The revolution's vibration is the periodic response of its own forces: the harmonic sum that
// milling_dynamics' periodicResponse takes term by term (O(N·K)), where edgeRevolution takes it by
// FFT. A robot-like low mode and the tool mode, up- and down-milling, 3 and 4 teeth, N = 360 and
// 480 (multiples of 4: the FFT's real-input path), 102 and 111 (its general path): at the
// converged revolution (its update ≤ 1e-9 m) the two agree to 1e-9 m against vibrations of
// several µm.
TEST(Milling, EdgeRevolutionVibrationIsTheDirectHarmonicSumOfItsForces) {
  const std::pair<int, int> teeth_and_samples[] = {{3, 120}, {4, 120}, {3, 34}, {3, 37}};
  for (MillingMode mode : {MillingMode::kUp, MillingMode::kDown}) {
    for (const auto& [teeth, per_tooth] : teeth_and_samples) {
      MillingCut c = regenerativeCut(mode);
      MillingTool t;
      t.teeth = teeth;
      t.runout = 10e-6;
      t.runout_angle = 30 * kDeg;
      const MillingModel m = makeMillingModel(t, c, kienzle800(), 360, 5);
      ModalModel dyn = toolMode(20, 1500, 0.05);
      ToolModeSpec low;
      low.stiffness = 5e6;
      low.frequency_hz = 230;
      low.damping_ratio = 0.05;
      addToolMode(dyn, low);
      EdgeRevolutionOptions o;
      o.samples_per_tooth = per_tooth;
      const EdgeRevolution r = edgeRevolution(m, dyn, c.fz, c.ae, c.ap, o);
      ASSERT_TRUE(r.converged) << r.iterations << " " << r.update;
      ASSERT_EQ(r.force.size(), static_cast<size_t>(per_tooth * teeth));
      const std::vector<Vec3> direct = periodicResponse(dyn, r.force, c.spindle_rpm);
      double pp = 0;
      double worst = 0;
      for (size_t n = 0; n < direct.size(); ++n) {
        worst = std::max(worst, (direct[n] - r.vibration[n]).norm());
        pp = std::max(pp, (r.vibration[n] - r.vibration[0]).norm());
      }
      EXPECT_GT(pp, 1e-6) << "the vibration must be large enough to compare";
      EXPECT_LT(worst, 1e-9) << worst << " m, teeth " << teeth << ", N " << r.force.size();
    }
  }
}

// The fixed point stops as soon as it diverges: past the chatter limit (the tool mode of the
// time-domain case at ap 20 mm instead of 1) the relaxed update grows at the smallest ω, and the
// revolution ends unconverged after `diverging_iterations` such updates in a row, long before
// max_iterations (which it runs to without the rule), with a finite vibration; below the limit
// the rule changes nothing (bit for bit).
TEST(Milling, EdgeRevolutionStopsOnceItDiverges) {
  const MillingCut c = regenerativeCut(MillingMode::kUp);
  const MillingModel m = regenerativeCutModel(c);
  const ModalModel tool = toolMode(20, 1500, 0.05);
  EdgeRevolutionOptions without;
  without.diverging_iterations = 1000000;
  const EdgeRevolution chatter = edgeRevolution(m, tool, c.fz, c.ae, 20e-3);
  EXPECT_FALSE(chatter.converged);
  EXPECT_LT(chatter.iterations, 150) << chatter.update;
  EXPECT_GE(chatter.iterations, 20);
  for (const Vec3& x : chatter.vibration) ASSERT_TRUE(x.allFinite());
  const EdgeRevolution all = edgeRevolution(m, tool, c.fz, c.ae, 20e-3, without);
  EXPECT_FALSE(all.converged);
  EXPECT_EQ(all.iterations, without.max_iterations);
  const EdgeRevolution stable = edgeRevolution(m, tool, c.fz, c.ae, c.ap);
  const EdgeRevolution stable_without = edgeRevolution(m, tool, c.fz, c.ae, c.ap, without);
  ASSERT_TRUE(stable.converged);
  EXPECT_EQ(stable.iterations, stable_without.iterations);
  EXPECT_EQ(stable.mean, stable_without.mean);
  EXPECT_EQ(stable.vibration, stable_without.vibration);
}

// The edge-consistent static solve against the time-domain march of the vibrating cut: a tool mode
// (20 N/µm, 1500 Hz, ζ 0.05; its static compliance 0.05 µm/N is the solve's compliance in X and Y)
// with 10 µm runout, ap 1 mm, in steady state (the feed term off: δ_{i−1} = δ). The march's mean
// displacement is the static deflection under the mean force of the cut the tool really makes
// (previous edges, runout, vibration, ae(t)); the consistent solve reproduces it within 1 % (and
// its mean force within 0.5 %; measured 0.03 % up-, 0.4 % down-milling, where the vibration moves
// the mean force by 0.2–0.3 %).
TEST(Milling, ConsistentSolveIsTheTimeDomainStaticDeflection) {
  for (MillingMode mode : {MillingMode::kUp, MillingMode::kDown}) {
    const MillingCut c = regenerativeCut(mode);
    const MillingModel m = regenerativeCutModel(c);
    const TimeDomainRevolution ref = timeDomainRevolution(m, 20e6, 1500, 0.05, 360);
    Vec3 ref_force = Vec3::Zero();
    for (const Vec3& F : ref.force) ref_force += F;
    ref_force /= static_cast<double>(ref.force.size());
    const ModalModel tool = toolMode(20, 1500, 0.05);
    const ComplianceFunction C = linearCompliance(Vec3(0.05e-6, 0.05e-6, 0.0).asDiagonal());
    const EdgeRevolutionFunction edges = [&](double fz, double ae, double ap) {
      return edgeRevolution(m, tool, fz, ae, ap);
    };
    CouplingOptions o;
    o.teeth_between_points = 1000000;
    o.tolerance = 1e-9;
    const ConsistentCoupling e = coupleMillingPointConsistent(m, C, edges, CouplingState{}, o);
    ASSERT_TRUE(e.converged()) << e.rounds << " " << e.edge_residual;
    const Vec3 d = e.point.delta;
    const Vec3 dref(ref.mean.x(), ref.mean.y(), 0.0);
    EXPECT_LT((d - dref).norm(), 0.01 * dref.norm()) << d.transpose() << " | " << dref.transpose();
    EXPECT_LT((e.point.force - ref_force).norm(), 0.005 * ref_force.norm());
  }
}

// The paper's qualitative result (corrected vs modelled force over the edge angle, with runout):
// the vibrating tool evens out the runout — the tooth with the largest chip is pushed back, so the
// spread of the per-tooth feeds and of the per-tooth peak chips shrinks and the peak force drops —
// while the teeth together still remove about Nt·fz (steady state: no feed is lost or invented;
// within 1 %, what the vibrating wall adds or takes at the arc's end). Tool mode 10 N/µm, 2000 Hz,
// ap 2 mm, 15 µm runout: measured feed spread 94.8 → 83.7 µm, chip spread 45.0 → 37.8 µm, peak
// 288.8 → 282.0 N, mean feed 99.3 µm.
TEST(Milling, VibratingToolEvensOutTheRunoutSignature) {
  MillingTool t;
  t.runout = 15e-6;
  MillingCut c;
  c.ap = 2e-3;
  c.ae = 2e-3;
  c.fz = 0.1e-3;
  c.spindle_rpm = 12000;
  const MillingModel m = makeMillingModel(t, c, kienzle800(), 360, 10);
  const EdgeRevolution rigid = edgeRevolution(m, ModalModel{}, c.fz, c.ae, c.ap);
  const EdgeRevolution soft = edgeRevolution(m, toolMode(10, 2000, 0.05), c.fz, c.ae, c.ap);
  ASSERT_TRUE(soft.converged);
  const auto spread = [](const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *hi - *lo;
  };
  EXPECT_LT(spread(soft.tooth_feed), 0.92 * spread(rigid.tooth_feed));
  EXPECT_LT(spread(soft.max_chip), 0.9 * spread(rigid.max_chip));
  EXPECT_LT(soft.peak_xy, 0.985 * rigid.peak_xy);
  double sum = 0;
  for (double f : soft.tooth_feed) sum += f;
  EXPECT_NEAR(sum / 3, c.fz, 0.01 * c.fz);
  EXPECT_GT(std::abs(soft.tooth_feed.front() - c.fz), 1e-6);  // per tooth: not the nominal fz
}

}  // namespace
}  // namespace roprec
