// Single-branch IK (IkOptions::branch): for every bundled robot and random in-limit joints, the
// solutions of one branch are exactly those of the all-branch solve carrying that branch label
// (same count, same joint vectors bit for bit, same flags), in both turn modes; the pose's own
// branch contains the original joints.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <utility>

#include "compensator/robot/ik.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec {
namespace {

/// The solutions of every single-branch solve at T (both turn modes) are those of the all-branch
/// solve carrying that branch label, bit for bit, in order; returns how many were compared.
int expectBranchesAreSubsetsOfAll(const IkModel& m, const Pose& T, const Vec6& seed, IkResult& all,
                                  IkResult& one) {
  int compared = 0;
  for (const IkTurns turns : {IkTurns::kPrimary, IkTurns::kAll}) {
    IkOptions o;
    o.turns = turns;
    o.seed = &seed;
    solveIk(m, T, o, all);
    for (int b = 0; b < 8; ++b) {
      o.branch = b;
      solveIk(m, T, o, one);
      std::vector<const IkSolution*> want;
      for (int k = 0; k < all.count; ++k) {
        const IkSolution& s = all.solutions[static_cast<size_t>(k)];
        if (s.branch.index() == b) want.push_back(&s);
      }
      EXPECT_EQ(static_cast<size_t>(one.count), want.size()) << "branch " << b;
      if (static_cast<size_t>(one.count) != want.size()) continue;
      for (size_t k = 0; k < want.size(); ++k) {
        const IkSolution& s = one.solutions[k];
        EXPECT_EQ(s.branch.index(), b);
        EXPECT_TRUE(s.q == want[k]->q);
        EXPECT_EQ(s.converged, want[k]->converged);
        EXPECT_EQ(s.within_limits, want[k]->within_limits);
        EXPECT_EQ(s.singular_wrist, want[k]->singular_wrist);
        ++compared;
      }
    }
  }
  return compared;
}

/// Seeded random joints within the model's limits, clipped to ±3 rad.
Vec6 jointsWithinLimits(const IkModel& m, std::mt19937& rng) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    std::uniform_real_distribution<double> u(std::max(m.lower[i], -3.0), std::min(m.upper[i], 3.0));
    q[i] = u(rng);
  }
  return q;
}

TEST(IkBranch, OneBranchEqualsTheMatchingSubsetOfAll) {
  const auto names = bundledRobotNames();
  ASSERT_FALSE(names.empty());
  auto all = std::make_unique<IkResult>();
  auto one = std::make_unique<IkResult>();
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Robot r = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(r);
    std::mt19937 rng(31);
    int compared = 0;
    for (int n = 0; n < 200; ++n) {
      const Vec6 q = jointsWithinLimits(m, rng);
      compared += expectBranchesAreSubsetsOfAll(m, ikForwardKinematics(m, q), q, *all, *one);
      // the original joints are among their own branch's solutions (kAll)
      IkOptions o;
      o.turns = IkTurns::kAll;
      o.branch = ikBranch(m, q).index();
      solveIk(m, ikForwardKinematics(m, q), o, *one);
      double best = 1e9;
      for (int k = 0; k < one->count; ++k)
        best = std::min(best, (one->solutions[static_cast<size_t>(k)].q - q).cwiseAbs().maxCoeff());
      EXPECT_LE(best, 1e-9);
    }
    EXPECT_GT(compared, 1000);
  }
}

/// The single-branch solve skips other branches by labels it knows before solving (|x| and
/// sin ψ beyond 1e-6): at postures within 1e-10 … 1e-4 of the shoulder (wrist centre on axis 1)
/// and elbow (sin ψ = 0) label boundaries, and 1.2e-6 … 1e-4 of the wrist one (sin(q5 + α) = 0),
/// on both sides, the labels it assumes or computes are still those of the all-branch solve.
/// Nearer the wrist boundary the refinement of a wrist-singular raw solution can move q5 across
/// it, and the single-branch solve (which filters by the raw solution's label) then differs:
/// those solutions are flagged singular_wrist, and not compared here.
TEST(IkBranch, OneBranchEqualsTheMatchingSubsetNearTheLabelBoundaries) {
  const auto names = bundledRobotNames();
  ASSERT_FALSE(names.empty());
  auto all = std::make_unique<IkResult>();
  auto one = std::make_unique<IkResult>();
  const std::array<double, 8> offsets{1e-10, -1e-10, 1e-7, -1e-7, 1.2e-6, -1.2e-6, 1e-4, -1e-4};
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Robot r = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(r);
    std::mt19937 rng(7);
    int compared = 0;
    for (int n = 0; n < 20; ++n) {
      const Vec6 q = jointsWithinLimits(m, rng);
      for (const double off : offsets) {
        // elbow: ψ0 + σ3 q3 = off (sin ψ ≈ off)
        Vec6 qe = q;
        qe[2] = m.sigma3 * (off - m.psi0);
        // shoulder: x = p2x + (Ry(q2) a).x = 0 shifted by off/|a| radians (|x| ≈ off m)
        Vec6 qs = q;
        const Eigen::Vector2d a = m.u0 + Eigen::Vector2d(std::cos(m.sigma3 * q[2]) * m.v0.x() +
                                                             std::sin(m.sigma3 * q[2]) * m.v0.y(),
                                                         -std::sin(m.sigma3 * q[2]) * m.v0.x() +
                                                             std::cos(m.sigma3 * q[2]) * m.v0.y());
        const double R = a.norm();
        if (R > std::abs(m.p2x)) qs[1] = std::atan2(a.y(), a.x()) + std::acos(-m.p2x / R) + off / R;
        // wrist: q5 + α = off
        Vec6 qw = q;
        qw[4] = off - m.alpha;
        const std::array<std::pair<const char*, const Vec6*>, 3> near{
            {{"elbow", &qe}, {"shoulder", &qs}, {"wrist", &qw}}};
        for (const auto& [what, p] : near) {
          if (p == &qw && std::abs(off) < 1e-6) continue;
          SCOPED_TRACE(std::string(what) + " boundary at " + std::to_string(off));
          compared += expectBranchesAreSubsetsOfAll(m, ikForwardKinematics(m, *p), *p, *all, *one);
        }
      }
    }
    EXPECT_GT(compared, 100);
  }
}

}  // namespace
}  // namespace roprec
