// The drilling force law tabulated along the lip radius (compensator/process/transient_forces.hpp)
// against the exact evaluator drillingForcesAtDepth (24-node Gauss–Legendre rebuilt at every
// call), which is the independent reference here:
//  * entry, full engagement and breakthrough of the sample cell's through hole and of a blind
//    hole, at depths between the table nodes and feeds 0.05–0.4 mm/rev: every force and torque
//    within 1e-6 of the steady full-engagement value, 1e-5 for a 1 mm plate (entry and exit
//    overlap; the stated table tolerance is 1e-5);
//  * the tabulated sums at the end of the entry give the evaluator's full-engagement thrust and
//    torque, written out from the Kienzle law, to 1e-12;
//  * runout 10 µm (unequal lip chips, corner strips in the breakthrough) within the same bound;
//  * the exact fallback for chips under the floor h_min;
//  * table accuracy converges like Δ⁴ (local cubic): 24 → 48 cells gains ≥ 8×.
#include "compensator/process/transient_forces.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "compensator/precision/cell.hpp"
#include "compensator/process/process_spec.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

DrillingSpec sampleSpec() {
  const CellSpec cell = loadCell(test::sourceDir() + "/samples/cells/alu-drilling-6061.xml");
  return parseProcess(cell.process).drilling;
}

double thicknessOf(const DrillingSpec& s) {
  return s.through ? (s.hole_depth > 0 ? s.hole_depth : 2.0 * s.geometry.diameter) : 0.0;
}

/// Largest |table − exact| over forces and torque, relative to the steady values at `feed`,
/// sampling depths from 0 to the exit (or 1.5× the entry depth) at a step off the table grid.
double worstRelativeError(const DrillingSpec& spec, double feed, int intervals) {
  const DrillingModel m = drillingModelOf(spec);
  DrillingData data(m);
  const double T = thicknessOf(spec);
  nc::DrillingForceTable table(m, T, intervals);
  const DrillGeometry& g = m.geometry;
  const double entry = (g.radius() - g.chiselHalfLength()) / std::tan(g.halfPoint());
  const double end = T > 0 ? T + entry + 1e-4 : 1.5 * entry;
  const DrillingForces steady = drillingForces(m, feed);
  const double scaleF = steady.thrust;
  const double scaleM = steady.torque;
  double worst = 0.0;
  for (double z = -1e-4; z <= end; z += entry / 997.0) {
    const DrillingForces a = table.forces(feed, z);
    const DrillingForces b = drillingForcesAtDepth(m, data, feed, z, T);
    worst = std::max({worst, std::abs(a.thrust - b.thrust) / scaleF,
                      std::abs(a.thrust_lips - b.thrust_lips) / scaleF,
                      std::abs(a.tangential - b.tangential) / scaleF,
                      (a.residual_xy - b.residual_xy).norm() / scaleF,
                      std::abs(a.torque - b.torque) / scaleM});
    EXPECT_EQ(a.chisel_engaged, b.chisel_engaged) << "z = " << z;
    EXPECT_DOUBLE_EQ(a.r_in, b.r_in);
    EXPECT_DOUBLE_EQ(a.r_out, b.r_out);
  }
  EXPECT_GT(table.tableCalls(), 100) << "the partial engagement must use the table";
  return worst;
}

TEST(TransientForces, TableMatchesExactEvaluatorThroughHole) {
  const DrillingSpec s = sampleSpec();
  ASSERT_TRUE(s.through);
  for (const double f : {0.05e-3, 0.2e-3, 0.4e-3}) {
    EXPECT_LT(worstRelativeError(s, f, 48), 1e-6) << "feed " << f;
  }
}

TEST(TransientForces, TableMatchesExactEvaluatorBlindHoleAndThinPlate) {
  DrillingSpec blind = sampleSpec();
  blind.through = false;
  EXPECT_LT(worstRelativeError(blind, 0.2e-3, 48), 1e-6);
  DrillingSpec thin = sampleSpec();  // entry and exit overlap: r_in and r_out both move
  thin.hole_depth = 1e-3;
  EXPECT_LT(worstRelativeError(thin, 0.2e-3, 48), 1e-5);
}

TEST(TransientForces, TableWithRunoutCornerStripMatches) {
  DrillingSpec s = sampleSpec();
  s.geometry.runout = 10e-6;
  EXPECT_LT(worstRelativeError(s, 0.2e-3, 48), 1e-6);
}

TEST(TransientForces, SumsReproduceTheEvaluatorAtFullEngagement) {
  DrillingSpec s = sampleSpec();
  s.geometry.runout = 0.0;  // equal chips q = f/2 on both lips, no corner strip
  const DrillingModel m = drillingModelOf(s);
  nc::DrillingForceTable table(m, 0.0);
  const DrillGeometry& g = m.geometry;
  const double entry = (g.radius() - g.chiselHalfLength()) / std::tan(g.halfPoint());
  nc::DrillingForceTable::Sums S;
  ASSERT_TRUE(table.sums(entry, S));  // the last grid point of the entry: the full lip
  EXPECT_FALSE(table.sums(1.5 * entry, S = nc::DrillingForceTable::Sums::Zero()));
  ASSERT_TRUE(table.sums(entry, S));
  // thrust of the lips at feed f, written out from the Kienzle law
  const double f = 0.2e-3;
  const double q = 0.5 * f;
  const SpecificPressure& ka = m.coeff.axial;
  const SpecificPressure& kt = m.coeff.tangential;
  const DrillingForces F = drillingForces(m, f);
  EXPECT_NEAR(2.0 * ka.k0 * std::pow(q / 1e-3, -ka.m) * q * S[1], F.thrust_lips,
              1e-12 * F.thrust_lips);
  EXPECT_NEAR(2.0 * kt.k0 * std::pow(q / 1e-3, -kt.m) * q * S[3], F.torque - F.torque_chisel,
              1e-12 * F.torque);
}

TEST(TransientForces, ChipBelowFloorFallsBackToExact) {
  const DrillingSpec s = sampleSpec();
  const DrillingModel m = drillingModelOf(s);
  DrillingData data(m);
  nc::DrillingForceTable table(m, thicknessOf(s));
  const double z = 1e-3;  // entry
  const double f = 2e-6;  // 1 % of the feed: every node under h_min = 5 µm
  const long before = table.exactCalls();
  const DrillingForces a = table.forces(f, z);
  EXPECT_EQ(table.exactCalls(), before + 1);
  const DrillingForces b = drillingForcesAtDepth(m, data, f, z, thicknessOf(s));
  EXPECT_DOUBLE_EQ(a.thrust, b.thrust);
  EXPECT_DOUBLE_EQ(a.torque, b.torque);
}

TEST(TransientForces, TableErrorConvergesAsFourthPower) {
  DrillingSpec blind = sampleSpec();
  blind.through = false;
  const double e24 = worstRelativeError(blind, 0.2e-3, 24);
  const double e48 = worstRelativeError(blind, 0.2e-3, 48);
  EXPECT_GT(e48, 0.0);
  EXPECT_GT(e24 / e48, 8.0) << e24 << " " << e48;  // 16 for a smooth integrand
}

TEST(TransientForces, RejectsNoCells) {
  const DrillingModel m = drillingModelOf(sampleSpec());
  EXPECT_THROW(nc::DrillingForceTable(m, 0.0, 3), std::invalid_argument);
}

}  // namespace
}  // namespace roprec
