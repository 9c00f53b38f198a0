#include "compensator/process/milling_engagement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace roprec {
namespace {

constexpr double kD = 10e-3;          // tool diameter
constexpr double kSample = kD / 200;  // lateral sampling of the tracker
constexpr double kEdge = 1e-8;        // its refined run ends (kBoundaryResolution) and rounding

StockShape box(double x0, double y0, double z0, double x1, double y1, double z1) {
  StockShape s;
  s.box_min = Vec3(x0, y0, z0);
  s.box_max = Vec3(x1, y1, z1);
  s.top_z = z1;
  return s;
}

/// A straight pass along +x at height z and lateral position y, in steps of `step`; the
/// engagement at every point after the first.
std::vector<MillingEngagement> pass(EngagementTracker& t, double y, double z, double x0, double x1,
                                    double step = 1e-3) {
  std::vector<MillingEngagement> out;
  for (double x = x0 + step; x <= x1 + 1e-12; x += step)
    out.push_back(t.cut(Vec3(x - step, y, z), Vec3(x, y, z)));
  return out;
}

// A wall pass along a box edge: the tool centre at y = y0 − R + w overlaps the box (y ≥ y0) by w,
// so ae = w (closed form, to the refined run ends — widths off the D/200 sampling grid included)
// and ap = top − z; outside the box in x nothing is engaged. (A run narrower than D/200 between
// two samples is missed: the sampling finds runs, the bisection their ends.)
TEST(MillingEngagement, WallPassAlongABoxEdgeGivesTheOverlap) {
  for (const double w : {1e-3, 2e-3, 4.5e-3, 2.0173e-3}) {
    EngagementTracker t(box(0, 0, -0.02, 0.1, 0.05, 0), kD);
    const std::vector<MillingEngagement> e = pass(t, -kD / 2 + w, -5e-3, 0.02, 0.08);
    for (const MillingEngagement& g : e) {
      EXPECT_NEAR(g.ae, w, kEdge) << w;
      EXPECT_NEAR(g.ap, 5e-3, 1e-12);
    }
    // beyond the box's end face (x = 0.1 + R … ) the leading half is in the air
    const MillingEngagement out =
        t.cut(Vec3(0.12, -kD / 2 + w, -5e-3), Vec3(0.121, -kD / 2 + w, -5e-3));
    EXPECT_FALSE(out.cuts());
  }
}

// The program's own earlier passes: a second pass offset by the stepover s from the first cuts
// ae = s (the first pass removed the rest); a pass back over the same line cuts nothing; a pass
// one step Δz down on the same line cuts the same width, ap = Δz (below the first pass's floor);
// in a plane stock, the first pass is a slot (ae = D) of depth top − z.
TEST(MillingEngagement, EarlierPassesSetTheStepoverAndTheStepDown) {
  const double z = -5e-3;
  EngagementTracker t(box(0, 0, -0.02, 0.1, 0.05, 0), kD);
  pass(t, -kD / 2 + 2e-3, z, 0.0, 0.1);  // first wall pass, ae 2
  for (const double s : {1.5e-3, 3e-3}) {
    EngagementTracker u = t;
    for (const MillingEngagement& g : pass(u, -kD / 2 + 2e-3 + s, z, 0.02, 0.08)) {
      EXPECT_NEAR(g.ae, s, kEdge) << s;
      EXPECT_NEAR(g.ap, 5e-3, 1e-12);
    }
  }
  EngagementTracker again = t;
  for (const MillingEngagement& g : pass(again, -kD / 2 + 2e-3, z, 0.02, 0.08))
    EXPECT_FALSE(g.cuts());
  EngagementTracker down = t;
  for (const MillingEngagement& g : pass(down, -kD / 2 + 2e-3, z - 1.5e-3, 0.02, 0.08)) {
    EXPECT_NEAR(g.ae, 2e-3, kEdge);  // the box's side, below the first pass's floor
    EXPECT_NEAR(g.ap, 1.5e-3, 1e-12);
  }
  StockShape plane;
  plane.top_z = 0;
  EngagementTracker p(plane, kD);
  for (const MillingEngagement& g : pass(p, 0.0, -3e-3, 0.0, 0.05)) {
    EXPECT_NEAR(g.ae, kD, 1e-12);
    EXPECT_NEAR(g.ap, 3e-3, 1e-12);
  }
}

// Entering the stock: the tool moving along +x into the box's face x = 0 engages the chord of its
// leading half inside the box: with the tool centre at x = c (−R < c < 0, a full-width pass
// y ∈ box), the samples with c + √(R² − s²) > 0 are engaged: ae = 2 √(R² − c²) (closed form).
TEST(MillingEngagement, EnteringTheStockEngagesTheChord) {
  for (const double c : {-4e-3, -2.5e-3, -1e-3}) {
    EngagementTracker t(box(0, -0.02, -0.02, 0.1, 0.02, 0), kD);
    const MillingEngagement g = t.cut(Vec3(c - 1e-3, 0, -2e-3), Vec3(c, 0, -2e-3));
    EXPECT_NEAR(g.ae, 2 * std::sqrt(kD * kD / 4 - c * c), 2 * kEdge) << c;
    EXPECT_NEAR(g.ap, 2e-3, 1e-12);
  }
}

// A query removes nothing: the same move queried twice engages the same; record() removes what
// it swept: after the longer move a → c is recorded, the move a → b (b between them, its leading
// half inside the swept capsule) engages nothing.
TEST(MillingEngagement, AQueryRemovesNothingARecordRemovesTheMove) {
  EngagementTracker t(box(0, 0, -0.02, 0.1, 0.05, 0), kD);
  const Vec3 a(0.03, -kD / 2 + 2e-3, -5e-3);
  const Vec3 b(0.031, -kD / 2 + 2e-3, -5e-3);
  const Vec3 c(0.04, -kD / 2 + 2e-3, -5e-3);
  const MillingEngagement e1 = t.engagementAt(a, b);
  const MillingEngagement e2 = t.engagementAt(a, b);
  EXPECT_NEAR(e1.ae, 2e-3, kEdge);
  EXPECT_EQ(e1.ae, e2.ae);
  EXPECT_EQ(e1.ap, e2.ap);
  t.record(a, c);
  EXPECT_FALSE(t.engagementAt(a, b).cuts());
}

// The wall a pass really left sets the next pass's ae: the first pass recorded d off its
// programmed line (d > 0 into the material: an overcut; d < 0: an undercut), the second pass
// queried on its programmed line, stepover s: ae = s − d (closed form), for d of a few µm — far
// below the D/200 = 50 µm sampling, so only the refined run ends resolve it.
TEST(MillingEngagement, AWallLeftOffsetByDChangesTheNextPassesAeByD) {
  const double y1 = -kD / 2 + 2e-3;
  const double z = -5e-3;
  const double s = 2e-3;
  for (const double d : {17e-6, -8.5e-6, 3.2e-6}) {
    EngagementTracker t(box(0, 0, -0.02, 0.1, 0.05, 0), kD);
    for (double x = 0.001; x <= 0.1 + 1e-12; x += 1e-3)
      t.record(Vec3(x - 1e-3, y1 + d, z), Vec3(x, y1 + d, z));
    for (double x = 0.021; x <= 0.08; x += 1e-3) {
      const MillingEngagement g = t.engagementAt(Vec3(x - 1e-3, y1 + s, z), Vec3(x, y1 + s, z));
      EXPECT_NEAR(g.ae, s - d, kEdge) << d;
      EXPECT_NEAR(g.ap, 5e-3, 1e-12);
    }
  }
}

}  // namespace
}  // namespace roprec
