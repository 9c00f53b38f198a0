// simulate (plugin/api/simulate.hpp): its static deviations are deflect's, measured from the same
// reference, so the summary's "as deflect" holds for a calibrated card too.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "plugin/api/deflect.hpp"
#include "plugin/api/simulate.hpp"
#include "plugin/report/simulate_output.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nlohmann::json;

Vec3 vec3(const json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

// A calibrated card: deflect measures the deviation from the pose the controller means by the
// command, FK_nom(θ_cmd) (docs/model.md §6.8); simulate's static deviations under gravity alone
// and under the cell's drilling load at full engagement equal deflect's at the same joints and
// load to 1e-9 m (and 1e-9 rad), and both hold the geometric error (they differ from the
// deviation taken from the calibrated FK by more than 0.1 mm).
TEST(Simulate, StaticDeviationOfACalibratedCardIsDeflects) {
  api::RobotSetupRequest sr;
  sr.cell = test::sourceDir() + "/samples/verification/housing-kr120-calibrated.xml";
  const api::RobotSetup s = api::loadRobotSetup(sr);
  ASSERT_TRUE(s.robot.card.calibration.has_value());
  api::HoleJoints at;  // the cell's own drill and cut, as `simulate --joints`
  at.joints = (nc::Vec6() << 5, -80, 95, 10, 40, -20).finished() * kDeg;
  at.source = "--joints";

  api::SimulateOptions opt;
  opt.duration = 0.02;
  const api::SimulationResult r = api::simulateAt(s, at, opt);
  ASSERT_TRUE(r.transient.ok) << r.transient.message;
  const json st = json::parse(api::simulationSummaryJson(s, at, r).dump()).at("static");

  api::DeflectRequest gravity_only;
  gravity_only.joints = at.joints;
  gravity_only.process = false;
  const nc::Deflection g = api::deflectAt(s, gravity_only).deflection;
  api::DeflectRequest loaded;
  loaded.joints = at.joints;
  const nc::Deflection f = api::deflectAt(s, loaded).deflection;

  EXPECT_LT((vec3(st.at("gravity_only_um")) * 1e-6 - g.dp).norm(), 1e-9) << g.dp.transpose();
  EXPECT_LT((vec3(st.at("full_engagement_um")) * 1e-6 - f.dp).norm(), 1e-9) << f.dp.transpose();
  EXPECT_LT((vec3(st.at("full_engagement_rotation_urad")) * 1e-6 - f.drot).norm(), 1e-9);
  const Vec3 from_calibrated_fk =
      f.T_real.translation() -
      chainForwardKinematics(s.robot.real_chain, at.joints) * s.tool.T_flange_tcp.translation();
  EXPECT_GT((f.dp - from_calibrated_fk).norm(), 0.1e-3);
}

}  // namespace
}  // namespace roprec
