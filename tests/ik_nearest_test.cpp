// solveIkNearest (ik.hpp) against an independent selection over solveIk's full list: the admissible
// solution (converged, in limits, not wrist/shoulder singular) with the smallest weighted joint
// distance, ties to the first in the list. Every bundled robot and corpus URDF, random in-limit
// targets with seeds near and far (other branches nearer, wrist flips, near-singular wrists,
// seeds a turn away), a perturbed (non-exact) chain, and unreachable targets; and with the
// candidates computed ahead (ikCandidates, predictHoles' parallel stage): the same solution, bit
// for bit, and candidates marked not valid where the reference chooses a joint (a singular wrist).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <random>

#include "compensator/robot/ik.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

struct Case {
  std::string name;
  ChainDescription chain;
  IkModel model;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& name : bundledRobotNames()) {
    const Robot r = loadRobot({name, "", ""});
    out.push_back({name, r.chain, buildIkModel(r)});
  }
  const std::string corpus = test::corpusDir();
  EXPECT_FALSE(corpus.empty()) << "corpus absent";
  if (corpus.empty()) return out;
  for (const char* f : {"kr120r2500pro.urdf", "kr16_2.urdf", "irb2400.urdf", "irb6640_185_280.urdf",
                        "r2000ic165f.urdf", "m20ia.urdf"}) {
    const std::string path = corpus + "/urdf/" + f;
    if (!std::filesystem::exists(path)) {
      ADD_FAILURE() << path << " is missing from the corpus";
      continue;
    }
    ChainDescription ch = loadUrdfChain(path);
    IkModel m = buildIkModel(ch);
    out.push_back({f, ch, m});
  }
  // a non-exact chain (refinement moves q: the full path)
  ChainDescription ch = out.front().chain;
  ch.joints[2].origin.linear() = Eigen::AngleAxisd(2e-3, Vec3::UnitX()).toRotationMatrix();
  ch.joints[5].origin.translation() += Vec3(0.0, 0.0004, 0.0);
  out.push_back({"perturbed " + out.front().name, ch, buildIkModel(ch)});
  return out;
}

/// Joints within the chain's limits (clipped to ±2π), one draw of `unit` (−1..1) per joint.
Vec6 randomJoints(const ChainDescription& chain, std::mt19937& rng,
                  std::uniform_real_distribution<double>& unit) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    const ChainJoint& j = chain.joints[static_cast<size_t>(i)];
    const double lo = std::max(j.lower, -2.0 * kPi);
    const double hi = std::min(j.upper, 2.0 * kPi);
    q[i] = lo + (hi - lo) * 0.5 * (1.0 + unit(rng));
  }
  return q;
}

/// The reference: solveIk's list, then the first admissible solution of smallest distance.
bool referenceNearest(const IkModel& m, const Pose& T, const Vec6& ref,
                      const std::array<double, 6>& w, IkResult& all, IkSolution& best) {
  IkOptions o;
  o.seed = &ref;
  solveIk(m, T, o, all);
  bool found = false;
  double bd = 0;
  for (int i = 0; i < all.count; ++i) {
    const IkSolution& s = all.solutions[static_cast<size_t>(i)];
    if (!s.within_limits || !s.converged || s.singular_wrist || s.singular_shoulder) continue;
    double d = 0;
    for (int j = 0; j < 6; ++j)
      d += w[static_cast<size_t>(j)] * (s.q[j] - ref[j]) * (s.q[j] - ref[j]);
    if (!found || d < bd) {
      best = s;
      bd = d;
      found = true;
    }
  }
  return found;
}

TEST(IkNearest, SameChoiceAsTheFullListOnEveryRobot) {
  const std::array<double, 6> w{1.0, 1.0, 1.0, 0.5, 0.5, 0.3};
  auto all = std::make_unique<IkResult>();
  auto scratch = std::make_unique<IkResult>();
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0;
  int none = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    for (int n = 0; n < 300; ++n) {
      Vec6 q = randomJoints(c.chain, rng, unit);
      if (n % 10 == 0) q[4] = 1e-4 * unit(rng);  // near the wrist singularity
      const Pose T = ikForwardKinematics(c.model, q);
      Vec6 ref = q;
      switch (n % 4) {
        case 0:  // seed near the solution
          for (int i = 0; i < 6; ++i) ref[i] += 0.05 * unit(rng);
          break;
        case 1:  // seed anywhere: another branch may be nearer
          for (int i = 0; i < 6; ++i) ref[i] = 3.0 * unit(rng);
          break;
        case 2:  // a wrist flip away
          ref[3] += kPi;
          ref[4] = -ref[4];
          ref[5] += kPi;
          break;
        default:  // a turn away on axis 6
          ref[5] += 2.0 * kPi * (unit(rng) > 0 ? 1 : -1);
      }
      IkSolution a;
      IkSolution b;
      const bool fa = solveIkNearest(c.model, T, ref, w, *scratch, a);
      const bool fb = referenceNearest(c.model, T, ref, w, *all, b);
      ASSERT_EQ(fa, fb) << "n " << n;
      if (!fa) {
        ++none;
        EXPECT_EQ(scratch->count, all->count);  // the full list for the caller's reason
        continue;
      }
      ++compared;
      EXPECT_TRUE(a.q == b.q) << a.q.transpose() << "\n" << b.q.transpose();
      EXPECT_EQ(a.branch.index(), b.branch.index());
      EXPECT_EQ(a.turn, b.turn);
      EXPECT_EQ(a.converged, b.converged);
      EXPECT_EQ(a.within_limits, b.within_limits);
      EXPECT_EQ(a.singular_elbow, b.singular_elbow);
      EXPECT_EQ(a.branch.wrist_margin_rad, b.branch.wrist_margin_rad);
    }
  }
  EXPECT_GT(compared, 2000);
  RecordProperty("without_admissible", none);
}

TEST(IkNearest, CandidatesComputedAheadGiveTheSameSolutionBitForBit) {
  const std::array<double, 6> w{1.0, 1.0, 1.0, 0.5, 0.5, 0.3};
  auto r1 = std::make_unique<IkResult>();
  auto r2 = std::make_unique<IkResult>();
  auto cand = std::make_unique<IkCandidates>();
  std::mt19937 rng(1515);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0;
  int singular = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    for (int n = 0; n < 200; ++n) {
      Vec6 q = randomJoints(c.chain, rng, unit);
      if (n % 10 == 0) q[4] = 0.0;  // on the wrist singularity: the reference picks q4
      if (n % 10 == 1) q[4] = 1e-6 * unit(rng);
      Pose T = ikForwardKinematics(c.model, q);
      if (n % 50 == 7) T.translation() *= 10.0;  // out of reach
      Vec6 ref = q;
      for (int i = 0; i < 6; ++i) ref[i] += (n % 2 ? 3.0 : 0.05) * unit(rng);
      ikCandidates(c.model, T, *cand);
      EXPECT_EQ(cand->valid && !c.model.deviation.exact, false);
      singular += c.model.deviation.exact && !cand->valid ? 1 : 0;
      IkSolution a;
      IkSolution b;
      const bool fa = solveIkNearest(c.model, T, ref, w, *r1, a);
      const bool fb = solveIkNearest(c.model, T, ref, w, cand.get(), *r2, b);
      ASSERT_EQ(fa, fb) << "n " << n;
      if (!fa) {
        EXPECT_EQ(r1->count, r2->count);
        EXPECT_EQ(r1->failure, r2->failure);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(r1->failure_value),
                  std::bit_cast<std::uint64_t>(r2->failure_value));
        continue;
      }
      ++compared;
      for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a.q[i]), std::bit_cast<std::uint64_t>(b.q[i]))
            << "n " << n << " joint " << i;
      }
      EXPECT_EQ(a.branch.index(), b.branch.index());
      EXPECT_EQ(a.turn, b.turn);
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a.residual.position),
                std::bit_cast<std::uint64_t>(b.residual.position));
      EXPECT_EQ(a.singular_wrist, b.singular_wrist);
      EXPECT_EQ(a.singular_shoulder, b.singular_shoulder);
    }
  }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(singular, 10);  // the fallback (candidates that depend on the reference) was taken
}

TEST(IkNearest, UnreachableTargetGivesTheFailure) {
  const Case c = cases().front();
  Pose T = ikForwardKinematics(c.model, Vec6::Zero());
  T.translation() *= 10.0;
  auto r = std::make_unique<IkResult>();
  IkSolution s;
  EXPECT_FALSE(solveIkNearest(c.model, T, Vec6::Zero(), {1, 1, 1, 1, 1, 1}, *r, s));
  EXPECT_EQ(r->count, 0);
  EXPECT_EQ(r->failure, IkFailure::kOutOfReach);
  EXPECT_GT(r->failure_value, 1.0);
}

}  // namespace
}  // namespace roprec
