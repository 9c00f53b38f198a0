#include "compensator/process/milling_engagement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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

// The reference of the bounded tracker: the stock and every recorded move in a plain list, the
// top at p the lowest tip height of a move whose capsule holds p, and the engagement found from it
// as milling_engagement.hpp states it (K samples of the leading half, runs refined by bisection).
class PlainListEngagement {
 public:
  PlainListEngagement(const StockShape& stock, double diameter)
      : stock_(stock), R_(0.5 * diameter) {}
  void record(const Vec3& a, const Vec3& b) {
    if ((b.head<2>() - a.head<2>()).norm() > 0)
      moves_.push_back({a.head<2>(), b.head<2>(), std::min(a.z(), b.z())});
  }
  [[nodiscard]] MillingEngagement engagementAt(const Vec3& a, const Vec3& b) const {
    MillingEngagement e;
    const Eigen::Vector2d b2 = b.head<2>();
    const Eigen::Vector2d d = b2 - a.head<2>();
    if (!(d.norm() > 0)) return e;
    const Eigen::Vector2d f = d / d.norm();
    const Eigen::Vector2d l(-f.y(), f.x());
    const auto depth = [&](double s) {
      return top(b2 + s * l + std::sqrt(std::max(0.0, R_ * R_ - s * s)) * f) - b.z();
    };
    const auto edge = [&](double in, double out) {
      while (std::abs(out - in) > kBoundaryResolution) {
        const double mid = 0.5 * (in + out);
        (depth(mid) > 1e-6 ? in : out) = mid;
      }
      return 0.5 * (in + out);
    };
    const double step = 2 * R_ / kSamples;
    const auto offset = [&](int k) { return -R_ + (k + 0.5) * step; };
    bool prev = false;
    double lo = -R_;
    for (int k = 0; k < kSamples; ++k) {
      const double h = depth(offset(k));
      const bool in = h > 1e-6;
      if (in) e.ap = std::max(e.ap, h);
      if (in && !prev) lo = k == 0 ? -R_ : edge(offset(k), offset(k - 1));
      if (!in && prev) e.ae += edge(offset(k - 1), offset(k)) - lo;
      prev = in;
    }
    if (prev) e.ae += R_ - lo;
    if (!(e.ae > 0)) e = MillingEngagement{};
    return e;
  }

 private:
  static constexpr int kSamples = 200;
  struct Move {
    Eigen::Vector2d a, b;
    double z;
  };
  [[nodiscard]] double top(const Eigen::Vector2d& p) const {
    if (stock_.box_min && (p.x() < stock_.box_min->x() || p.x() > stock_.box_max->x() ||
                           p.y() < stock_.box_min->y() || p.y() > stock_.box_max->y()))
      return -1e300;
    double t = stock_.box_max ? std::min(stock_.top_z, stock_.box_max->z()) : stock_.top_z;
    for (const Move& m : moves_) {
      const Eigen::Vector2d ab = m.b - m.a;
      const double s = std::clamp((p - m.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      if ((p - (m.a + s * ab)).norm() < R_ * (1 - 1e-9)) t = std::min(t, m.z);
    }
    return t;
  }
  StockShape stock_;
  double R_;
  std::vector<Move> moves_;
};

/// Cuts the moves `path` (a polyline; a NaN point lifts the tool: no move into the next point)
/// with the tracker and the plain list; every engagement must be the same doubles.
void expectSameAsPlainList(const StockShape& stock, const std::vector<Vec3>& path,
                           const char* what) {
  EngagementTracker t(stock, kD);
  PlainListEngagement ref(stock, kD);
  int cutting = 0;
  for (size_t i = 1; i < path.size(); ++i) {
    if (std::isnan(path[i - 1].x()) || std::isnan(path[i].x())) continue;
    const MillingEngagement e = t.cut(path[i - 1], path[i]);
    const MillingEngagement r = ref.engagementAt(path[i - 1], path[i]);
    ref.record(path[i - 1], path[i]);
    ASSERT_EQ(e.ae, r.ae) << what << " move " << i;
    ASSERT_EQ(e.ap, r.ap) << what << " move " << i;
    cutting += e.cuts() ? 1 : 0;
  }
  EXPECT_GT(cutting, 10) << what;  // the paths do cut
}

const Vec3 kLift(std::nan(""), 0, 0);

/// A raster pocket over box(0, 0, −0.02, 0.1, 0.05, 0): passes along ±x (zig-zag) at stepover
/// `stepover`, points every `step`, `layers` layers 1.5 mm apart; each point moved by a seeded
/// deviation of up to `wobble` (a real path's), none for 0.
std::vector<Vec3> rasterPocket(double stepover, double step, int layers, double wobble,
                               std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dev(-wobble, wobble);
  std::vector<Vec3> path;
  for (int k = 0; k < layers; ++k) {
    const double z = -1.5e-3 * (k + 1);
    bool forward = true;
    for (double y = 0.01; y <= 0.04 + 1e-12; y += stepover, forward = !forward) {
      for (double x = 0.015; x <= 0.085 + 1e-12; x += step) {
        const double px = forward ? x : 0.1 - x;
        path.emplace_back(px + dev(rng), y + dev(rng), z);
      }
    }
    path.push_back(kLift);
  }
  return path;
}

/// `passes` wall passes along the box face y = 0 (ae 2 mm, ap 5 mm), each a lifted pass of 1 mm
/// moves with seeded deviations of up to `wobble`.
std::vector<Vec3> wallPasses(int passes, double wobble, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dev(-wobble, wobble);
  std::vector<Vec3> path;
  for (int k = 0; k < passes; ++k) {
    for (double x = -0.01; x <= 0.11 + 1e-12; x += 1e-3)
      path.emplace_back(x + dev(rng), -kD / 2 + 2e-3 + dev(rng), -5e-3);
    path.push_back(kLift);
  }
  return path;
}

// The tracker keeps in its cells only what can still set a top (the floor of a cell a capsule
// holds, a segment again at the same or a lower height, nothing outside the box): the engagement
// of every move is the same doubles as from the stock and every earlier move in a plain list, on
// seeded random moves (short and long, all directions, a few heights so that floors and repeats
// occur, segments repeated exactly, some above the stock and some outside the box), raster pockets
// and repeated wall passes, exact and with µm deviations, in a box and in a plane stock.
TEST(MillingEngagement, BoundedCellsGiveThePlainListsEngagement) {
  const StockShape b = box(0, 0, -0.02, 0.1, 0.05, 0);
  StockShape plane;
  plane.top_z = 0;
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> path{Vec3(0.05, 0.025, -2e-3)};
    for (int i = 0; i < 600; ++i) {
      const Vec3& p = path.back();
      const double r = u(rng);
      if (r < 0.05 && path.size() > 20) {  // a segment repeated, as low or a step lower
        const size_t j = 1 + static_cast<size_t>(u(rng) * (path.size() - 2));
        if (std::isnan(path[j - 1].x()) || std::isnan(path[j].x())) continue;
        const double dz = u(rng) < 0.5 ? 0.0 : -1e-3;
        path.push_back(kLift);
        path.push_back(path[j - 1] + Vec3(0, 0, dz));
        path.push_back(path[j] + Vec3(0, 0, dz));
        continue;
      }
      const double len = r < 0.5 ? 0.3e-3 + u(rng) * 1.5e-3 : u(rng) * 25e-3;
      const double angle = 2 * M_PI * u(rng);
      const double z = r < 0.9 ? -1e-3 * std::floor(1 + 4 * u(rng)) : 1e-3;
      const Vec3 q(std::clamp(p.x() + len * std::cos(angle), -0.01, 0.11),
                   std::clamp(p.y() + len * std::sin(angle), -0.01, 0.06), z);
      path.push_back(q);
    }
    expectSameAsPlainList(b, path, "random moves, box");
    expectSameAsPlainList(plane, path, "random moves, plane");
  }
  expectSameAsPlainList(b, rasterPocket(4e-3, 1e-3, 3, 0, 7), "raster pocket");
  expectSameAsPlainList(b, rasterPocket(6e-3, 0.7e-3, 3, 3e-6, 8), "raster pocket, deviations");
  expectSameAsPlainList(plane, rasterPocket(8.5e-3, 2e-3, 2, 1e-6, 9), "raster pocket, plane");
  expectSameAsPlainList(b, wallPasses(6, 0, 10), "wall passes");
  expectSameAsPlainList(b, wallPasses(6, 2e-6, 11), "wall passes, deviations");
}

// The memory is bounded by the area swept, not the path: a wall pass repeated exactly holds the
// same moves after 100 passes as after 2, and a raster pocket cut again layer by layer holds the
// same count after 25 layers as after 2 (each layer's moves replace the one above where they do
// not make a cell's floor), all of it far below the moves recorded.
TEST(MillingEngagement, HeldMovesStayBoundedOnARepeatedPath) {
  const StockShape b = box(0, 0, -0.02, 0.1, 0.05, 0);
  EngagementTracker wall(b, kD);
  size_t after_two = 0;
  const std::vector<Vec3> passes = wallPasses(100, 0, 1);
  size_t recorded = 0;
  for (size_t i = 1, pass = 0; i < passes.size(); ++i) {
    if (std::isnan(passes[i].x())) {
      if (++pass == 2) after_two = wall.movesHeld();
      continue;
    }
    if (std::isnan(passes[i - 1].x())) continue;
    wall.cut(passes[i - 1], passes[i]);
    ++recorded;
  }
  EXPECT_GT(after_two, 0u);
  EXPECT_EQ(wall.movesHeld(), after_two);
  EXPECT_LT(wall.movesHeld(), recorded / 40);
  EngagementTracker pocket(b, kD);
  size_t layer = 0, held_two = 0, moves = 0;
  for (int k = 0; k < 25; ++k) {
    const std::vector<Vec3> one = rasterPocket(5e-3, 1e-3, 1, 0, 3);
    for (size_t i = 1; i < one.size(); ++i) {
      if (std::isnan(one[i].x())) continue;
      pocket.cut(one[i - 1] - Vec3(0, 0, 1e-3 * k), one[i] - Vec3(0, 0, 1e-3 * k));
      ++moves;
    }
    if (++layer == 2) held_two = pocket.movesHeld();
  }
  EXPECT_GT(held_two, 0u);
  EXPECT_EQ(pocket.movesHeld(), held_two);
  EXPECT_LT(pocket.movesHeld(), moves / 10);
}

}  // namespace
}  // namespace roprec
