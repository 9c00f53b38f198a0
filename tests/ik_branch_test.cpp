// Single-branch IK (IkOptions::branch): for every bundled robot and random in-limit joints, the
// solutions of one branch are exactly those of the all-branch solve carrying that branch label
// (same count, same joint vectors bit for bit, same flags), in both turn modes; the pose's own
// branch contains the original joints.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "compensator/robot/ik.hpp"
#include "compensator/robot/robot_card.hpp"

namespace roprec {
namespace {

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
      Vec6 q;
      for (int i = 0; i < 6; ++i) {
        std::uniform_real_distribution<double> u(std::max(m.lower[i], -3.0),
                                                 std::min(m.upper[i], 3.0));
        q[i] = u(rng);
      }
      const Pose T = ikForwardKinematics(m, q);
      for (const IkTurns turns : {IkTurns::kPrimary, IkTurns::kAll}) {
        IkOptions o;
        o.turns = turns;
        o.seed = &q;
        solveIk(m, T, o, *all);
        for (int b = 0; b < 8; ++b) {
          o.branch = b;
          solveIk(m, T, o, *one);
          std::vector<const IkSolution*> want;
          for (int k = 0; k < all->count; ++k) {
            const IkSolution& s = all->solutions[static_cast<size_t>(k)];
            if (s.branch.index() == b) want.push_back(&s);
          }
          ASSERT_EQ(static_cast<size_t>(one->count), want.size()) << "branch " << b;
          for (size_t k = 0; k < want.size(); ++k) {
            const IkSolution& s = one->solutions[k];
            EXPECT_EQ(s.branch.index(), b);
            EXPECT_TRUE(s.q == want[k]->q);
            EXPECT_EQ(s.converged, want[k]->converged);
            EXPECT_EQ(s.within_limits, want[k]->within_limits);
            EXPECT_EQ(s.singular_wrist, want[k]->singular_wrist);
            ++compared;
          }
        }
      }
      // the original joints are among their own branch's solutions (kAll)
      IkOptions o;
      o.turns = IkTurns::kAll;
      o.branch = ikBranch(m, q).index();
      solveIk(m, T, o, *one);
      double best = 1e9;
      for (int k = 0; k < one->count; ++k)
        best = std::min(best, (one->solutions[static_cast<size_t>(k)].q - q).cwiseAbs().maxCoeff());
      EXPECT_LE(best, 1e-9);
    }
    EXPECT_GT(compared, 1000);
  }
}

}  // namespace
}  // namespace roprec
