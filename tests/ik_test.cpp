// Analytic IK (compensator/robot/ik.hpp) against the chain's own product-of-transforms FK
// (chainForwardKinematics, an independent code path), on every corpus URDF and bundled robot.
#include "compensator/robot/ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>

#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "tests/support/counting_new.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string name;
  ChainDescription chain;
  IkModel model;
};

double rotAngle(const Mat3& a, const Mat3& b) {
  const Mat3 R = a * b.transpose();
  const Vec3 v = 0.5 * Vec3(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(v.norm(), 0.5 * (R.trace() - 1.0));
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  const std::string corpus = test::corpusDir();
  if (!corpus.empty()) {
    for (const char* f : {"kr120r2500pro.urdf", "kr16_2.urdf", "irb2400.urdf",
                          "irb6640_185_280.urdf", "r2000ic165f.urdf", "m20ia.urdf"}) {
      const std::string path = corpus + "/urdf/" + f;
      if (!fs::exists(path)) {  // the corpus is there but incomplete: a failure, not a skip
        ADD_FAILURE() << path << " is missing from the corpus";
        continue;
      }
      Case c;
      c.name = f;
      c.chain = loadUrdfChain(path);
      c.model = buildIkModel(c.chain);
      cases.push_back(std::move(c));
    }
  }
  for (const std::string& name : bundledRobotNames()) {
    Case c;
    c.name = name;
    const Robot r = loadRobot({name, "", ""});
    c.chain = r.chain;
    c.model = buildIkModel(r);
    cases.push_back(std::move(c));
  }
  return cases;
}

Vec6 randomWithinLimits(const ChainDescription& ch, std::mt19937& rng) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    const auto& j = ch.joints[static_cast<size_t>(i)];
    std::uniform_real_distribution<double> u(j.lower, j.upper);
    q[i] = u(rng);
  }
  return q;
}

double jointDistance(const Vec6& a, const Vec6& b) { return (a - b).cwiseAbs().maxCoeff(); }

TEST(Ik, RandomRoundTripAllRobots) {
  const auto cases = allCases();
  if (cases.empty()) GTEST_SKIP() << "no corpus and no bundled robots";
  auto result = std::make_unique<IkResult>();
  auto primary = std::make_unique<IkResult>();
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    EXPECT_TRUE(c.model.deviation.exact) << c.name;
    std::mt19937 rng(20261121);
    int full_branch_sets = 0;
    for (int n = 0; n < 1000; ++n) {
      const Vec6 q = randomWithinLimits(c.chain, rng);
      const Pose T = chainForwardKinematics(c.chain, q);
      IkOptions all;
      all.turns = IkTurns::kAll;
      // Caller-owned storage: no allocation per call.
      ASSERT_EQ(test::allocationsOf([&] { solveIk(c.model, T, all, *result); }), 0);
      ASSERT_GT(result->count, 0) << describeIkFailure(*result);
      ASSERT_FALSE(result->truncated);
      double best = 1e9;
      for (int k = 0; k < result->count; ++k) {
        const IkSolution& s = result->solutions[static_cast<size_t>(k)];
        const Pose Ts = chainForwardKinematics(c.chain, s.q);
        ASSERT_TRUE(s.converged);
        EXPECT_LE((Ts.translation() - T.translation()).norm(), 1e-9);
        EXPECT_LE(rotAngle(Ts.linear(), T.linear()), 1e-9);
        EXPECT_EQ(s.within_limits, withinLimits(c.model, s.q));
        if (k > 0) {  // deterministic order: branch, then turns
          const IkSolution& p = result->solutions[static_cast<size_t>(k - 1)];
          EXPECT_LE(p.branch.index(), s.branch.index());
        }
        best = std::min(best, jointDistance(s.q, q));
      }
      EXPECT_LE(best, 1e-9) << "original joints not among the " << result->count
                            << " solutions, n=" << n;

      // Primary mode: at most one solution per branch label away from singularities; joint vectors
      // distinct.
      solveIk(c.model, T, IkOptions{}, *primary);
      std::array<int, 8> seen{};
      bool singular = false;
      for (int k = 0; k < primary->count; ++k) {
        const IkSolution& s = primary->solutions[static_cast<size_t>(k)];
        singular = singular || s.singular_wrist || s.singular_elbow || s.singular_shoulder;
        ++seen[static_cast<size_t>(s.branch.index())];
        for (int l = 0; l < k; ++l) {
          EXPECT_GT(jointDistance(s.q, primary->solutions[static_cast<size_t>(l)].q), 1e-6);
        }
      }
      if (!singular) {
        for (int v : seen) EXPECT_LE(v, 1);
      }
      if (primary->count == 8 && !singular) ++full_branch_sets;
    }
    EXPECT_GT(full_branch_sets, 100)
        << "all 8 distinct branches should appear for many random poses";
  }
}

/// a and b are the same bits (−0 and +0 differ, NaN equals itself).
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectSameSolutions(const IkResult& a, const IkResult& b) {
  ASSERT_EQ(a.count, b.count);
  EXPECT_EQ(a.failure, b.failure);
  for (int k = 0; k < a.count; ++k) {
    const IkSolution& x = a.solutions[static_cast<size_t>(k)];
    const IkSolution& y = b.solutions[static_cast<size_t>(k)];
    for (int i = 0; i < 6; ++i) EXPECT_TRUE(sameBits(x.q[i], y.q[i])) << "joint " << i + 1;
    EXPECT_TRUE(sameBits(x.residual.position, y.residual.position));
    EXPECT_TRUE(sameBits(x.residual.rotation, y.residual.rotation));
    EXPECT_EQ(x.branch.index(), y.branch.index());
    EXPECT_TRUE(sameBits(x.branch.shoulder_margin_m, y.branch.shoulder_margin_m));
    EXPECT_TRUE(sameBits(x.branch.elbow_margin_rad, y.branch.elbow_margin_rad));
    EXPECT_TRUE(sameBits(x.branch.wrist_margin_rad, y.branch.wrist_margin_rad));
    EXPECT_EQ(x.converged, y.converged);
    EXPECT_EQ(x.iterations, y.iterations);
    EXPECT_EQ(x.within_limits, y.within_limits);
    EXPECT_EQ(x.singular_wrist, y.singular_wrist);
    EXPECT_EQ(x.singular_shoulder, y.singular_shoulder);
  }
}

// An IkArmCache reuses joints 1–3's forward kinematics and the shoulder/elbow margins where the
// joints are the same bits: one cache over random drill targets, each solved at 24 rotations about
// its axis (mostly the same wrist centre and joints 1–3, with runs of new ones), in one branch and
// in all, gives every solution of solveIk without it, bit for bit.
TEST(Ik, AnArmCacheGivesTheSolutionsOfSolveIkWithoutIt) {
  for (const std::string& name :
       {std::string("kuka-kr120-r2500-pro"), std::string("abb-irb6640-185-280")}) {
    SCOPED_TRACE(name);
    const Robot r = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(r);
    std::mt19937 rng(20261129);
    auto plain = std::make_unique<IkResult>();
    auto cached = std::make_unique<IkResult>();
    IkArmCache cache;
    int same_arm = 0;
    for (int n = 0; n < 200; ++n) {
      const Vec6 q = randomWithinLimits(r.chain, rng);
      const Pose T = chainForwardKinematics(r.chain, q);
      const int branch = ikBranch(m, q).index();
      for (int k = 0; k < 24; ++k) {
        Pose Tk = T;
        Tk.linear() = T.linear() * Eigen::AngleAxisd(2.0 * kPi * k / 24, Vec3::UnitZ()).matrix();
        for (const int b : {branch, -1}) {
          IkOptions o;
          o.seed = &q;
          o.branch = b;
          solveIk(m, Tk, o, *plain);
          o.arm_cache = &cache;
          const std::array<double, 3> before = cache.fk_q;
          solveIk(m, Tk, o, *cached);
          if (k > 0 && cached->count > 0 && sameBits(before[0], cache.fk_q[0]) &&
              sameBits(before[1], cache.fk_q[1]) && sameBits(before[2], cache.fk_q[2]))
            ++same_arm;
          SCOPED_TRACE(testing::Message()
                       << "target " << n << ", rotation " << k << ", branch " << b);
          expectSameSolutions(*cached, *plain);
        }
      }
    }
    EXPECT_GT(same_arm, 2000);  // the cache was read, not only written
  }
}

// A pose taught exactly at a joint limit (KR 120 A2 = +35.000°, its URDF upper limit) and written
// as a program writes it (mm with 3 decimals, i.e. rounded to 1e-6 m) is reachable: the rounding
// moves the exact IK solution up to ~1e-6 rad past the limit, which is no reason to refuse it.
TEST(Ik, APoseTaughtExactlyAtAJointLimitIsReachable) {
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  const IkModel m = buildIkModel(robot);
  auto result = std::make_unique<IkResult>();
  int checked = 0;
  for (const double q1 : {-0.4, 0.0, 0.3}) {
    for (const double q3 : {-1.2, -0.6, 0.2, 0.9}) {
      for (const double q5 : {-0.9, 0.7}) {
        Vec6 q;
        q << q1, m.upper[1], q3, 0.3, q5, -0.2;
        Pose T = ikForwardKinematics(m, q);
        for (int i = 0; i < 3; ++i)
          T.translation()[i] = std::round(T.translation()[i] * 1e6) / 1e6;  // 0.001 mm
        solveIk(m, T, IkOptions{}, *result);
        bool found = false;
        for (int k = 0; k < result->count; ++k) {
          const IkSolution& s = result->solutions[static_cast<size_t>(k)];
          found = found || (s.within_limits && (s.q - q).cwiseAbs().maxCoeff() < 1e-4);
        }
        EXPECT_TRUE(found) << "q1 " << q1 << " q3 " << q3 << " q5 " << q5 << ": "
                           << describeIkFailure(*result);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 24);
}

TEST(Ik, OpwParametersFromGeometry) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "no corpus";
  // ABB IRB 2400/10: published OPW parameters (Brandstötter et al. 2014 [S31], Table 1):
  // a1 = 100, a2 = -135, b = 0, c1 = 615, c2 = 705, c3 = 755, c4 = 85 (mm).
  const IkModel abb = buildIkModel(loadUrdfChain(corpus + "/urdf/irb2400.urdf"));
  EXPECT_NEAR(abb.opw.a1, 0.100, 1e-12);
  EXPECT_NEAR(abb.opw.a2, -0.135, 1e-12);
  EXPECT_NEAR(abb.opw.b, 0.0, 1e-12);
  EXPECT_NEAR(abb.opw.c1, 0.615, 1e-12);
  EXPECT_NEAR(abb.opw.c2, 0.705, 1e-12);
  EXPECT_NEAR(abb.opw.c3, 0.755, 1e-12);
  EXPECT_NEAR(abb.opw.c4, 0.085, 1e-12);
  // KUKA KR 120 R2500 pro, from the URDF's joint origins: A2 350 mm ahead and 675 mm above the
  // base, 1150 mm upper arm, 1000 mm forearm with the wrist 41 mm below the A3 line, 215 mm to the
  // flange.
  const std::string kr = corpus + "/urdf/kr120r2500pro.urdf";
  IkModelOptions ko;
  ko.reference_q << 0, -kPi / 2, kPi / 2, 0, 0, 0;
  const IkModel kuka = buildIkModel(loadUrdfChain(kr), ko);
  EXPECT_NEAR(kuka.opw.a1, 0.350, 1e-12);
  EXPECT_NEAR(kuka.opw.a2, 0.041, 1e-12);
  EXPECT_NEAR(kuka.opw.c1, 0.675, 1e-12);
  EXPECT_NEAR(kuka.opw.c2, 1.150, 1e-12);
  EXPECT_NEAR(kuka.opw.c3, 1.000, 1e-12);
  EXPECT_NEAR(kuka.opw.c4, 0.215, 1e-12);
}

TEST(Ik, PerturbedGeometryIsRefinedOnTheExactChain) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "no corpus";
  ChainDescription ch = loadUrdfChain(corpus + "/urdf/kr120r2500pro.urdf");
  // Non-ideal URDF: axis 3 tilted by 2 mrad, axis 6 offset 0.4 mm from axis 4/5's intersection.
  ch.joints[2].origin.linear() = Eigen::AngleAxisd(2e-3, Vec3::UnitX()).toRotationMatrix();
  ch.joints[5].origin.translation() += Vec3(0.0, 0.0004, 0.0);
  const IkModel m = buildIkModel(ch);
  EXPECT_FALSE(m.deviation.exact);
  std::mt19937 rng(7);
  auto result = std::make_unique<IkResult>();
  int found = 0;
  for (int n = 0; n < 300; ++n) {
    const Vec6 q = randomWithinLimits(ch, rng);
    const Pose T = chainForwardKinematics(ch, q);
    IkOptions o;
    o.turns = IkTurns::kAll;
    solveIk(m, T, o, *result);
    ASSERT_GT(result->count, 0);
    double best = 1e9;
    for (int k = 0; k < result->count; ++k) {
      const IkSolution& s = result->solutions[static_cast<size_t>(k)];
      if (!s.converged) continue;  // flagged, not silently wrong
      const Pose Ts = chainForwardKinematics(ch, s.q);
      EXPECT_LE((Ts.translation() - T.translation()).norm(), 1e-9);
      EXPECT_LE(rotAngle(Ts.linear(), T.linear()), 1e-9);
      best = std::min(best, jointDistance(s.q, q));
    }
    found += best <= 1e-9 ? 1 : 0;
  }
  EXPECT_GE(found, 297);  // all but poses within a few mrad of a singularity
}

TEST(Ik, NonOpwChainIsRejectedWithFileAndLine) {
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) GTEST_SKIP() << "no corpus";
  ChainDescription ch = loadUrdfChain(corpus + "/urdf/kr120r2500pro.urdf");
  ch.joints[5].origin.translation() += Vec3(0.0, 0.1, 0.0);  // wrist axes 100 mm apart
  try {
    buildIkModel(ch);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("kr120r2500pro.urdf"), std::string::npos);
    EXPECT_GT(e.line(), 0);
    EXPECT_NE(e.message().find("do not intersect"), std::string::npos) << e.message();
  }
  ChainDescription ch2 = loadUrdfChain(corpus + "/urdf/kr120r2500pro.urdf");
  ch2.joints[2].axis = Vec3(0, 0, 1);  // axis 3 no longer parallel to axis 2
  EXPECT_THROW(buildIkModel(ch2), InputError);
}

class IkSingular : public ::testing::Test {
 protected:
  void SetUp() override {
    if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
    robot_ = loadRobot({bundledRobotNames().front(), "", ""});
    model_ = buildIkModel(robot_);
    result_ = std::make_unique<IkResult>();
  }
  void expectAllReenter(const Pose& T) {
    for (int k = 0; k < result_->count; ++k) {
      const IkSolution& s = result_->solutions[static_cast<size_t>(k)];
      EXPECT_TRUE(s.converged);
      const Pose Ts = chainForwardKinematics(robot_.chain, s.q);
      EXPECT_LE((Ts.translation() - T.translation()).norm(), 1e-9);
      EXPECT_LE(rotAngle(Ts.linear(), T.linear()), 1e-9);
    }
  }
  Robot robot_;
  IkModel model_;
  std::unique_ptr<IkResult> result_;
};

TEST_F(IkSingular, WristAtAndNear) {
  for (double q5 : {0.0, 1e-7, 1e-5}) {
    Vec6 q;
    q << 0.3, -1.2, 1.4, 0.7, q5 - model_.alpha, -0.4;
    const Pose T = chainForwardKinematics(robot_.chain, q);
    IkOptions o;
    o.seed = &q;
    solveIk(model_, T, o, *result_);
    ASSERT_GT(result_->count, 0);
    expectAllReenter(T);
    int flagged = 0;
    double best = 1e9;
    for (int k = 0; k < result_->count; ++k) {
      const IkSolution& s = result_->solutions[static_cast<size_t>(k)];
      if (std::abs(s.q[4] + model_.alpha) < 1e-3 ||
          std::abs(std::abs(s.q[4] + model_.alpha) - kPi) < 1e-3) {
        EXPECT_TRUE(s.singular_wrist);
        ++flagged;
      }
      best = std::min(best, jointDistance(s.q, q));
    }
    EXPECT_GE(flagged, 2);
    // At the singularity only q4 + q6 is defined: q4 is taken from the seed, so the seed is
    // recovered.
    EXPECT_LE(best, q5 == 1e-7 ? 1e-8 : 1e-9) << "q5=" << q5;
  }
}

TEST_F(IkSingular, ShoulderAtAndNear) {
  // Wrist centre on axis 1 (the lateral offset b of the bundled robots is 0).
  ASSERT_NEAR(model_.b, 0.0, 1e-12);
  for (double off : {0.0, 1e-7}) {
    const Mat3 R = rotationFromZyx(0.2, 0.9, -0.3);
    const Vec3 C = model_.o + model_.F0 * Vec3(off, 0.0, 0.6);
    Pose T = Pose::Identity();
    T.linear() = R;
    T.translation() = C - R * model_.c_tip;
    Vec6 seed;
    seed << 0.25, -1.0, 1.0, 0.0, 0.5, 0.0;
    IkOptions o;
    o.seed = &seed;
    solveIk(model_, T, o, *result_);
    ASSERT_GT(result_->count, 0) << describeIkFailure(*result_);
    expectAllReenter(T);
    for (int k = 0; k < result_->count; ++k) {
      const IkSolution& s = result_->solutions[static_cast<size_t>(k)];
      EXPECT_TRUE(s.singular_shoulder);
      if (off == 0.0) {  // q1 free: seed (front) or seed + π (back)
        const double d = std::abs(wrapAngle(s.q[0] - seed[0]));
        EXPECT_TRUE(d < 1e-12 || std::abs(d - kPi) < 1e-12) << s.q[0];
      }
    }
  }
}

TEST_F(IkSingular, ElbowStretched) {
  // ψ = 0: upper arm and forearm (to the wrist centre) aligned.
  Vec6 q;
  q << -0.2, -0.6, model_.sigma3 * (0.0 - model_.psi0), 0.4, 0.8, 0.1;
  EXPECT_LT(ikBranch(model_, q).elbow_margin_rad, 1e-12);
  const Pose T = chainForwardKinematics(robot_.chain, q);
  IkOptions o;
  o.turns = IkTurns::kAll;
  solveIk(model_, T, o, *result_);
  ASSERT_GT(result_->count, 0);
  expectAllReenter(T);
  double best = 1e9;
  for (int k = 0; k < result_->count; ++k) {
    const IkSolution& s = result_->solutions[static_cast<size_t>(k)];
    if (s.branch.shoulder == ikBranch(model_, q).shoulder) {
      EXPECT_TRUE(s.singular_elbow);
    }
    best = std::min(best, jointDistance(s.q, q));
  }
  // acos near 1 loses half the digits: sqrt(eps) ~ 1.5e-8 rad in q2/q3 while the pose is exact.
  EXPECT_LE(best, 1e-7);
  // 1 mm beyond the stretched arm (along axis 2 → wrist centre): that shoulder branch has no
  // solution.
  const Pose T2 = robot_.chain.joints[0].origin *
                  Eigen::AngleAxisd(q[0], robot_.chain.joints[0].axis) *
                  robot_.chain.joints[1].origin;
  const Vec3 C = T * model_.c_tip;
  Pose far = T;
  far.translation() += (C - T2.translation()).normalized() * 1e-3;
  solveIk(model_, far, IkOptions{}, *result_);
  for (int k = 0; k < result_->count; ++k) {
    EXPECT_NE(result_->solutions[static_cast<size_t>(k)].branch.shoulder,
              ikBranch(model_, q).shoulder);
  }
}

TEST_F(IkSingular, UnreachableAndNonFinite) {
  Pose T = Pose::Identity();
  T.translation() = Vec3(10.0, 0.0, 1.0);
  solveIk(model_, T, IkOptions{}, *result_);
  EXPECT_EQ(result_->count, 0);
  EXPECT_EQ(result_->failure, IkFailure::kOutOfReach);
  EXPECT_NEAR(result_->failure_value, 10.0 - 3.0, 1.0);  // roughly 7 m beyond a ~3 m reach
  T.translation() = Vec3(std::nan(""), 0.0, 1.0);
  solveIk(model_, T, IkOptions{}, *result_);
  EXPECT_EQ(result_->count, 0);
  EXPECT_EQ(result_->failure, IkFailure::kNotFinite);
}

TEST(Ik, SeededNearSolutionNoAllocation) {
  const auto cases = allCases();
  if (cases.empty()) GTEST_SKIP() << "no corpus and no bundled robots";
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    int newton = 0;
    for (int n = 0; n < 500; ++n) {
      const Vec6 q = randomWithinLimits(c.chain, rng);
      const IkBranch bq = ikBranch(c.model, q);
      // Away from singularities (there a 2 mm move may need large joint motion: tested separately).
      if (bq.wrist_margin_rad < 0.1 || bq.elbow_margin_rad < 0.1 || bq.shoulder_margin_m < 0.1)
        continue;
      Pose T = chainForwardKinematics(c.chain, q);
      // A hole correction: ≤ 2 mm and ≤ 0.5° away from the seed's pose.
      T.translation() += 2e-3 * Vec3(d(rng), d(rng), d(rng)) / std::sqrt(3.0);
      T.linear() =
          Eigen::AngleAxisd(0.5 * kDeg * d(rng), Vec3(d(rng), d(rng), d(rng)).normalized()) *
          T.linear();
      IkNearResult r;
      ASSERT_EQ(test::allocationsOf([&] { r = solveIkNear(c.model, T, q); }), 0);
      ASSERT_TRUE(r.converged);
      const Pose Ts = chainForwardKinematics(c.chain, r.q);
      EXPECT_LE((Ts.translation() - T.translation()).norm(), 1e-9);
      EXPECT_LE(rotAngle(Ts.linear(), T.linear()), 1e-9);
      EXPECT_EQ(ikBranch(c.model, r.q).index(), ikBranch(c.model, q).index());
      EXPECT_LT(jointDistance(r.q, q), 0.2);
      newton += r.analytic_fallback ? 0 : 1;
      if (!r.analytic_fallback) {
        EXPECT_LE(r.iterations, 5);
      }
    }
    EXPECT_GT(newton, 200);
  }
}

TEST(Ik, SeededFarFromTargetFallsBackToTheSeedsBranch) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  const Robot robot = loadRobot({bundledRobotNames().back(), "", ""});
  const IkModel m = buildIkModel(robot);
  Vec6 q;
  q << 0.5, 0.2, -0.3, 1.0, 0.9, -1.0;
  Vec6 seed = q;
  seed[0] -= 1.5;  // far away in joints 1, 4, 6, which do not change the branch labels
  seed[3] -= 1.8;
  seed[5] += 2.0;
  ASSERT_EQ(ikBranch(m, q).index(), ikBranch(m, seed).index());
  const Pose T = chainForwardKinematics(robot.chain, q);
  IkNearOptions o;
  o.max_iterations = 2;  // Newton alone cannot get there
  const IkNearResult r = solveIkNear(m, T, seed, o);
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r.analytic_fallback);
  EXPECT_LE(jointDistance(r.q, q), 1e-9);
}

TEST(Ik, TurnsWithinLimits) {
  if (bundledRobotNames().empty()) GTEST_SKIP() << "no bundled robots";
  for (const std::string& name : bundledRobotNames()) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot({name, "", ""});
    const IkModel m = buildIkModel(robot);
    Vec6 q;
    q << 0.1, -1.0, 1.2, 0.3, 0.7, 0.2;
    q = q.cwiseMax(m.lower).cwiseMin(m.upper);
    const Pose T = chainForwardKinematics(robot.chain, q);
    auto all = std::make_unique<IkResult>();
    IkOptions o;
    o.turns = IkTurns::kAll;
    solveIk(m, T, o, *all);
    auto primary = std::make_unique<IkResult>();
    solveIk(m, T, IkOptions{}, *primary);
    ASSERT_GT(primary->count, 0);
    EXPECT_GE(all->count, primary->count);
    // Every turn variant differs from its wrapped base by whole turns and lies within the limits.
    for (int k = 0; k < all->count; ++k) {
      const IkSolution& s = all->solutions[static_cast<size_t>(k)];
      if (!s.within_limits) continue;
      for (int i = 0; i < 6; ++i) {
        EXPECT_GE(s.q[i], m.lower[i] - 1e-12);
        EXPECT_LE(s.q[i], m.upper[i] + 1e-12);
        EXPECT_NEAR(std::remainder(s.q[i] - wrapAngle(s.q[i]), 2 * kPi), 0.0, 1e-12);
      }
    }
    // Expected count of variants per branch = Π_i #{k : wrapped_i + 2πk within limits}.
    int expected = 0;
    for (int k = 0; k < primary->count; ++k) {
      const IkSolution& s = primary->solutions[static_cast<size_t>(k)];
      if (!s.within_limits) {
        ++expected;
        continue;
      }
      int prod = 1;
      for (int i = 0; i < 6; ++i) {
        const double w = wrapAngle(s.q[i]);
        int n = 0;
        for (int t = -3; t <= 3; ++t) {
          const double v = w + 2 * kPi * t;
          n += (v >= m.lower[i] - 1e-12 && v <= m.upper[i] + 1e-12) ? 1 : 0;
        }
        prod *= n;
      }
      expected += prod;
    }
    EXPECT_EQ(all->count, expected);
  }
}

TEST(Ik, TurnEnumerationIsBoundedWhateverTheModelsLimits) {
  IkModel m = buildIkModel(loadRobot({"kuka-kr120-r2500-pro", "", ""}));
  const Vec6 q = (Vec6() << 0.1, -1.2, 1.4, 0.3, 0.7, -0.2).finished();
  const Pose T = ikForwardKinematics(m, q);
  for (const double lim : {1e300, 1e12, std::numeric_limits<double>::infinity()}) {
    m.lower = Vec6::Constant(-lim);
    m.upper = Vec6::Constant(lim);
    for (const IkTurns turns : {IkTurns::kPrimary, IkTurns::kAll}) {
      IkOptions opt;
      opt.turns = turns;
      IkResult r;
      solveIk(m, T, opt, r);  // an unbounded enumeration would not end within the time limit
      EXPECT_GT(r.count, 0);
      EXPECT_LE(r.count, kIkMaxSolutions);
      if (turns == IkTurns::kAll) {
        EXPECT_TRUE(r.truncated) << "limit " << lim;
      }
    }
  }
}

TEST(Ik, FailureMessagesHaveNoInfOrNan) {
  IkResult r;
  r.failure = IkFailure::kOutOfReach;
  r.failure_value = std::numeric_limits<double>::infinity();
  std::string msg = describeIkFailure(r);
  EXPECT_EQ(msg.find("inf "), std::string::npos) << msg;
  r.failure_value = std::numeric_limits<double>::quiet_NaN();
  msg = describeIkFailure(r);
  EXPECT_EQ(msg.find("nan"), std::string::npos) << msg;
  r.failure_value = 1e300;
  msg = describeIkFailure(r);
  EXPECT_LT(msg.size(), 120u) << msg;
}

}  // namespace
}  // namespace roprec
