// Milling path compensation (issue 7 item 5): every point of the sample wall pass is compensated
// with the coupled force iteration; the commands, fed to an independent nonlinear joint-compliance
// equilibrium computed here with KDL (FK + RNE, same stiffness, tool mass and converged milling
// force on the tool), put the tool on the nominal path ≤ 0.5 µm; through the CLI only the path
// targets' bytes change.
#include "compensator/compensation/milling_compensation.hpp"

#include <gtest/gtest.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>

#include <sstream>

#include "plugin/api/prediction_setup.hpp"
#include "postproc/program.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

TEST(MillingCompensation, PathLandsOnTheNominalPathAgainstKdl) {
  const std::string cell = test::sourceDir() + "/samples/cells/alu-milling-7075.xml";
  const std::string prog = test::sourceDir() + "/samples/milling/wall_pass.src";
  const api::PredictionContext c =
      api::loadPredictionContext(cell, prog, std::nullopt, "", 0.5, false);
  const postproc::Program& p = *c.job.program;
  std::vector<Pose> points;
  for (const postproc::Motion& m : p.motions) {
    if (m.type != postproc::MotionType::kLinear || m.target < 0) continue;
    const postproc::Frame& f = p.frames[static_cast<size_t>(m.base)];
    ASSERT_TRUE(f.resolved);
    points.push_back(f.pose * postproc::targetPose(p, p.targets()[static_cast<size_t>(m.target)]));
  }
  ASSERT_GE(points.size(), 25u);
  const auto comp = compensateMillingPath(c.model, points);
  // KDL: chain + tool segment; the milling force acts on the tool in the TCP frame (X feed = tool
  // x, Z = −tool z, Y = −tool y)
  const ChainDescription& ch = c.robot.chain;
  KDL::Chain kc = test::kdlChain(c.robot.card.urdf_path, ch.base_link, ch.tip_link);
  const Pose T_tcp_flange = c.tool.T_flange_tcp.inverse();
  const Vec3 com = T_tcp_flange * c.tool.com;
  kc.addSegment(
      KDL::Segment("tool", KDL::Joint(KDL::Joint::None), test::toKdl(c.tool.T_flange_tcp),
                   KDL::RigidBodyInertia(c.tool.mass, KDL::Vector(com.x(), com.y(), com.z()))));
  KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
  KDL::ChainFkSolverPos_recursive fk(kc);
  for (size_t i = 0; i < comp.size(); ++i) {
    ASSERT_TRUE(comp[i].ok) << i << ": " << comp[i].reason;
    EXPECT_TRUE(comp[i].coupling_converged);
    EXPECT_LE(comp[i].residual.norm(), 1e-7) << i;
    const Vec3 Ft(comp[i].force.x(), -comp[i].force.y(), -comp[i].force.z());
    nc::Vec6 th = comp[i].theta_cmd;
    for (int it = 0; it < 200; ++it) {
      KDL::JntArray q(6);
      KDL::JntArray z(6);
      KDL::JntArray t(6);
      for (unsigned j = 0; j < 6; ++j) q(j) = th[j];
      KDL::Wrenches f(kc.getNrOfSegments(), KDL::Wrench::Zero());
      f.back() = KDL::Wrench(KDL::Vector(Ft.x(), Ft.y(), Ft.z()), KDL::Vector::Zero());
      rne.CartToJnt(q, z, z, f, t);
      for (int j = 0; j < 6; ++j)
        th[j] = comp[i].theta_cmd[j] - t(static_cast<unsigned>(j)) / c.model.compliance.k[j];
    }
    KDL::JntArray q(6);
    for (unsigned j = 0; j < 6; ++j) q(j) = th[j];
    KDL::Frame F;
    fk.JntToCart(q, F);
    EXPECT_LE((Vec3(F.p.x(), F.p.y(), F.p.z()) - points[i].translation()).norm(), 0.5e-6)
        << "point " << i;
  }
}

TEST(MillingCompensation, CliChangesOnlyThePathTargets) {
  const std::string dir = test::tempDir("mill");
  const std::string prog = test::sourceDir() + "/samples/milling/wall_pass.src";
  const auto r = test::runRoprec("compensate --cell '" + test::sourceDir() +
                                 "/samples/cells/alu-milling-7075.xml' '" + prog + "' -o '" + dir +
                                 "/out.src' --targets '" + dir + "/t.json'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream a(test::readFile(prog));
  std::istringstream b(test::readFile(dir + "/out.src"));
  std::string la;
  std::string lb;
  int changed = 0;
  while (std::getline(a, la)) {
    ASSERT_TRUE(std::getline(b, lb));
    if (la == lb) continue;
    ++changed;
    EXPECT_EQ(la.rfind("LIN {", 0), 0u) << la;
  }
  EXPECT_FALSE(std::getline(b, lb));
  EXPECT_EQ(changed, 27);
  EXPECT_NE(test::readFile(dir + "/t.json").find("\"force_fixed_point_iterations\""),
            std::string::npos);
}

}  // namespace
}  // namespace roprec
