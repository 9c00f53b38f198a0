// The mixed-natural-coordinate model against independent references:
//  * FK and TCP Jacobian against Orocos KDL (kdl_parser on the same URDF file) at 1,000 seeded
//    random joint vectors per robot: position ≤ 1e-9 m, rotation ≤ 1e-9 rad, Jacobian ≤ 1e-9;
//  * Φ_q against central finite differences of Φ; the structured solves of A and Aᵀ against a
//    dense LU of the assembled A; R and Sc against finite differences of q(z);
//  * Newton from a warm start converges quadratically; no allocation in the per-pose path.
#include "compensator/robot/model.hpp"

#include <gtest/gtest.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <filesystem>
#include <random>

#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/counting_new.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using nc::Vec6;

struct Case {
  std::string label;
  std::string urdf;
  std::string base;  // "" = root
  std::string tip;
};

std::vector<Case> robotCases() {
  std::vector<Case> cases;
  for (const std::string& name : bundledRobotNames()) {
    const RobotCard card = loadRobotCard(bundledRobotsDir() + "/" + name + "/robot.xml");
    cases.push_back({name, card.urdf_path, "", card.flange_link});
  }
  const std::string corpus = test::corpusDir();
  if (!corpus.empty()) {
    for (const auto& e : fs::directory_iterator(corpus + "/urdf")) {
      if (e.path().extension() == ".urdf")
        cases.push_back({e.path().filename().string(), e.path().string(), "", ""});
    }
  }
  std::sort(cases.begin(), cases.end(),
            [](const Case& a, const Case& b) { return a.label < b.label; });
  return cases;
}

Vec6 randomJoints(const ChainDescription& c, std::mt19937& rng) {
  Vec6 q;
  for (int i = 0; i < 6; ++i) {
    const auto& j = c.joints[static_cast<size_t>(i)];
    std::uniform_real_distribution<double> d(std::max(j.lower, -2 * kPi),
                                             std::min(j.upper, 2 * kPi));
    q[i] = d(rng);
  }
  return q;
}

constexpr double kTol = 1e-9;

TEST(NaturalModel, ForwardKinematicsAndJacobianMatchKdl) {
  const auto cases = robotCases();
  if (cases.empty()) GTEST_SKIP() << "no robots and no corpus";
  const Pose tool = [] {
    Pose T = Pose::Identity();
    T.translation() = Vec3(0.012, -0.03, 0.25);
    T.linear() = rotationFromRpy(0.1, -0.2, 0.3);
    return T;
  }();
  for (const Case& cs : cases) {
    SCOPED_TRACE(cs.label);
    const ChainDescription chain = loadUrdfChain(cs.urdf, {cs.base, cs.tip});
    const nc::Model model = nc::buildModel(chain, {tool, 0.0, Vec3::Zero(), Mat3::Zero()});
    nc::Data data(model);
    const KDL::Chain kchain = test::kdlChain(cs.urdf, chain.base_link, chain.tip_link, tool);
    ASSERT_EQ(kchain.getNrOfJoints(), 6u);
    KDL::ChainFkSolverPos_recursive fk(kchain);
    KDL::ChainJntToJacSolver jac(kchain);
    KDL::JntArray kq(6);
    KDL::Frame F;
    KDL::Jacobian kJ(6);
    std::mt19937 rng(20261121);
    double worst_p = 0;
    double worst_r = 0;
    double worst_j = 0;
    for (int n = 0; n < 1000; ++n) {
      const Vec6 z = randomJoints(chain, rng);
      const nc::PositionResult pr = nc::forwardKinematics(model, data, z);
      ASSERT_TRUE(pr.converged) << "residual " << pr.residual;
      nc::tcpJacobian(model, data);
      for (int i = 0; i < 6; ++i) kq(static_cast<unsigned>(i)) = z[i];
      ASSERT_GE(fk.JntToCart(kq, F), 0);
      ASSERT_GE(jac.JntToJac(kq, kJ), 0);
      const Pose T = test::fromKdl(F);
      worst_p = std::max(worst_p, (data.T_W_tcp.translation() - T.translation()).norm());
      worst_r =
          std::max(worst_r, smallRotationDifference(data.T_W_tcp.linear(), T.linear()).norm());
      for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 6; ++c) {
          worst_j = std::max(worst_j, std::abs(data.J_tcp(r, c) - kJ(static_cast<unsigned>(r),
                                                                     static_cast<unsigned>(c))));
        }
      }
    }
    EXPECT_LE(worst_p, kTol);
    EXPECT_LE(worst_r, kTol);
    EXPECT_LE(worst_j, kTol);
  }
}

TEST(NaturalModel, FlangePoseEqualsChainProduct) {
  for (const Case& cs : robotCases()) {
    SCOPED_TRACE(cs.label);
    const ChainDescription chain = loadUrdfChain(cs.urdf, {cs.base, cs.tip});
    const nc::Model model = nc::buildModel(chain);
    nc::Data data(model);
    std::mt19937 rng(3);
    for (int n = 0; n < 50; ++n) {
      const Vec6 z = randomJoints(chain, rng);
      ASSERT_TRUE(nc::forwardKinematics(model, data, z).converged);
      const Pose ref = chainForwardKinematics(chain, z);
      EXPECT_LT((data.T_W_flange.matrix() - ref.matrix()).norm(), 1e-12);
    }
  }
}

/// A robot for the finite-difference and solve tests: the first bundled robot or corpus URDF.
ChainDescription someChain() {
  const auto cases = robotCases();
  if (cases.empty()) return {};
  return loadUrdfChain(cases.front().urdf, {cases.front().base, cases.front().tip});
}

Eigen::MatrixXd denseA(const nc::Model& model, const nc::Data& data) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nc::kNq, nc::kNq);
  nc::assemblePhiq(model, data, A.topRows(nc::kNc));
  for (int i = 0; i < 6; ++i) A(nc::kNc + i, nc::idxTheta(i)) = 1.0;
  return A;
}

TEST(NaturalModel, PhiqMatchesCentralDifferencesAndSolvesMatchDenseLu) {
  const ChainDescription chain = someChain();
  if (chain.file.empty()) GTEST_SKIP();
  const nc::Model model = nc::buildModel(chain);
  nc::Data data(model);
  std::mt19937 rng(11);
  for (int n = 0; n < 20; ++n) {
    const Vec6 z = randomJoints(chain, rng);
    ASSERT_TRUE(nc::solvePosition(model, data, z).converged);
    EXPECT_LE(data.Phi.lpNorm<Eigen::Infinity>(), model.tol_phi);
    Eigen::MatrixXd J(nc::kNc, nc::kNq);
    nc::assemblePhiq(model, data, J);
    // Central differences of Φ at a perturbed (non-solution) q as well: Φ_q is analytic anywhere.
    nc::VecQ q0 = data.q;
    std::normal_distribution<double> nd(0, 1e-3);
    for (int k = 0; k < nc::kNq; ++k) q0[k] += nd(rng);
    nc::Data d2 = data;
    d2.q = q0;
    nc::assemblePhiq(model, d2, J);
    const double h = 1e-6;
    for (int k = 0; k < nc::kNq; ++k) {
      nc::VecQ qp = q0;
      nc::VecQ qm = q0;
      qp[k] += h;
      qm[k] -= h;
      nc::evaluatePhi(model, d2, qp);
      const nc::VecC fp = d2.Phi;
      nc::evaluatePhi(model, d2, qm);
      const nc::VecC fd = (fp - d2.Phi) / (2 * h);
      EXPECT_LE((fd - J.col(k)).lpNorm<Eigen::Infinity>(), 1e-8) << "column " << k;
    }
    // Structured solves vs dense LU.
    nc::factorize(model, data);
    const Eigen::MatrixXd A = denseA(model, data);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    nc::VecQ r;
    for (int k = 0; k < nc::kNq; ++k) r[k] = nd(rng) * 1e3;
    nc::VecQ x;
    nc::solveA(model, data, r, x);
    const Eigen::VectorXd r_dense = r;
    const Eigen::VectorXd xr = lu.solve(r_dense);
    EXPECT_LE((x - xr).norm(), 1e-10 * (1.0 + xr.norm()));
    nc::VecQ y;
    nc::solveAT(model, data, r, y);
    const Eigen::VectorXd yr = lu.transpose().solve(r_dense);
    EXPECT_LE((y - yr).norm(), 1e-10 * (1.0 + yr.norm()));
  }
}

TEST(NaturalModel, VelocityTransformAndScMatchFiniteDifferencesOfPositionProblem) {
  const ChainDescription chain = someChain();
  if (chain.file.empty()) GTEST_SKIP();
  const nc::Model model = nc::buildModel(chain);
  nc::Data data(model);
  nc::Data dp(model);
  nc::Data dm(model);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  for (int n = 0; n < 10; ++n) {
    const Vec6 z = randomJoints(chain, rng);
    ASSERT_TRUE(nc::solvePosition(model, data, z).converged);
    const nc::MatR R = nc::velocityTransform(model, data);
    // Φ_q R = 0 and B R = I.
    Eigen::MatrixXd J(nc::kNc, nc::kNq);
    nc::assemblePhiq(model, data, J);
    EXPECT_LE((J * R).lpNorm<Eigen::Infinity>(), 1e-12);
    EXPECT_LE(
        (R.bottomRows<6>() - Eigen::Matrix<double, 6, 6>::Identity()).lpNorm<Eigen::Infinity>(),
        0.0);
    const double h = 1e-6;
    for (int j = 0; j < 6; ++j) {
      Vec6 zp = z;
      Vec6 zm = z;
      zp[j] += h;
      zm[j] -= h;
      ASSERT_TRUE(nc::solvePosition(model, dp, zp).converged);
      ASSERT_TRUE(nc::solvePosition(model, dm, zm).converged);
      const nc::VecQ fd = (dp.q - dm.q) / (2 * h);
      EXPECT_LE((fd - R.col(j)).lpNorm<Eigen::Infinity>(), 2e-8) << "column " << j;
    }
    // Sc = Ṙ ż: central difference of R(z) along ż.
    Vec6 zd;
    for (int i = 0; i < 6; ++i) zd[i] = ud(rng);
    nc::velocities(model, data, zd);
    const nc::VecQ Sc = nc::accelerationTerm(model, data, zd);
    ASSERT_TRUE(nc::solvePosition(model, dp, z + h * zd).converged);
    ASSERT_TRUE(nc::solvePosition(model, dm, z - h * zd).converged);
    const nc::MatR Rp = nc::velocityTransform(model, dp);
    const nc::MatR Rm = nc::velocityTransform(model, dm);
    const nc::VecQ fd = (Rp - Rm) / (2 * h) * zd;
    EXPECT_LE((fd - Sc).lpNorm<Eigen::Infinity>(), 2e-7);
  }
}

TEST(NaturalModel, NewtonFromWarmStartConvergesQuadratically) {
  const ChainDescription chain = someChain();
  if (chain.file.empty()) GTEST_SKIP();
  const nc::Model model = nc::buildModel(chain);
  nc::Data data(model);
  std::mt19937 rng(9);
  for (int n = 0; n < 50; ++n) {
    const Vec6 z = randomJoints(chain, rng);
    ASSERT_TRUE(nc::solvePosition(model, data, z).converged);
    Vec6 z2 = z;
    for (int i = 0; i < 6; ++i) z2[i] += 0.02 * (i % 2 ? 1 : -1);  // ~1° step, previous q as guess
    const nc::PositionResult r = nc::solvePosition(model, data, z2, nc::Guess::kWarmStart);
    EXPECT_TRUE(r.converged);
    EXPECT_LE(r.iterations, 5);
    EXPECT_LE(r.residual, model.tol_phi);
    const Pose ref = chainForwardKinematics(chain, z2);
    nc::framePoses(model, data);
    EXPECT_LT((data.T_W_flange.translation() - ref.translation()).norm(), 1e-12);
  }
}

TEST(NaturalModel, NonConvergenceIsReportedAsAValue) {
  const ChainDescription chain = someChain();
  if (chain.file.empty()) GTEST_SKIP();
  nc::Model model = nc::buildModel(chain);
  model.max_iterations = 0;
  nc::Data data(model);
  data.q.setConstant(0.3);  // a meaningless guess, no iterations allowed
  const nc::PositionResult r = nc::solvePosition(model, data, Vec6::Zero(), nc::Guess::kWarmStart);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_GT(r.residual, 1e-3);
}

TEST(NaturalModel, PerPosePathDoesNotAllocate) {
  const ChainDescription chain = someChain();
  if (chain.file.empty()) GTEST_SKIP();
  const nc::Model model = nc::buildModel(chain);
  nc::Data data(model);
  Vec6 z;
  z << 0.1, -1.2, 1.3, 0.4, 0.5, 0.6;
  nc::PositionResult r;
  nc::PositionResult r2;
  const long allocations = test::allocationsOf([&] {
    r = nc::forwardKinematics(model, data, z);
    nc::tcpJacobian(model, data);
    z[2] += 0.01;
    r2 = nc::solvePosition(model, data, z, nc::Guess::kWarmStart);
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r2.converged);
}

TEST(NaturalModel, KineticEnergyMatchesRigidBodyFormulas) {
  // ½ q̇ᵀ M q̇ (constant M of §4) vs Σ ½ m v_G² + ½ ωᵀ I_G ω from the same motion.
  const ChainDescription chain = someChain();
  if (chain.file.empty()) GTEST_SKIP();
  ChainDescription c = chain;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& in : c.inertials) {  // synthetic, full inertials with rotated principal axes
    in.mass = 10 + 5 * u(rng);
    in.com = Vec3(u(rng), u(rng), u(rng)) * 0.2;
    const Mat3 Rp = rotationFromRpy(u(rng), u(rng), u(rng));
    in.inertia = Rp * Vec3(1.0 + 0.5 * u(rng), 1.5, 2.0).asDiagonal() * Rp.transpose();
  }
  const nc::Model model = nc::buildModel(c);
  nc::Data data(model);
  for (int n = 0; n < 10; ++n) {
    Vec6 z;
    Vec6 zd;
    for (int i = 0; i < 6; ++i) {
      z[i] = u(rng);
      zd[i] = u(rng);
    }
    ASSERT_TRUE(nc::solvePosition(model, data, z).converged);
    nc::velocities(model, data, zd);
    double T_nc = 0;
    double T_ref = 0;
    for (int i = 0; i < 6; ++i) {
      const nc::Body& b = model.bodies[static_cast<size_t>(i)];
      // elements [p, u, v, w] of body i and their rates
      std::array<Vec3, 4> xd;
      xd[0] = i == 0 ? Vec3::Zero() : Vec3(data.qd.segment<3>(nc::idxPnext(i - 1)));
      xd[1] = i == 0 ? Vec3::Zero() : Vec3(data.qd.segment<3>(nc::idxUnext(i - 1)));
      xd[2] = data.qd.segment<3>(nc::idxV(i));
      xd[3] = data.qd.segment<3>(nc::idxW(i));
      for (int k = 0; k < 4; ++k) {
        for (int l = 0; l < 4; ++l)
          T_nc += 0.5 * b.K(k, l) * xd[static_cast<size_t>(k)].dot(xd[static_cast<size_t>(l)]);
      }
      // reference: body twist from the chain's geometric Jacobian (finite rotation of frames)
      const double h = 1e-7;
      Eigen::Matrix<double, 6, 1> zp = z + h * zd;
      Eigen::Matrix<double, 6, 1> zm = z - h * zd;
      auto linkPose = [&](const Vec6& zz) {
        Pose T = Pose::Identity();
        for (int k = 0; k <= i; ++k) {
          T = T * c.joints[static_cast<size_t>(k)].origin;
          T.rotate(Eigen::AngleAxisd(zz[k], c.joints[static_cast<size_t>(k)].axis));
        }
        return T;
      };
      const Pose Tp = linkPose(zp);
      const Pose Tm = linkPose(zm);
      const Pose T0 = linkPose(z);
      const Vec3 vG = (Tp * b.com - Tm * b.com) / (2 * h);
      const Vec3 w = smallRotationDifference(Tp.linear(), Tm.linear()) / (2 * h);
      const Mat3 I_W = T0.linear() * b.inertia * T0.linear().transpose();
      T_ref += 0.5 * b.mass * vG.squaredNorm() + 0.5 * w.dot(I_W * w);
    }
    EXPECT_NEAR(T_nc, T_ref, 1e-6 * T_ref);
  }
}

}  // namespace
}  // namespace roprec
