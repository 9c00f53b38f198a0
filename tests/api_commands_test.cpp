// The per-pose and per-file API behind fk, ik, deflect, simulate, forces, inspect, convert and
// robots (plugin/api/), called directly: the numbers and texts equal what the CLI prints for the
// same input, and the errors are the documented ones.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "compensator/support/error.hpp"
#include "plugin/api/convert.hpp"
#include "plugin/api/deflect.hpp"
#include "plugin/api/forces.hpp"
#include "plugin/api/inspect.hpp"
#include "plugin/api/kinematics.hpp"
#include "plugin/api/plan_test.hpp"
#include "plugin/api/robots.hpp"
#include "plugin/api/simulate.hpp"
#include "plugin/report/deflect_json.hpp"
#include "plugin/report/forces_output.hpp"
#include "plugin/report/inspect_output.hpp"
#include "plugin/report/kinematics_json.hpp"
#include "plugin/report/robots_output.hpp"
#include "plugin/report/simulate_output.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nlohmann::json;

std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

nc::Vec6 degrees(double a, double b, double c, double d, double e, double f) {
  return (nc::Vec6() << a, b, c, d, e, f).finished() * kDeg;
}

api::RobotSetup kuka() {
  api::RobotSetupRequest req;
  req.robot = "kuka-kr120-r2500-pro";
  return api::loadRobotSetup(req);
}

TEST(ApiCommands, DeflectAtAPoseEqualsTheCliJson) {
  const api::RobotSetup s = kuka();
  api::DeflectRequest req;
  req.joints = degrees(0, -60, 100, 0, 50, 0);
  req.wrench = nc::Wrench{Vec3(0, 0, 800), Vec3::Zero()};
  const api::DeflectResult r = api::deflectAt(s, req);
  ASSERT_TRUE(r.deflection.converged);

  const auto cli = test::runRoprec(
      "deflect --robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\" --wrench \"0 0 800 0 0 "
      "0\"");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const json j = json::parse(cli.out);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(j["deviation"]["translation_um"][static_cast<size_t>(i)].get<double>(),
                r.deflection.dp[i] * 1e6, 1e-3);
    EXPECT_NEAR(j["deviation"]["rotation_urad"][static_cast<size_t>(i)].get<double>(),
                r.deflection.drot[i] * 1e6, 1e-3);
  }
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(j["torques_Nm"][static_cast<size_t>(i)].get<double>(), r.deflection.tau[i], 1e-3);
  }
  EXPECT_EQ(j["loads"]["force_N"][2].get<double>(), 800.0);
  // the JSON the API builds is the CLI's, except for the label the CLI gives its --wrench
  json api_json = json::parse(api::deflectJson(s, r).dump());
  EXPECT_EQ(api_json["loads"]["wrench_source"].get<std::string>(),
            "given wrench (base frame, on the TCP)");
  api_json["loads"]["wrench_source"] = j["loads"]["wrench_source"];
  EXPECT_EQ(api_json, j);
}

TEST(ApiCommands, DeflectRefusesJointsOutsideTheLimitsAndABareUrdf) {
  const api::RobotSetup s = kuka();
  api::DeflectRequest req;
  req.joints = degrees(0, -170, 100, 0, 50, 0);
  try {
    api::deflectAt(s, req);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("joints outside the joint limits: joint_a2"), std::string::npos)
        << e.message();
  }
  api::RobotSetupRequest bare;
  bare.robot = test::sourceDir() + "/robots/kuka-kr120-r2500-pro/kr120r2500pro.urdf";
  const api::RobotSetup u = api::loadRobotSetup(bare);
  req.joints = degrees(0, -60, 100, 0, 50, 0);
  EXPECT_THROW(api::deflectAt(u, req), InputError);
}

TEST(ApiCommands, RobotSetupErrorsAndStiffnessOverride) {
  EXPECT_THROW(api::loadRobotSetup({}), UsageError);
  api::RobotSetup s = kuka();
  EXPECT_THROW(api::overrideStiffness(s, (nc::Vec6() << 1, 1, 0, 1, 1, 1).finished()), InputError);
  api::overrideStiffness(s, nc::Vec6::Constant(2e6), "k", "test");
  EXPECT_EQ(s.robot.card.joints[3].stiffness, 2e6);
  EXPECT_EQ(s.robot.card.joints[3].source, "test");
  // a cell gives the tool
  api::RobotSetupRequest req;
  req.cell = sample("cells/housing-kr120.xml");
  const api::RobotSetup c = api::loadRobotSetup(req);
  ASSERT_TRUE(c.cell.has_value());
  EXPECT_GT(c.tool.mass, 0.0);
  EXPECT_EQ(api::limitViolations(c.robot.chain, degrees(0, -60, 100, 0, 50, 0)).size(), 0u);
  EXPECT_EQ(api::limitViolations(c.robot.chain, degrees(0, -170, 100, 0, 50, 0)).size(), 1u);
}

TEST(ApiCommands, FkAndIkEqualTheCli) {
  api::RobotSetupRequest req;
  req.cell = sample("cells/housing-kr120.xml");
  const api::RobotSetup s = api::loadRobotSetup(req);
  const nc::Vec6 q = degrees(10, -80, 100, 20, 40, -30);
  const api::FkResult fk = api::forwardKinematicsAt(s, q);
  const auto cli =
      test::runRoprec("fk --cell '" + *req.cell + "' --joints \"10 -80 100 20 40 -30\"");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_EQ(api::fkJson(s, fk).dump(), cli.out);

  // IK of that TCP gives back the joints among its solutions
  api::IkRequest ik;
  ik.target = fk.T_tcp;
  const api::IkAnswer a = api::inverseKinematicsFor(s, ik);
  EXPECT_TRUE(a.unreachable.empty());
  double best = 1e9;
  for (int k = 0; k < a.result->count; ++k)
    best = std::min(best, (a.result->solutions[static_cast<size_t>(k)].q - q).norm());
  EXPECT_LT(best, 1e-9);

  api::IkRequest far;
  far.target = Pose::Identity();
  far.target.translation() = Vec3(8.0, 0, 0);
  const api::IkAnswer none = api::inverseKinematicsFor(kuka(), far);
  EXPECT_EQ(none.usable, 0);
  EXPECT_FALSE(none.unreachable.empty());
  EXPECT_EQ(json::parse(api::ikJson(kuka(), none).dump())["unreachable"].get<std::string>(),
            none.unreachable);
}

TEST(ApiCommands, SimulateAHoleOfAHoleList) {
  api::RobotSetupRequest req;
  req.cell = sample("cells/alu-drilling-6061.xml");
  const api::RobotSetup s = api::loadRobotSetup(req);
  const std::string holes = test::sourceDir() + "/tests/data/programs/holes.csv";
  const api::HoleJoints at = api::holeJoints(s, holes, "H2");
  EXPECT_NE(at.source.find("hole list row"), std::string::npos);
  EXPECT_THROW(api::holeJoints(s, holes, "NOPE"), InputError);

  api::SimulateOptions opt;
  opt.duration = 0.05;
  const api::SimulationResult r = api::simulateAt(s, at, opt);
  ASSERT_TRUE(r.transient.ok) << r.transient.message;
  const std::string dir = test::tempDir("api_simulate");
  const auto cli =
      test::runRoprec("simulate --cell '" + *req.cell + "' --hole H2 '" + holes +
                      "' --duration 0.05 -o '" + dir + "/h.csv' --summary '" + dir + "/h.json'");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_EQ(api::transientHistoryCsv(r.transient), test::readFile(dir + "/h.csv"));
  EXPECT_EQ(api::simulationSummaryJson(s, at, r).dump(), test::readFile(dir + "/h.json"));

  // a hole out of reach is a per-hole failure, not bad input
  test::writeFile(dir + "/far.csv",
                  "id,x,y,z,i,j,k,diameter,depth,tolerance\nFAR,9000,0,0,0,0,-1,6.0,12,0.2\n");
  EXPECT_THROW(api::holeJoints(s, dir + "/far.csv", "FAR"), api::HoleUnreachable);
}

TEST(ApiCommands, ForcesEqualTheCli) {
  api::ForcesRequest req;
  req.cell = sample("cells/alu-drilling-6061.xml");
  req.calibrate = api::DrillingMeasurement{1466, 4.04};
  req.calibrated_cell = true;
  const api::ForcesResult r = api::processForces(req);
  EXPECT_TRUE(r.converged);
  const std::string dir = test::tempDir("api_forces");
  const auto cli =
      test::runRoprec("forces --cell '" + req.cell + "' --calibrate 'Fa_N=1466 M_Nm=4.04' --o '" +
                      dir + "/cal.xml' --csv '" + dir + "/d.csv'");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const api::ForcesOutput o = api::forcesOutput(r);
  EXPECT_EQ(o.json.dump() + "\n", cli.out);
  EXPECT_EQ(o.curve_csv, test::readFile(dir + "/d.csv"));
  EXPECT_EQ(r.calibrated_cell, test::readFile(dir + "/cal.xml"));

  api::ForcesRequest mill;
  mill.cell = sample("cells/alu-milling-7075.xml");
  mill.calibrate = api::DrillingMeasurement{3, 4};
  EXPECT_THROW(api::processForces(mill), InputError);  // calibration needs a drilling process
  mill.calibrate.reset();
  mill.calibrated_cell = true;
  EXPECT_THROW(api::processForces(mill), UsageError);  // a calibrated cell needs a calibration
}

TEST(ApiCommands, InspectConvertAndRobotsEqualTheCli) {
  const std::string src = test::sourceDir() + "/tests/data/programs/kss_drill.src";
  const std::string holes = test::sourceDir() + "/tests/data/programs/holes.csv";
  api::InspectRequest ins;
  ins.program = src;
  ins.hole_list = holes;
  const auto cli = test::runRoprec("inspect '" + src + "' --holes '" + holes + "' --all");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_EQ(api::inspectJson(api::inspectProgram(ins)).dump() + "\n", cli.out);

  const std::string dir = test::tempDir("api_convert");
  api::ConvertRequest conv;
  conv.program = src;
  conv.output = dir + "/copy.src";
  const api::ConvertResult c = api::convertProgramFile(conv);
  EXPECT_TRUE(c.skipped.empty());
  EXPECT_EQ(test::readFile(dir + "/copy.src"), test::readFile(src));

  EXPECT_EQ(api::groupNotes(
                {"p1: no config", "p2: no config", "p3: no config", "p4: no config", "tool: mass"}),
            (std::vector<std::string>{"no config (4 items: p1, p2, p3, ...)", "tool: mass"}));

  const api::RobotList robots = api::robotList(api::bundledRobotCards());
  EXPECT_EQ(robots.summary, test::runRoprec("robots").out);
  EXPECT_EQ(robots.text, test::runRoprec("robots --all").out);
  EXPECT_EQ(robots.json.dump(), test::runRoprec("robots --json").out);
}

// ---- a calibrated card: the real robot is the URDF `card export-urdf` writes (KDL)

api::RobotSetup calibratedKuka() {
  api::RobotSetupRequest req;
  req.robot = sample("verification/kr120-calibrated.xml");
  return api::loadRobotSetup(req);
}

// ik answers for the real robot: every usable solution puts KDL's flange of the exported URDF on
// the target to 1e-9 m (and the nominal URDF's flange off it by the calibration).
TEST(ApiCommands, IkOfACalibratedCardReachesTheTargetWithTheExportedUrdf) {
  const api::RobotSetup s = calibratedKuka();
  ASSERT_TRUE(s.robot.card.calibration.has_value());
  const KDL::Chain real = test::kdlExportedChain(s.robot.card.file, test::tempDir("ikcal"));
  const KDL::Chain nominal =
      test::kdlChain(s.robot.card.urdf_path, s.robot.chain.base_link, s.robot.chain.tip_link);
  api::IkRequest req;
  req.target = test::kdlPose(nominal, degrees(15, -70, 100, 25, 45, -35));
  const api::IkAnswer a = api::inverseKinematicsFor(s, req);
  ASSERT_GT(a.usable, 0) << a.unreachable;
  for (int k = 0; k < a.result->count; ++k) {
    const IkSolution& sol = a.result->solutions[static_cast<size_t>(k)];
    if (!sol.converged || !sol.within_limits) continue;
    const Pose T = test::kdlPose(real, sol.q);
    EXPECT_LT((T.translation() - req.target.translation()).norm(), 1e-9) << k;
    EXPECT_LT(Eigen::AngleAxisd(T.linear().transpose() * req.target.linear()).angle(), 1e-9) << k;
    EXPECT_GT((test::kdlPose(nominal, sol.q).translation() - req.target.translation()).norm(),
              0.1e-3)
        << k;
  }
}

// deflect at commanded joints: the real TCP is KDL's on the exported URDF at the equilibrium
// joints, and the deviation is taken from the pose the controller means (KDL on the nominal
// URDF at the command), both to 1e-9 m.
TEST(ApiCommands, DeflectOfACalibratedCardIsTheExportedUrdfsTcp) {
  api::RobotSetupRequest sr;
  sr.cell = sample("verification/housing-kr120-calibrated.xml");
  const api::RobotSetup s = api::loadRobotSetup(sr);
  ASSERT_TRUE(s.robot.card.calibration.has_value());
  const Pose tool = s.tool.T_flange_tcp;
  const KDL::Chain real = test::kdlExportedChain(s.robot.card.file, test::tempDir("deflcal"), tool);
  const KDL::Chain nominal =
      test::kdlChain(s.robot.card.urdf_path, s.robot.chain.base_link, s.robot.chain.tip_link, tool);
  api::DeflectRequest req;
  req.joints = degrees(5, -60, 100, 10, 50, -20);
  req.wrench = nc::Wrench{Vec3(0, 0, 800), Vec3::Zero()};
  const api::DeflectResult r = api::deflectAt(s, req);
  ASSERT_TRUE(r.deflection.converged);
  const Vec3 real_tcp = test::kdlPose(real, r.deflection.theta).translation();
  EXPECT_LT((real_tcp - r.deflection.T_real.translation()).norm(), 1e-9);
  const Vec3 commanded = test::kdlPose(nominal, req.joints).translation();
  EXPECT_LT((r.deflection.dp - (real_tcp - commanded)).norm(), 1e-9);
  EXPECT_GT((real_tcp - test::kdlPose(nominal, r.deflection.theta).translation()).norm(), 0.1e-3);
}

// simulate on a calibrated cell: the hole's joints are the controller's command (KDL on the
// nominal URDF puts the TCP on the hole's axis) and the static gravity deviation is the exported
// URDF's TCP at deflect's equilibrium joints less the nominal URDF's TCP at the command (the pose
// the controller means, as deflect), both to 1e-9 m.
TEST(ApiCommands, SimulateOfACalibratedCellUsesTheExportedUrdfsKinematics) {
  api::RobotSetupRequest sr;
  sr.cell = sample("verification/housing-kr120-calibrated.xml");
  const api::RobotSetup s = api::loadRobotSetup(sr);
  ASSERT_TRUE(s.robot.card.calibration.has_value());
  const std::string dir = test::tempDir("simcal");
  test::writeFile(dir + "/holes.csv",
                  "id,x,y,z,i,j,k,diameter,depth,tolerance\nH1,40,-30,150,0,0,-1,8.5,20,0.2\n");
  const api::HoleJoints at = api::holeJoints(s, dir + "/holes.csv", "H1");
  const Pose tool = s.tool.T_flange_tcp;
  const KDL::Chain real = test::kdlExportedChain(s.robot.card.file, dir, tool);
  const KDL::Chain nominal =
      test::kdlChain(s.robot.card.urdf_path, s.robot.chain.base_link, s.robot.chain.tip_link, tool);
  const Pose T_W_wobj = s.cell->T_base_wobj;
  const Vec3 hole = T_W_wobj * Vec3(0.040, -0.030, 0.150);
  const Vec3 axis = -T_W_wobj.linear().col(2);
  const Pose commanded = test::kdlPose(nominal, at.joints);
  const Vec3 off = commanded.translation() - hole;
  EXPECT_LT((off - off.dot(axis) * axis).norm(), 1e-9);
  EXPECT_LT((commanded.linear().col(2) - axis).norm(), 1e-9);

  api::SimulateOptions opt;
  opt.duration = 0.02;
  const api::SimulationResult r = api::simulateAt(s, at, opt);
  ASSERT_TRUE(r.transient.ok) << r.transient.message;
  api::DeflectRequest dq;
  dq.joints = at.joints;
  dq.process = false;
  const api::DeflectResult d = api::deflectAt(s, dq);
  const Vec3 expected = test::kdlPose(real, d.deflection.theta).translation() -
                        test::kdlPose(nominal, at.joints).translation();
  const json sj = json::parse(api::simulationSummaryJson(s, at, r).dump());
  const auto& g = sj.at("static").at("gravity_only_um");
  const Vec3 got(g[0].get<double>(), g[1].get<double>(), g[2].get<double>());
  EXPECT_LT((got * 1e-6 - expected).norm(), 1e-9) << got.transpose();
}

// plan-test on a calibrated cell plans with the calibrated robot: each chosen hole's command is
// the controller's (KDL on the nominal URDF reaches the hole) and its predicted real TCP is KDL on
// the exported URDF at the equilibrium joints, both to 1e-9 m.
TEST(ApiCommands, PlanTestOfACalibratedCellPlansWithTheExportedUrdfsKinematics) {
  const std::string cell = sample("verification/housing-kr120-calibrated.xml");
  api::PlanTestOptions o;
  o.per_axis = 3;
  const api::PlanTestResult r =
      api::planTestJob(cell, Vec3(-150, -150, 100), Vec3(150, 150, 200), 6, o);
  const PredictionModel& m = r.context.model;
  ASSERT_TRUE(r.context.robot.card.calibration.has_value());
  const Pose tool = r.context.tool.T_flange_tcp;
  const ChainDescription& ch = r.context.robot.chain;
  const KDL::Chain real =
      test::kdlExportedChain(r.context.robot.card.file, test::tempDir("plancal"), tool);
  const KDL::Chain nominal =
      test::kdlChain(r.context.robot.card.urdf_path, ch.base_link, ch.tip_link, tool);
  ASSERT_EQ(r.plan.chosen.size(), 6u);
  PredictionData d(m);
  for (const int k : r.plan.chosen) {
    const HoleRequest& c = r.candidates[static_cast<size_t>(k)];
    const HolePrediction h = predictHole(m, d, c, nullptr);
    ASSERT_EQ(h.status, HoleStatus::kOk) << h.reason;
    EXPECT_LT((test::kdlPose(nominal, h.joints).translation() - c.T_W_tcp.translation()).norm(),
              1e-9)
        << c.id;
    const Vec3 tcp = test::kdlPose(real, h.deflection.theta).translation();
    EXPECT_LT((tcp - h.deflection.T_real.translation()).norm(), 1e-9) << c.id;
    EXPECT_GT((tcp - test::kdlPose(nominal, h.deflection.theta).translation()).norm(), 0.1e-3);
  }
}

}  // namespace
}  // namespace roprec
