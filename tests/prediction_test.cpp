// Per-hole prediction: the robot-process precision study's qualitative findings on a
// paper-like cell, Monte Carlo vs linearised U_robdef, the budget recomputed by hand, and
// byte-identical JSON/HTML through the CLI.
#include "compensator/precision/prediction.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>

#include "compensator/precision/uncertainty.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

std::string paper(const std::string& f) { return test::sourceDir() + "/tests/data/paper/" + f; }

/// The paper cell with the feed (mm/rev) replaced, written to a temp dir.
std::string cellWithFeed(double feed) {
  std::string xml = test::readFile(paper("cell.xml"));
  xml = std::regex_replace(xml, std::regex("feed_mm_per_rev=\"0.2\""),
                           "feed_mm_per_rev=\"" + std::to_string(feed) + "\"");
  const std::string dir = test::tempDir("feed");
  test::writeFile(dir + "/cell.xml", xml);
  return dir + "/cell.xml";
}

const HolePrediction& byId(const std::vector<HolePrediction>& p, const std::string& id) {
  for (const auto& h : p) {
    if (h.id == id) return h;
  }
  throw std::runtime_error("no hole " + id);
}

TEST(Prediction, DeviationGrowsWithFeedAndWithArmExtension) {
  // The process-induced deviation (gravity off: drilling downward, the thrust also lifts the
  // gravity sag, so the total can fall while the process part grows).
  double prev = 0;
  for (const double f : {0.1, 0.2, 0.3}) {
    api::PredictionContext c =
        api::loadPredictionContext(cellWithFeed(f), paper("holes.csv"), std::nullopt, "");
    c.model.gravity = false;
    const auto p = predictHoles(c.model, c.job.requests);
    const double e = byId(p, "X2").d_robot.norm();
    EXPECT_GT(e, prev) << "feed " << f;
    prev = e;
  }
  api::PredictionContext c =
      api::loadPredictionContext(paper("cell.xml"), paper("holes.csv"), std::nullopt, "");
  c.model.gravity = false;
  const auto p = predictHoles(c.model, c.job.requests);
  EXPECT_LT(byId(p, "X1").d_robot.norm(), byId(p, "X2").d_robot.norm());
  EXPECT_LT(byId(p, "X2").d_robot.norm(), byId(p, "X3").d_robot.norm());
  EXPECT_LT(byId(p, "X3").d_robot.norm(), byId(p, "X4").d_robot.norm());
}

TEST(Prediction, DeviationAtTheChosenJointsIsThePredictedDeviationWithoutIk) {
  // the calibrated robot too: δrobot is referred to the controller's pose there
  for (const auto& [cell, holes] :
       {std::pair<std::string, std::string>{paper("cell.xml"), paper("holes.csv")},
        {test::sourceDir() + "/samples/verification/housing-kr120-calibrated.xml",
         test::sourceDir() + "/samples/verification/geometry_kr120_holes.csv"}}) {
    const api::PredictionContext c = api::loadPredictionContext(cell, holes, std::nullopt, "");
    const auto p = predictHoles(c.model, c.job.requests);
    PredictionData d(c.model);
    size_t ok = 0;
    for (size_t i = 0; i < p.size(); ++i) {
      if (p[i].status != HoleStatus::kOk) continue;
      ++ok;
      // a scratch used before for another hole: no state carried from hole to hole
      const std::optional<Vec3> at = robotDeviationAt(c.model, d, c.job.requests[i], p[i].joints);
      ASSERT_TRUE(at.has_value()) << p[i].id;
      EXPECT_EQ(*at, p[i].d_robot) << p[i].id;  // the same equilibrium: the same bits
    }
    EXPECT_GT(ok, 3u) << cell;
  }
}

TEST(Prediction, WristConfigurationChangeIsAJumpOfTensOfMicrometres) {
  // Neighbouring holes (1 mm apart) drilled with the wrist reconfigured: the OLP turned the
  // spindle 90° about the drill axis, so the wrist axes take other angles and, with the spindle
  // mass off the drill axis (paper cell), other loads. A pure flip
  // (θ4 ± 180°, −θ5, θ6 ± 180°) moves nothing in a joint-compliance model (τ5 and φ5 both change
  // sign), which this test checks too.
  const api::PredictionContext c =
      api::loadPredictionContext(paper("cell.xml"), paper("holes.csv"), std::nullopt, "");
  PredictionData d(c.model);
  HoleRequest a = c.job.requests[1];
  HoleRequest b = a;
  b.T_W_tcp.translation().x() += 1e-3;
  b.T_W_tcp.rotate(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ()));
  const HolePrediction pa = predictHole(c.model, d, a, nullptr);
  const HolePrediction pb = predictHole(c.model, d, b, &pa.joints);
  ASSERT_EQ(pa.status, HoleStatus::kOk) << pa.reason;
  ASSERT_EQ(pb.status, HoleStatus::kOk) << pb.reason;
  EXPECT_GT(std::abs(pb.joints[3] - pa.joints[3]) + std::abs(pb.joints[5] - pa.joints[5]),
            45 * kDeg);
  const double jump = (pa.d_work - pb.d_work).norm();
  EXPECT_GT(jump, 10e-6) << "jump " << jump * 1e6 << " µm";
  EXPECT_LT(jump, 1000e-6);
  // The flip invariance is a property of the loads (gravity, tool, process) only: without the
  // controller's constant mastering offset the flipped wrist lands where the other does. With
  // it, the offset Δθ_c (constant in joint space) does not change sign with the flip, so the
  // jump is J(θ_flip) Δθ_c − J(θ) Δθ_c — checked against that linear estimate.
  PredictionModel m_loads = c.model;
  m_loads.controller = nc::ControllerReference{};
  PredictionData dl(m_loads);
  HoleRequest f = a;
  f.config = parseConfig(Vendor::kKuka, "S 6");  // θ5 < 0: the flipped wrist
  const HolePrediction pal = predictHole(m_loads, dl, a, nullptr);
  const HolePrediction pfl = predictHole(m_loads, dl, f, nullptr);
  ASSERT_EQ(pfl.status, HoleStatus::kOk) << pfl.reason;
  EXPECT_NE(pfl.branch, pal.branch);
  EXPECT_LT((pfl.d_work - pal.d_work).norm(), 5e-6);
  ASSERT_EQ(c.model.controller.kind, nc::ControllerReference::Kind::kMastering);
  const HolePrediction pf = predictHole(c.model, d, f, nullptr);
  ASSERT_EQ(pf.status, HoleStatus::kOk) << pf.reason;
  const Vec6 off = controllerOffset(c.model, d.nc, pa.joints);
  nc::Data s(c.model.model);
  auto tcpAt = [&](const Vec6& q) {
    nc::forwardKinematics(c.model.model, s, q);
    return Vec3(s.T_W_tcp.translation());
  };
  auto tcpShift = [&](const Vec6& q) { return Vec3(tcpAt(q + off) - tcpAt(q)); };
  const Vec3 expected = tcpShift(pf.joints) - tcpShift(pa.joints);
  const Vec3 jump_off = (pf.d_work - pa.d_work) - (pfl.d_work - pal.d_work);
  EXPECT_LT((jump_off - expected).norm(), 0.05 * expected.norm() + 1e-6)
      << "jump " << jump_off.transpose() * 1e6 << " µm, offset estimate "
      << expected.transpose() * 1e6 << " µm";
}

TEST(Prediction, MachiningUncertaintyRisesFrom30To60MicrometresWithDiameter) {
  const api::PredictionContext c =
      api::loadPredictionContext(paper("cell.xml"), paper("holes.csv"), std::nullopt, "");
  const auto p = predictHoles(c.model, c.job.requests);
  // the study's ± band is per axis with k = 2 (U = 2 u); the report's U_mach is the 2-D radius
  const double u8 = 2.0 * byId(p, "D8").u_mach;
  const double u12 = 2.0 * byId(p, "D12").u_mach;
  EXPECT_NEAR(u8, 30e-6, 0.15 * 30e-6);
  EXPECT_NEAR(u12, 60e-6, 0.15 * 60e-6);
  EXPECT_NEAR(byId(p, "D8").U_mach, rayleighCoverageFactor(0.95) * byId(p, "D8").u_mach, 1e-15);
}

TEST(Prediction, ProcessShareIsReportedAndAtMostFortyPercentInThePaperLikeCell) {
  const api::PredictionContext c =
      api::loadPredictionContext(paper("cell.xml"), paper("holes.csv"), std::nullopt, "");
  const auto p = predictHoles(c.model, c.job.requests);
  for (const auto& h : p) {
    ASSERT_EQ(h.status, HoleStatus::kOk) << h.id;
    EXPECT_GT(h.process_share, 0.0) << h.id;
    EXPECT_LE(h.process_share, 0.40) << h.id;
  }
}

TEST(Prediction, BudgetRecomputedByHand) {
  const api::PredictionContext c =
      api::loadPredictionContext(paper("cell.xml"), paper("holes.csv"), std::nullopt, "");
  const auto p = predictHoles(c.model, c.job.requests);
  const HolePrediction& h = byId(p, "X2");
  double u2_robot = 0;
  double u2_mach = 0;
  for (const BudgetTerm& t : h.budget)
    (std::string(t.name).rfind("mach", 0) == 0 ? u2_mach : u2_robot) += t.u * t.u;
  EXPECT_NEAR(h.u_robot, std::sqrt(u2_robot), 1e-15);
  EXPECT_NEAR(h.u_mach, std::sqrt(u2_mach), 1e-15);
  EXPECT_NEAR(h.U_work, std::sqrt(h.U_robot * h.U_robot + h.U_mach * h.U_mach), 1e-15);
  EXPECT_NEAR(h.budget[0].u, 0.06e-3 / 3.6161, 1e-8);  // KR 120 RP 0.06 mm
  EXPECT_NEAR(h.k, 2.4477, 1e-4);
  // the verdict uses the anisotropic 95 % radius of Σ_def + (u_robpos² + u_acc² + u_mach²) I
  // (the card's uncalibrated absolute accuracy is isotropic), ≥ U_work
  const BudgetTerm* acc = nullptr;
  for (const BudgetTerm& t : h.budget)
    if (std::string(t.name) == "robot_absolute_accuracy") acc = &t;
  ASSERT_NE(acc, nullptr);
  EXPECT_NEAR(acc->u, 1.0e-3 / 2.7955, 1e-15);  // KR 120 card: AP 1.0 mm (estimate)
  const double iso2 = h.budget[0].u * h.budget[0].u + acc->u * acc->u + u2_mach;
  const Eigen::Matrix2d S = h.robdef_cov + iso2 * Eigen::Matrix2d::Identity();
  EXPECT_NEAR(h.U_work_exact, radialCoverage(S), 1e-12);
  EXPECT_GE(h.U_work_exact, h.U_work * (1 - 1e-12));
  EXPECT_EQ(h.verdict, verdictFor(h.position_error, h.U_work_exact, 0.2e-3));
}

TEST(Prediction, MonteCarloAgreesWithLinearisationAtSmallInputUncertainty) {
  std::string xml = test::readFile(paper("cell.xml"));
  xml = std::regex_replace(
      xml, std::regex("<tolerance"),
      "<uncertainty method=\"montecarlo\" stiffness_rel=\"0.02\" process_halfwidth=\"0.03\" "
      "samples=\"4000\" seed=\"7\"/>\n  <tolerance");
  const std::string dir = test::tempDir("mc");
  test::writeFile(dir + "/cell.xml", xml);
  const api::PredictionContext mc =
      api::loadPredictionContext(dir + "/cell.xml", paper("holes.csv"), std::nullopt, "");
  const api::PredictionContext lin =
      api::loadPredictionContext(dir + "/cell.xml", paper("holes.csv"), std::nullopt, "linear");
  const auto pm = predictHoles(mc.model, mc.job.requests);
  const auto pl = predictHoles(lin.model, lin.job.requests);
  for (size_t i = 0; i < pm.size(); ++i) {
    const double um = std::sqrt(0.5 * pm[i].robdef_cov.trace());
    const double ul = std::sqrt(0.5 * pl[i].robdef_cov.trace());
    EXPECT_NEAR(um, ul, 0.10 * ul) << pm[i].id;
  }
}

/// The paper cell with its robot replaced by a copy of the KR 120 card holding `card_extra` (before
/// </robot>) and `cell_extra` before <tolerance>.
std::string paperCellWith(const std::string& card_extra, const std::string& cell_extra,
                          const std::string& tag) {
  const std::string dir = test::tempDir(tag);
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  const std::string card = test::cardWithCalibration(robot, card_extra, dir);
  std::string xml = test::readFile(paper("cell.xml"));
  xml = std::regex_replace(xml, std::regex("<robot ref=\"kuka-kr120-r2500-pro\"/>"),
                           "<robot file=\"" + card + "\"/>");
  xml = std::regex_replace(xml, std::regex("<tolerance"), cell_extra + "\n  <tolerance");
  test::writeFile(dir + "/cell.xml", xml);
  return dir + "/cell.xml";
}

const BudgetTerm* termNamed(const HolePrediction& h, const std::string& name) {
  for (const BudgetTerm& t : h.budget)
    if (name == t.name) return &t;
  return nullptr;
}

/// The card of a paperCellWith cell with its <accuracy> element replaced by `accuracy`.
void replaceCardAccuracy(const std::string& cell, const std::string& accuracy) {
  const std::string card = std::filesystem::path(cell).parent_path().string() + "/robot.xml";
  test::writeFile(card, std::regex_replace(test::readFile(card),
                                           std::regex("  <accuracy [^>]*/>\n"), accuracy));
}

TEST(Prediction, AbsoluteAccuracyTermFromTheCardTheOptionAndTheRegistration) {
  const std::string none = paperCellWith("", "", "acc-none");
  replaceCardAccuracy(none, "");
  const api::PredictionContext plain =
      api::loadPredictionContext(none, paper("holes.csv"), std::nullopt, "");
  const HolePrediction h0 = byId(predictHoles(plain.model, plain.job.requests), "X2");
  EXPECT_EQ(termNamed(h0, "robot_absolute_accuracy"), nullptr);  // nothing stated: no term
  // the card's AP (uncalibrated): AP / 2.7955 per axis, in u_robot, with its source
  const std::string with_ap = paperCellWith("", "", "acc-card");
  replaceCardAccuracy(with_ap, "  <accuracy ap_mm=\"0.8\" source=\"test: AP\"/>\n");
  api::PredictionContext c =
      api::loadPredictionContext(with_ap, paper("holes.csv"), std::nullopt, "");
  HolePrediction h = byId(predictHoles(c.model, c.job.requests), "X2");
  const BudgetTerm* t = termNamed(h, "robot_absolute_accuracy");
  ASSERT_NE(t, nullptr);
  EXPECT_NEAR(t->u, 0.8e-3 / 2.7955, 1e-15);
  ASSERT_NE(t->source, nullptr);
  EXPECT_NE(std::string(t->source).find("test: AP"), std::string::npos) << t->source;
  EXPECT_NEAR(h.u_robot, std::sqrt(h0.u_robot * h0.u_robot + t->u * t->u), 1e-12);
  EXPECT_GT(h.U_work_exact, h0.U_work_exact);
  // the controller's option replaces it; the registration σ adds in quadrature
  const std::string option =
      paperCellWith("", "<absolute_accuracy ap_mm=\"0.2\" source=\"test: option\"/>", "acc-option");
  test::writeFile(option, std::regex_replace(test::readFile(option), std::regex("rpy=\"0 0 0\"/>"),
                                             "rpy=\"0 0 0\" sigma_mm=\"0.01\"/>"));
  c = api::loadPredictionContext(option, paper("holes.csv"), std::nullopt, "");
  h = byId(predictHoles(c.model, c.job.requests), "X2");
  t = termNamed(h, "robot_absolute_accuracy");
  ASSERT_NE(t, nullptr);
  EXPECT_NEAR(t->u, std::hypot(0.2e-3 / 2.7955, 0.01e-3), 1e-15);
  EXPECT_NE(std::string(t->source).find("test: option"), std::string::npos) << t->source;
}

TEST(Prediction, CalibratedAccuracyTermMatchesAMonteCarloOfTheCalibration) {
  // σ per component, propagated by the FK Jacobian, against sampled calibrations pushed through
  // the calibrated chain's FK (no Jacobian): in-plane standard deviation within 5 % (4000 samples:
  // sampling error ~2 %)
  GeometryCalibration cal = test::seededGeometryErrors(3, 0.3, 0.4);
  const auto setSigma = [](FrameError& e) {
    e.sigma_xyz = Vec3(0.02e-3, 0.03e-3, 0.01e-3);
    e.sigma_rpy = Vec3(0.02e-3, 0.01e-3, 0.03e-3);
  };
  for (FrameError& j : cal.joints) setSigma(j);
  setSigma(cal.base);
  setSigma(cal.tool);
  std::array<std::string, 6> names;
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  for (size_t i = 0; i < 6; ++i) names[i] = robot.card.joints[i].name;
  const api::PredictionContext c =
      api::loadPredictionContext(paperCellWith(calibrationXml(cal, names), "", "acc-cal"),
                                 paper("holes.csv"), std::nullopt, "");
  const HolePrediction h = byId(predictHoles(c.model, c.job.requests), "X3");
  const BudgetTerm* t = termNamed(h, "robot_absolute_accuracy");
  ASSERT_NE(t, nullptr);
  const Pose tool = c.tool.T_flange_tcp;
  const Vec3 e1 = c.job.requests[2].T_W_tcp.linear().col(0);
  const Vec3 e2 = c.job.requests[2].T_W_tcp.linear().col(1);
  std::mt19937 rng(17);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto draw = [&](const FrameError& e) {
    FrameError d = e;
    for (int k = 0; k < 3; ++k) {
      d.dxyz[k] += e.sigma_xyz[k] * n(rng);
      d.drpy[k] += e.sigma_rpy[k] * n(rng);
    }
    return d;
  };
  const Vec3 p0 =
      (chainForwardKinematics(calibratedChain(robot.chain, cal), h.deflection.theta) * tool)
          .translation();
  double s2 = 0;
  const int N = 4000;
  for (int s = 0; s < N; ++s) {
    GeometryCalibration d = cal;
    for (FrameError& j : d.joints) j = draw(j);
    d.base = draw(cal.base);
    d.tool = draw(cal.tool);
    const Vec3 dp =
        (chainForwardKinematics(calibratedChain(robot.chain, d), h.deflection.theta) * tool)
            .translation() -
        p0;
    s2 += 0.5 * (std::pow(dp.dot(e1), 2) + std::pow(dp.dot(e2), 2));
  }
  EXPECT_NEAR(t->u, std::sqrt(s2 / N), 0.05 * t->u);
  EXPECT_GT(t->u, 1e-5);
}

TEST(Prediction, CalibratedAccuracyTermCoversTruthRobotsDrawnFromTheCalibration) {
  // truth robots: the calibration's values plus seeded draws of its stated σ (each component
  // independent, normal), FK by calibratedChain at the predicted equilibrium; the in-plane miss
  // of the predicted real drill point lies inside k·u_acc (k = 2.4477, the 2-D 95 % factor) for
  // 95 ± 3 % of (robot, hole) pairs over the paper cell's holes
  GeometryCalibration cal = test::seededGeometryErrors(5, 0.3, 0.4);
  const auto setSigma = [](FrameError& e) {
    e.sigma_xyz = Vec3(0.015e-3, 0.015e-3, 0.015e-3);
    e.sigma_rpy = Vec3(0.015e-3, 0.015e-3, 0.015e-3);
  };
  for (FrameError& j : cal.joints) setSigma(j);
  setSigma(cal.base);
  setSigma(cal.tool);
  const Robot robot = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  std::array<std::string, 6> names;
  for (size_t i = 0; i < 6; ++i) names[i] = robot.card.joints[i].name;
  const api::PredictionContext c =
      api::loadPredictionContext(paperCellWith(calibrationXml(cal, names), "", "acc-cover"),
                                 paper("holes.csv"), std::nullopt, "");
  const std::vector<HolePrediction> p = predictHoles(c.model, c.job.requests);
  std::mt19937 rng(29);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto draw = [&](const FrameError& e) {
    FrameError d = e;
    for (int k = 0; k < 3; ++k) {
      d.dxyz[k] += e.sigma_xyz[k] * n(rng);
      d.drpy[k] += e.sigma_rpy[k] * n(rng);
    }
    return d;
  };
  const Pose tool = c.tool.T_flange_tcp;
  const ChainDescription real = calibratedChain(robot.chain, cal);
  int inside = 0;
  int total = 0;
  for (int s = 0; s < 500; ++s) {
    GeometryCalibration d = cal;
    for (FrameError& j : d.joints) j = draw(j);
    d.base = draw(cal.base);
    d.tool = draw(cal.tool);
    const ChainDescription truth = calibratedChain(robot.chain, d);
    for (size_t i = 0; i < p.size(); ++i) {
      const BudgetTerm* t = termNamed(p[i], "robot_absolute_accuracy");
      ASSERT_NE(t, nullptr);
      const Vec6& th = p[i].deflection.theta;
      const Vec3 e = (chainForwardKinematics(truth, th) * tool).translation() -
                     (chainForwardKinematics(real, th) * tool).translation();
      const Mat3 R = c.job.requests[i].T_W_tcp.linear();
      const double miss = std::hypot(e.dot(R.col(0)), e.dot(R.col(1)));
      inside += miss <= p[i].k * t->u ? 1 : 0;
      ++total;
    }
  }
  const double coverage = static_cast<double>(inside) / total;
  RecordProperty("coverage", std::to_string(coverage));
  EXPECT_NEAR(coverage, 0.95, 0.03) << inside << " of " << total;
}

TEST(PredictionCli, SameInputGivesByteIdenticalJsonAndHtml) {
  const std::string dir = test::tempDir("pdet");
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const std::string prog = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  for (const char* r : {"a", "b"}) {
    const auto res =
        test::runRoprec("predict --cell '" + cell + "' '" + prog + "' --json '" + dir + "/" + r +
                        ".json' --report '" + dir + "/" + r + ".html' --quiet");
    ASSERT_LE(res.exit_code, 1) << res.err;
  }
  EXPECT_EQ(test::readFile(dir + "/a.json"), test::readFile(dir + "/b.json"));
  EXPECT_EQ(test::readFile(dir + "/a.html"), test::readFile(dir + "/b.html"));
  EXPECT_NE(test::readFile(dir + "/a.json").find("\"verdict\""), std::string::npos);
}

TEST(PredictionCli, BadInputExitsTwoWithFileAndLine) {
  const std::string dir = test::tempDir("pbad");
  test::writeFile(dir + "/holes.csv", "id,x,y,z,i,j,k\nA,1,2,3,0,0,-1\nB,1,2,oops,0,0,-1\n");
  const auto r = test::runRoprec("predict --cell '" + paper("cell.xml") + "' '" + dir +
                                 "/holes.csv' --json '" + dir + "/o.json'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holes.csv:3"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(dir + "/o.json").good());
  test::writeFile(dir + "/cell.xml", "<cell><robot ref=\"no-such-robot\"/></cell>\n");
  const auto r2 = test::runRoprec("predict --cell '" + dir + "/cell.xml' '" + paper("holes.csv") +
                                  "' --json -");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_NE(r2.err.find("cell.xml:1"), std::string::npos) << r2.err;
}

/// Writes `text` as `name` into a fresh temp dir; its path.
std::string written(const std::string& tag, const std::string& name, const std::string& text) {
  const std::string path = test::tempDir(tag) + "/" + name;
  test::writeFile(path, text);
  return path;
}

TEST(Prediction, AHoleDeeperThanTheDrillCutsFailsAloneAndLeavesTheOthersAsTheyWere) {
  // housing-kr120: Ø8.5 drill, <drill stickout_mm="34"> (no flute length): it cuts 34 mm at most.
  // A 358 mm "hole" (a pick-and-place move fed slowly) fails with its reason, no IK, no time;
  // the holes around it are predicted as without it (it seeds nothing).
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const std::string with =
      written("deep", "p.src", test::krlCyclesOfDepths({18.0, 358.0, 34.0, 20.0}));
  const api::PredictionContext c = api::loadPredictionContext(cell, with, std::nullopt, "");
  ASSERT_EQ(c.job.requests.size(), 4u);
  for (const int threads : {1, 2}) {
    PredictOptions o;
    o.threads = threads;
    const std::vector<HolePrediction> p = predictHoles(c.model, c.job.requests, o);
    EXPECT_EQ(p[1].status, HoleStatus::kUnreachable);
    EXPECT_EQ(p[1].verdict, Verdict::kUnreachable);
    EXPECT_TRUE(p[1].beyond_drill);
    EXPECT_NE(p[1].reason.find("the hole is 358 mm deep, the Ø8.5 mm drill cuts 34 mm at most "
                               "(cell <drill stickout_mm>)"),
              std::string::npos)
        << p[1].reason;
    EXPECT_NEAR(p[1].depth, 358e-3, 1e-9);
    EXPECT_EQ(p[1].mc_time, 0.0);
    // exactly the drill's length is cut
    EXPECT_EQ(p[2].status, HoleStatus::kOk) << p[2].reason;
    EXPECT_FALSE(p[2].beyond_drill);
    EXPECT_GT(p[2].mc_time, 0.0);
    std::vector<HoleRequest> others = c.job.requests;
    others.erase(others.begin() + 1);
    const std::vector<HolePrediction> q = predictHoles(c.model, others, o);
    for (const auto& [i, k] : {std::pair{0, 0}, {2, 1}, {3, 2}}) {
      EXPECT_EQ(p[i].status, HoleStatus::kOk) << p[i].reason;
      EXPECT_TRUE(test::sameBits(p[i].d_work.data(), q[k].d_work.data(), 3)) << i;
      EXPECT_TRUE(test::sameBits(p[i].joints.data(), q[k].joints.data(), 6)) << i;
      EXPECT_TRUE(test::sameBits(p[i].U_work_exact, q[k].U_work_exact)) << i;
    }
  }
}

/// part (a prediction without the budget) has full's solution, status and deflection, bit for
/// bit, and no budget.
void expectFullWithoutTheBudget(const HolePrediction& part, const HolePrediction& full) {
  EXPECT_EQ(part.status, full.status);
  EXPECT_EQ(part.reason, full.reason);
  EXPECT_EQ(part.branch, full.branch);
  EXPECT_EQ(part.config, full.config);
  EXPECT_TRUE(test::sameBits(part.joints.data(), full.joints.data(), 6));
  EXPECT_TRUE(test::sameBits(part.d_robot.data(), full.d_robot.data(), 3));
  if (full.status != HoleStatus::kOk) return;
  EXPECT_GT(full.U_work_exact, 0.0);
  EXPECT_EQ(part.U_work_exact, 0.0);  // not made
  EXPECT_TRUE(part.budget.empty());
}

// Without the budget (PredictOptions::budget false) every hole takes the
// solution, status and deflection of the full prediction, bit for bit, on one thread and two
// (holes out of reach among them break the continuity chain); the budget is not made.
TEST(Prediction, WithoutTheBudgetEachHoleTakesTheFullPredictionsSolutionAndStatus) {
  const api::PredictionContext c = api::loadPredictionContext(
      test::sourceDir() + "/samples/cells/housing-kr120.xml",
      test::sourceDir() + "/samples/emotor-housing/holes.csv", std::nullopt, "");
  std::vector<HoleRequest> req = c.job.requests;
  for (size_t i = 0; i < req.size(); i += 9) req[i].T_W_tcp.translation().x() += 3.0;
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    PredictOptions o;
    o.threads = threads;
    const std::vector<HolePrediction> full = predictHoles(c.model, req, o);
    o.budget = false;
    const std::vector<HolePrediction> part = predictHoles(c.model, req, o);
    ASSERT_EQ(part.size(), full.size());
    int ok = 0;
    for (size_t i = 0; i < req.size(); ++i) {
      SCOPED_TRACE(req[i].id);
      expectFullWithoutTheBudget(part[i], full[i]);
      ok += full[i].status == HoleStatus::kOk ? 1 : 0;
    }
    EXPECT_GT(ok, 100);
    EXPECT_LT(ok, static_cast<int>(req.size()) - 10);
  }
}

TEST(Prediction, TheDrillsFluteLengthLimitsTheDepthItCuts) {
  // a cell stating <drill flute_length_mm="20">: a 26 mm hole fails, a 20 mm one does not
  std::string xml = test::readFile(test::sourceDir() + "/samples/cells/housing-kr120.xml");
  const std::string from = "stickout_mm=\"34\"";
  ASSERT_NE(xml.find(from), std::string::npos);
  xml.replace(xml.find(from), from.size(), from + " flute_length_mm=\"20\"");
  const std::string dir = test::tempDir("flute");
  test::writeFile(dir + "/cell.xml", xml);
  test::writeFile(dir + "/p.src", test::krlCyclesOfDepths({20.0, 26.0}));
  const api::PredictionContext c =
      api::loadPredictionContext(dir + "/cell.xml", dir + "/p.src", std::nullopt, "");
  const std::vector<HolePrediction> p = predictHoles(c.model, c.job.requests);
  EXPECT_EQ(p[0].status, HoleStatus::kOk) << p[0].reason;
  EXPECT_EQ(p[1].verdict, Verdict::kUnreachable);
  EXPECT_NE(p[1].reason.find("cuts 20 mm at most (cell <drill flute_length_mm>)"),
            std::string::npos)
      << p[1].reason;
}

TEST(PredictionCli, AHoleDeeperThanTheDrillCutsIsAFailedHoleNotAVerdictOfTheJob) {
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const std::string prog = written("deepcli", "p.src", test::krlCyclesOfDepths({18.0, 358.0}));
  const std::string json = prog + ".json";
  const auto r =
      test::runRoprec("predict --cell '" + cell + "' '" + prog + "' --json '" + json + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("roprec: hole H2 (" + prog +
                       ":13): unreachable: the drill cannot reach the bottom: the hole is 358 mm "
                       "deep"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("hole H1 ("), std::string::npos) << r.err;  // predicted normally
  const std::string j = test::readFile(json);
  const std::size_t h2 = j.find("\"id\": \"H2\"");
  ASSERT_NE(h2, std::string::npos) << j;
  const std::string tail = j.substr(h2);
  EXPECT_NE(tail.find("\"depth_mm\": 358.000"), std::string::npos);
  EXPECT_NE(tail.find("\"verdict\": \"unreachable\""), std::string::npos);
  EXPECT_NE(tail.find("\"reason\": \"the drill cannot reach the bottom"), std::string::npos);
  EXPECT_NE(tail.find("\"mc_time_s\": 0.000"), std::string::npos);
  EXPECT_EQ(tail.substr(0, tail.find("\"verdict\"")).find("joints_deg"), std::string::npos);
}

/// The "evidence" members of a prediction JSON, in hole order.
std::vector<std::string> evidenceOf(const std::string& json) {
  std::vector<std::string> e;
  const std::regex member("\"evidence\": \"([^\"]*)\"");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), member);
       it != std::sregex_iterator(); ++it)
    e.push_back((*it)[1]);
  return e;
}

TEST(PredictionCli, EveryHoleStatesItsDrillingEvidence) {
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const std::string dir = test::tempDir("evidence");
  // a slower feed along the tool axis; a spindle call with one speed throughout; a hole list
  test::writeFile(dir + "/feed.src", test::krlCyclesOfDepths({18.0, 20.0}));
  test::writeFile(dir + "/call.src",
                  std::string("DEF c ( )\n") + test::kHousingBase +
                      "\n$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n"
                      "$VEL.CP = 0.25\n"
                      "PTP {X 0.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 180.000}\n"
                      "LIN {X 0.000,Y 0.000,Z 282.000,A 0.000,B 0.000,C 180.000}\n"
                      "SPINDLE_DRILL()\n"
                      "LIN {X 0.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 180.000}\n"
                      "END\n");
  test::writeFile(dir + "/holes.csv", "id,x,y,z,i,j,k\nA1,100,0,150,0,0,-1\nA2,120,0,150,0,0,-1\n");
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases{
      {"feed.src", {"feed segment along the tool axis", "feed segment along the tool axis"}},
      {"call.src", {"call SPINDLE_DRILL after the motion at line 6"}},
      {"holes.csv", {"on the hole list", "on the hole list"}}};
  for (const auto& [file, expected] : cases) {
    const auto r = test::runRoprec("predict --cell '" + cell + "' '" + dir + "/" + file +
                                   "' --json '" + dir + "/" + file + ".json' --quiet");
    EXPECT_LE(r.exit_code, 1) << file << r.err;
    const std::string j = test::readFile(dir + "/" + file + ".json");
    EXPECT_EQ(evidenceOf(j), expected) << file;
    // one member per hole, right after its id and line
    EXPECT_NE(j.find("\"line\": " +
                     std::string(file == "holes.csv"  ? "2"
                                 : file == "call.src" ? "6"
                                                      : "7") +
                     ",\n      \"evidence\": \""),
              std::string::npos)
        << j.substr(0, 1500);
  }
}

TEST(PredictionCli, AnUnreachableHoleIsNamedOnceWithItsLineAndVerdict) {
  const std::string dir = test::tempDir("err-unreachable");
  test::writeFile(dir + "/far.csv", "id,x,y,z,i,j,k\nF1,9000,0,0,0,0,-1\nF2,100,0,150,0,0,-1\n");
  const test::RunResult r =
      test::runRoprec("predict --cell '" + test::sourceDir() +
                      "/samples/cells/housing-kr120.xml' '" + dir + "/far.csv' --json -");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(
      r.err.find("roprec: hole F1 (" + dir + "/far.csv:2): unreachable: the wrist centre is "),
      std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("unreachable: unreachable"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
