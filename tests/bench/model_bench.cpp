// FK + TCP Jacobian per pose: roprec's natural-coordinate model vs Orocos KDL, same URDF, same
// binary. KR 120-class chain from the bundled robots (or the corpus).
#include <benchmark/benchmark.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include <random>

#include "compensator/robot/model.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace {

using namespace roprec;

struct Fixture {
  ChainDescription chain;
  nc::Model model;
  KDL::Chain kchain;
  std::vector<nc::Vec6> poses;
  Fixture() {
    std::string urdf;
    std::string tip;
    const auto names = bundledRobotNames();
    if (std::find(names.begin(), names.end(), "kuka-kr120-r2500-pro") != names.end()) {
      const RobotCard card = loadRobotCard(bundledRobotsDir() + "/kuka-kr120-r2500-pro/robot.xml");
      urdf = card.urdf_path;
      tip = card.flange_link;
    } else {
      urdf = test::corpusDir() + "/urdf/kr120r2500pro.urdf";
      tip = "flange";
    }
    chain = loadUrdfChain(urdf, {"", tip});
    model = nc::buildModel(chain);
    kchain = test::kdlChain(urdf, chain.base_link, chain.tip_link);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int i = 0; i < 256; ++i) {
      nc::Vec6 q;
      for (int k = 0; k < 6; ++k) q[k] = u(rng);
      poses.push_back(q);
    }
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_Roprec_FK(benchmark::State& st) {
  Fixture& f = fixture();
  nc::Data data(f.model);
  size_t i = 0;
  for (auto _ : st) {
    nc::forwardKinematics(f.model, data, f.poses[i++ & 255]);
    benchmark::DoNotOptimize(data.T_W_flange);
  }
}
BENCHMARK(BM_Roprec_FK);

void BM_Roprec_FK_Jacobian(benchmark::State& st) {
  Fixture& f = fixture();
  nc::Data data(f.model);
  size_t i = 0;
  for (auto _ : st) {
    nc::forwardKinematics(f.model, data, f.poses[i++ & 255]);
    nc::tcpJacobian(f.model, data);
    benchmark::DoNotOptimize(data.J_tcp);
  }
}
BENCHMARK(BM_Roprec_FK_Jacobian);

void BM_KDL_FK(benchmark::State& st) {
  Fixture& f = fixture();
  KDL::ChainFkSolverPos_recursive fk(f.kchain);
  KDL::JntArray q(6);
  KDL::Frame F;
  size_t i = 0;
  for (auto _ : st) {
    const auto& p = f.poses[i++ & 255];
    for (unsigned k = 0; k < 6; ++k) q(k) = p[k];
    fk.JntToCart(q, F);
    benchmark::DoNotOptimize(F);
  }
}
BENCHMARK(BM_KDL_FK);

void BM_KDL_FK_Jacobian(benchmark::State& st) {
  Fixture& f = fixture();
  KDL::ChainFkSolverPos_recursive fk(f.kchain);
  KDL::ChainJntToJacSolver jac(f.kchain);
  KDL::JntArray q(6);
  KDL::Frame F;
  KDL::Jacobian J(6);
  size_t i = 0;
  for (auto _ : st) {
    const auto& p = f.poses[i++ & 255];
    for (unsigned k = 0; k < 6; ++k) q(k) = p[k];
    fk.JntToCart(q, F);
    jac.JntToJac(q, J);
    benchmark::DoNotOptimize(J);
  }
}
BENCHMARK(BM_KDL_FK_Jacobian);

}  // namespace
