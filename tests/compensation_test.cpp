// Compensation against independent references and its contract:
//  * every bundled robot, every orientation mode: the predicted residual at the nominal hole is
//    ≤ 0.1 µm, and the compensated commands fed to an independent nonlinear joint-compliance
//    equilibrium computed here with KDL (FK + RNE, same stiffness, tool mass and tool-frame
//    process wrench) land on the nominal holes ≤ 0.5 µm;
//  * keep changes positions only (orientation within 1e-9 rad); stiffest never predicts a larger
//    U_work than keep; flip-free removes the axis-4/6 flips of a sample built to flip under keep
//    and keeps |θ5| ≥ the margin;
//  * orientation choices: on the 204-hole demo flip-free turns no hole that keep could
//    drill without a jump, limit or wrist-margin violation, and every turned hole has its reason;
//    stiffest makes no axis-4/6 jump over the threshold and reports its U_work gain over keep;
//    flags stay as programmed at a sign boundary (A4 = 0 on the x axis) and a hole that really
//    needs other flags gets them with the reason;
//  * CLI: unreachable holes -> exit 1 and nothing written; --allow-partial flags them; outputs
//    are byte-identical for identical inputs.
#include "compensator/compensation/compensation.hpp"

#include <gtest/gtest.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "compensator/robot/geometry_calibration.hpp"
#include "plugin/api/prediction_setup.hpp"
#include "tests/support/compensation_compare.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

struct RobotCase {
  std::string robot;
  std::string cell;  // sample cell for this robot
};

const std::vector<RobotCase>& robots() {
  static const std::vector<RobotCase> r = {{"kuka-kr120-r2500-pro", "housing-kr120.xml"},
                                           {"abb-irb6640-185-280", "housing-irb6640.xml"},
                                           {"fanuc-r2000ic-165f", "housing-r2000.xml"}};
  return r;
}

/// A hole list with 8 top-face and 6 side-face holes of the sample housing (every 6th / 8th row).
std::string writeHoleSubset(const std::string& dir) {
  std::ifstream in(test::sourceDir() + "/samples/emotor-housing/holes.csv");
  std::ofstream out(dir + "/holes.csv");
  std::string line;
  int top = 0;
  int side = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("id,", 0) == 0) {
      out << line << "\n";
      continue;
    }
    if (line[0] == 'T' && top < 8 && (top++ % 1) == 0) out << line << "\n";
    if (line[0] == 'R' && side < 6) {
      ++side;
      out << line << "\n";
    }
  }
  return dir + "/holes.csv";
}

/// KDL: chain + spindle segment; returns the real TCP position for the command θ_cmd by the
/// fixed point θ = θ_cmd + off − K⁻¹ τ_KDL(θ) (off: the controller's own gravity compensation).
/// `truth`: the calibrated robot's geometry (nullptr: the card's URDF).
Vec3 kdlRealTcp(const api::PredictionContext& c, const nc::Vec6& theta_cmd, const ToolWrench& w,
                const test::KdlTruthGeometry* truth = nullptr) {
  const ChainDescription& ch = c.robot.chain;
  KDL::Chain kc = truth != nullptr
                      ? truth->chain(ch.base_link, ch.tip_link)
                      : test::kdlChain(c.robot.card.urdf_path, ch.base_link, ch.tip_link);
  const nc::ToolAttachment& t = c.tool;
  const Pose T_tcp_flange = t.T_flange_tcp.inverse();
  const Vec3 com = T_tcp_flange * t.com;
  const Mat3 I = T_tcp_flange.linear() * t.inertia * T_tcp_flange.linear().transpose();
  kc.addSegment(KDL::Segment(
      "tool", KDL::Joint(KDL::Joint::None), test::toKdl(t.T_flange_tcp),
      KDL::RigidBodyInertia(
          t.mass, KDL::Vector(com.x(), com.y(), com.z()),
          KDL::RotationalInertia(I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)))));
  KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
  KDL::ChainFkSolverPos_recursive fk(kc);
  nc::Vec6 k;
  for (int i = 0; i < 6; ++i) k[i] = c.robot.card.joints[static_cast<size_t>(i)].stiffness;
  auto tau = [&](const nc::Vec6& th, bool with_wrench, const KDL::Chain& chain,
                 KDL::ChainIdSolver_RNE& solver) {
    KDL::JntArray q(6);
    KDL::JntArray z(6);
    KDL::JntArray out(6);
    for (unsigned i = 0; i < 6; ++i) q(i) = th[i];
    KDL::Wrenches f(chain.getNrOfSegments(), KDL::Wrench::Zero());
    if (with_wrench) {
      f.back() = KDL::Wrench(KDL::Vector(w.force.x(), w.force.y(), w.force.z()),
                             KDL::Vector(w.torque.x(), w.torque.y(), w.torque.z()));
    }
    solver.CartToJnt(q, z, z, f, out);
    nc::Vec6 r;
    for (unsigned i = 0; i < 6; ++i) r[i] = out(i);
    const Counterbalance& cb = c.robot.chain.counterbalance;  // the axis-2 balancer's share
    if (cb.present()) r[cb.joint] -= balancerTorque(cb, th[cb.joint]);
    return r;
  };
  nc::Vec6 off = nc::Vec6::Zero();
  if (c.model.controller.kind == nc::ControllerReference::Kind::kGravityCompensated)
    off = tau(theta_cmd, false, kc, rne).cwiseQuotient(k);  // calibration load = tool
  else if (c.model.controller.kind == nc::ControllerReference::Kind::kMastering)
    off = c.model.controller.calibration_pose_torque.cwiseQuotient(k);  // checked in gravity tests
  nc::Vec6 th = theta_cmd;
  for (int it = 0; it < 200; ++it) th = theta_cmd + off - tau(th, true, kc, rne).cwiseQuotient(k);
  KDL::JntArray q(6);
  for (unsigned i = 0; i < 6; ++i) q(i) = th[i];
  KDL::Frame F;
  fk.JntToCart(q, F);
  return Vec3(F.p.x(), F.p.y(), F.p.z());
}

TEST(Compensation, EveryRobotEveryModeLandsOnTheNominalHoles) {
  const std::string dir = test::tempDir("comp");
  const std::string holes = writeHoleSubset(dir);
  for (const RobotCase& rc : robots()) {
    SCOPED_TRACE(rc.robot);
    const api::PredictionContext c = api::loadPredictionContext(
        test::sourceDir() + "/samples/cells/" + rc.cell, holes, std::nullopt, "");
    ASSERT_TRUE(c.model.has_process);
    const ToolWrench w = c.model.process_by_diameter.begin()->second.wrench;
    std::vector<HoleCompensation> keep;
    for (const OrientationMode mode :
         {OrientationMode::kKeep, OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
      SCOPED_TRACE(orientationModeName(mode));
      CompensationOptions o;
      o.mode = mode;
      o.grid = 24;
      const std::vector<HoleCompensation> comp = compensateHoles(c.model, c.job.requests, o);
      ASSERT_EQ(comp.size(), c.job.requests.size());
      for (size_t i = 0; i < comp.size(); ++i) {
        const HoleCompensation& h = comp[i];
        ASSERT_TRUE(h.ok) << h.id << ": " << h.reason;
        EXPECT_LE(h.residual.norm(), 1e-7) << h.id;  // 0.1 µm, the library's own prediction
        if (mode == OrientationMode::kKeep) {
          EXPECT_LE((h.T_programmed.linear() - c.job.requests[i].T_W_tcp.linear()).norm(), 1e-9)
              << h.id;
        }
        // independent: KDL equilibrium at the compensated command lands on the nominal hole
        const ToolWrench wd =
            c.model.process_by_diameter.count(std::lround(c.job.requests[i].diameter * 1e6))
                ? c.model.process_by_diameter.at(std::lround(c.job.requests[i].diameter * 1e6))
                      .wrench
                : w;
        const Vec3 real = kdlRealTcp(c, h.theta_cmd, wd);
        EXPECT_LE((real - h.T_nominal.translation()).norm(), 0.5e-6) << h.id << " (KDL)";
      }
      if (mode == OrientationMode::kKeep) keep = comp;
      if (mode == OrientationMode::kStiffest) {
        for (size_t i = 0; i < comp.size(); ++i) {
          EXPECT_LE(comp[i].after.U_work, keep[i].after.U_work + 1e-9) << comp[i].id;
        }
      }
    }
  }
}

/// A sample cell whose robot is a copy of its bundled card with `cal` as <calibration>, and the
/// KDL truth of that robot.
std::string calibratedCell(const RobotCase& rc, const GeometryCalibration& cal,
                           const std::string& dir, test::KdlTruthGeometry& truth) {
  const Robot robot = loadRobot({rc.robot, "", ""});
  std::array<std::string, 6> names;
  for (size_t i = 0; i < 6; ++i) names[i] = robot.card.joints[i].name;
  truth = test::kdlTruthGeometry(robot, cal, dir);
  const std::string card = test::cardWithCalibration(robot, calibrationXml(cal, names), dir);
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/" + rc.cell);
  const std::string ref = "<robot ref=\"" + rc.robot + "\"/>";
  const std::size_t r = cell.find(ref);
  EXPECT_NE(r, std::string::npos);
  cell.replace(r, ref.size(), "<robot file=\"" + card + "\"/>");
  test::writeFile(dir + "/cell.xml", cell);
  return dir + "/cell.xml";
}

TEST(Compensation, CalibratedRobotLandsOnTheNominalHolesOfItsKdlTruth) {
  // The truth robot is KDL on a perturbed URDF (not roprec's chain). Its uncompensated holes
  // miss by the geometric error (well above the deflection); the compensated commands, moved by
  // the controller's nominal kinematics, put the truth's TCP on the nominal holes.
  const std::string dir = test::tempDir("comp-cal");
  const std::string holes = writeHoleSubset(dir);
  for (const RobotCase& rc : {robots()[0], robots()[1]}) {
    SCOPED_TRACE(rc.robot);
    const std::string rdir = test::tempDir("comp-cal-" + rc.robot);
    test::KdlTruthGeometry truth;
    const std::string cell =
        calibratedCell(rc, test::seededGeometryErrors(8, 0.3, 0.4), rdir, truth);
    const api::PredictionContext c = api::loadPredictionContext(cell, holes, std::nullopt, "");
    ASSERT_TRUE(c.model.calibrated);
    const ToolWrench w = c.model.process_by_diameter.begin()->second.wrench;
    for (const OrientationMode mode : {OrientationMode::kKeep, OrientationMode::kFlipFree}) {
      SCOPED_TRACE(orientationModeName(mode));
      CompensationOptions o;
      o.mode = mode;
      const std::vector<HoleCompensation> comp = compensateHoles(c.model, c.job.requests, o);
      for (size_t i = 0; i < comp.size(); ++i) {
        const HoleCompensation& h = comp[i];
        ASSERT_TRUE(h.ok) << h.id << ": " << h.reason;
        const ToolWrench wd =
            c.model.process_by_diameter.count(std::lround(c.job.requests[i].diameter * 1e6))
                ? c.model.process_by_diameter.at(std::lround(c.job.requests[i].diameter * 1e6))
                      .wrench
                : w;
        // before: roprec's predicted real TCP is the truth's at the uncompensated command
        const Vec3 before = kdlRealTcp(c, h.before.joints, wd, &truth);
        const Vec3 programmed = c.job.requests[i].T_W_tcp.translation();
        EXPECT_GT((before - programmed).norm(), 0.2e-3) << h.id;  // the geometry is visible
        EXPECT_LE((before - programmed - h.before.d_robot).norm(), 0.5e-6) << h.id;
        // after: the truth lands on the nominal hole
        const Vec3 real = kdlRealTcp(c, h.theta_cmd, wd, &truth);
        EXPECT_LE((real - h.T_nominal.translation()).norm(), 0.5e-6) << h.id << " (KDL)";
        EXPECT_LE(h.residual.norm(), 1e-7) << h.id;
      }
    }
  }
}

TEST(Compensation, FlipFreeRemovesTheFlipsOfASampleBuiltToFlip) {
  // One row of top-face holes whose programmed rotation about the drill axis alternates 0/180°:
  // under keep the wrist must turn half a revolution between neighbours.
  const std::string dir = test::tempDir("flip");
  const std::string holes = writeHoleSubset(dir);
  const api::PredictionContext c = api::loadPredictionContext(
      test::sourceDir() + "/samples/cells/housing-kr120.xml", holes, std::nullopt, "");
  std::vector<HoleRequest> row;
  for (int k = 0; k < 8; ++k) {
    HoleRequest r = c.job.requests[static_cast<size_t>(k)];
    if (r.T_W_tcp.linear().col(2).z() > -0.99) continue;  // top face only
    if (k % 2) r.T_W_tcp.rotate(Eigen::AngleAxisd(kPi, Vec3::UnitZ()));
    row.push_back(r);
  }
  ASSERT_GE(row.size(), 6u);
  CompensationOptions keep;
  keep.mode = OrientationMode::kKeep;
  const auto k = compensateHoles(c.model, row, keep);
  int flips_keep = 0;
  for (size_t i = 1; i < k.size(); ++i) {
    ASSERT_TRUE(k[i].ok && k[i - 1].ok);
    if (std::abs(k[i].theta_cmd[3] - k[i - 1].theta_cmd[3]) > keep.jump_threshold ||
        std::abs(k[i].theta_cmd[5] - k[i - 1].theta_cmd[5]) > keep.jump_threshold) {
      ++flips_keep;
    }
  }
  EXPECT_GE(flips_keep, 3) << "the sample must flip under keep";
  CompensationOptions ff;
  ff.mode = OrientationMode::kFlipFree;
  CompensationStats st;
  const auto f = compensateHoles(c.model, row, ff, &st);
  EXPECT_FALSE(st.relaxed_jumps);
  for (size_t i = 0; i < f.size(); ++i) {
    ASSERT_TRUE(f[i].ok) << f[i].reason;
    EXPECT_GE(ikBranch(c.model.ik, f[i].theta_cmd).wrist_margin_rad,
              std::sin(ff.wrist_margin) - 1e-9);
    if (i > 0) {
      EXPECT_LE(std::abs(f[i].theta_cmd[3] - f[i - 1].theta_cmd[3]), ff.jump_threshold);
      EXPECT_LE(std::abs(f[i].theta_cmd[5] - f[i - 1].theta_cmd[5]), ff.jump_threshold);
    }
  }
}

/// The demo job (samples/emotor-housing, KR 120, KRL) through the library.
api::PredictionContext demoContext() {
  return api::loadPredictionContext(test::sourceDir() + "/samples/cells/housing-kr120.xml",
                                    test::sourceDir() + "/samples/emotor-housing/housing_kr120.src",
                                    test::sourceDir() + "/samples/emotor-housing/holes.csv", "");
}

bool sameFaceAxis(const HoleRequest& a, const HoleRequest& b) {
  return a.T_W_tcp.linear().col(2).dot(b.T_W_tcp.linear().col(2)) > std::cos(10.0 * kDeg);
}

double wristJump(const Vec6& a, const Vec6& b) {
  return std::max(std::abs(a[3] - b[3]), std::abs(a[5] - b[5]));
}

TEST(CompensationOrientation, FlipFreeOnTheDemoTurnsOnlyHolesWithAReason) {
  const api::PredictionContext c = demoContext();
  const auto& req = c.job.requests;
  ASSERT_EQ(req.size(), 204u);
  CompensationOptions keep;
  keep.mode = OrientationMode::kKeep;
  const auto k = compensateHoles(c.model, req, keep);
  CompensationOptions ff;
  ff.mode = OrientationMode::kFlipFree;
  CompensationStats st;
  const auto f = compensateHoles(c.model, req, ff, &st);
  // Holes with a real reason to turn, judged on the keep result (ψ = 0): a jump > threshold to a
  // same-face neighbour, |θ5| below the margin, or no keep result at all.
  std::vector<bool> reason(req.size(), false);
  for (size_t i = 0; i < req.size(); ++i) {
    if (!k[i].ok) {
      reason[i] = true;
      continue;
    }
    if (std::abs(std::sin(k[i].theta_cmd[4])) < std::sin(ff.wrist_margin)) reason[i] = true;
    for (const size_t j : {i - 1, i + 1}) {
      if (j >= req.size() || !k[j].ok || !sameFaceAxis(req[i], req[j])) continue;
      if (wristJump(k[i].theta_cmd, k[j].theta_cmd) > ff.jump_threshold) reason[i] = true;
    }
  }
  int turned = 0;
  int with_reason = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    ASSERT_TRUE(f[i].ok) << f[i].id << ": " << f[i].reason;
    with_reason += reason[i] ? 1 : 0;
    if (std::abs(f[i].psi) > 1e-9) {
      ++turned;
      EXPECT_FALSE(f[i].psi_reason.empty()) << f[i].id;
      // a hole is turned only next to or at a hole with a reason
      const bool near =
          reason[i] || (i > 0 && reason[i - 1]) || (i + 1 < f.size() && reason[i + 1]);
      EXPECT_TRUE(near) << f[i].id << " turned by " << f[i].psi / kDeg
                        << " deg: " << f[i].psi_reason;
    } else {
      EXPECT_TRUE(f[i].psi_reason.empty()) << f[i].id;
    }
  }
  EXPECT_LE(turned, with_reason);
  EXPECT_EQ(st.psi_changed, turned);
  EXPECT_EQ(st.psi_for_limits + st.psi_for_wrist + st.psi_for_jumps + st.psi_for_stiffness, turned);
  // the demo program has no flags: the written (posture) flags do not change either
  for (const auto& h : f)
    EXPECT_EQ(h.config_text, h.config_before) << h.id << ": " << h.config_reason;
}

TEST(CompensationOrientation, StiffestObeysTheJumpLimitAndReportsItsGain) {
  const api::PredictionContext c = demoContext();
  const auto& req = c.job.requests;
  CompensationOptions o;
  o.mode = OrientationMode::kStiffest;
  CompensationStats st;
  const auto s = compensateHoles(c.model, req, o, &st);
  EXPECT_FALSE(st.relaxed_jumps);
  int jumps = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    ASSERT_TRUE(s[i].ok) << s[i].id << ": " << s[i].reason;
    EXPECT_GE(std::abs(std::sin(s[i].theta_cmd[4])), std::sin(o.wrist_margin) - 1e-6) << s[i].id;
    if (i > 0 && sameFaceAxis(req[i], req[i - 1]) &&
        wristJump(s[i].theta_cmd, s[i - 1].theta_cmd) > o.jump_threshold) {
      ++jumps;
    }
    ASSERT_TRUE(std::isfinite(s[i].U_work_keep)) << s[i].id;
    if (std::abs(s[i].psi) > 1e-9) {
      EXPECT_FALSE(s[i].psi_reason.empty()) << s[i].id;
    }
  }
  EXPECT_EQ(jumps, 0);
  // the gain over keep, summed: stiffest is not worse on the whole job
  EXPECT_EQ(st.stiffness_compared, static_cast<int>(req.size()));
  EXPECT_LE(st.U_work_sum, st.U_work_keep_sum + 1e-12);
  std::printf(
      "stiffest on the demo: mean U_work %.3f um (keep %.3f um), largest gain %.3f um, "
      "%d holes turned\n",
      st.U_work_sum / st.stiffness_compared * 1e6, st.U_work_keep_sum / st.stiffness_compared * 1e6,
      st.U_work_gain_max * 1e6, st.psi_changed);
}

// Stiffest keeps a hole at ψ = 0 only with its keep result (made only as far as whether it is ok,
// when both are): every hole of the demo stiffest leaves at ψ = 0 is keep's result for it, bit for
// bit (the programmed pose, the command, the budget after), with the U_work of keep it reports.
TEST(CompensationOrientation, StiffestHolesAtTheProgrammedRotationAreKeepsResults) {
  const api::PredictionContext c = demoContext();
  const auto& req = c.job.requests;
  CompensationOptions o;
  const std::vector<HoleCompensation> keep = compensateHoles(c.model, req, o);
  o.mode = OrientationMode::kStiffest;
  const std::vector<HoleCompensation> s = compensateHoles(c.model, req, o);
  ASSERT_EQ(s.size(), keep.size());
  int kept = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    SCOPED_TRACE(s[i].id);
    ASSERT_TRUE(s[i].ok) << s[i].reason;
    if (std::abs(s[i].psi) > 1e-9) continue;
    ++kept;
    EXPECT_TRUE(test::sameBits(s[i].T_programmed.matrix().data(),
                               keep[i].T_programmed.matrix().data(), 16));
    EXPECT_TRUE(test::sameBits(s[i].theta_cmd.data(), keep[i].theta_cmd.data(), 6));
    EXPECT_TRUE(test::sameBits(s[i].after.U_work_exact, keep[i].after.U_work_exact));
    EXPECT_TRUE(test::sameBits(s[i].U_work_keep, keep[i].after.U_work_exact));
    EXPECT_EQ(s[i].config_text, keep[i].config_text);
  }
  EXPECT_GT(kept, static_cast<int>(s.size()) / 2);
}

// flip-free and stiffest hold one block of predictions and candidate grids at a time (the DP
// keeps its last reachable hole and a table of predecessors, the chosen nodes are evaluated again,
// the predictions made again block by block): blocks of 1, 3 and 50 holes give the result of one
// block holding the whole program, bit for bit, with the same counters. The demo on several faces
// with every fifth hole turned by 90° about its axis (turned back for the jump limit) and three
// holes out of reach, two of them in a row (the DP's chain breaks and starts again); at the
// default jump threshold and at 5°, which no sequence meets (the threshold is relaxed: the grids
// are evaluated again).
TEST(CompensationOrientation, BlocksOfAnySizeGiveTheResultOfOneBlock) {
  const api::PredictionContext c = demoContext();
  std::vector<HoleRequest> req = c.job.requests;
  for (size_t i = 1; i < req.size(); i += 5)
    req[i].T_W_tcp.linear() *= Eigen::AngleAxisd(90.0 * kDeg, Vec3::UnitZ()).toRotationMatrix();
  for (const size_t i : {30, 31, 100}) req[i].T_W_tcp.translation().x() += 3.0;
  for (const auto& [mode, threshold] :
       {std::pair{OrientationMode::kFlipFree, 60.0}, std::pair{OrientationMode::kStiffest, 60.0},
        std::pair{OrientationMode::kFlipFree, 5.0}}) {
    SCOPED_TRACE(testing::Message() << orientationModeName(mode) << ", jumps " << threshold);
    CompensationOptions o;
    o.mode = mode;
    o.jump_threshold = threshold * kDeg;
    o.block = req.size();
    CompensationStats ref_st;
    const std::vector<HoleCompensation> ref = compensateHoles(c.model, req, o, &ref_st);
    EXPECT_GT(ref_st.psi_changed, 10);
    EXPECT_EQ(ref_st.relaxed_jumps, threshold < 10.0);
    EXPECT_EQ(std::count_if(ref.begin(), ref.end(), [](const auto& h) { return !h.ok; }), 3);
    for (const size_t block : {1, 3, 50}) {
      for (const int threads : {1, 2}) {
        SCOPED_TRACE(testing::Message() << "block " << block << ", threads " << threads);
        o.block = block;
        o.threads = threads;
        CompensationStats st;
        const std::vector<HoleCompensation> got = compensateHoles(c.model, req, o, &st);
        ASSERT_EQ(got.size(), ref.size());
        for (size_t i = 0; i < ref.size(); ++i) test::expectSameHole(got[i], ref[i]);
        test::expectSameStats(st, ref_st);
      }
    }
  }
}

/// The demo's job on the sample cell with its tool line `from` replaced by `to` (test::tempDir).
api::PredictionContext demoContextWithTool(const std::string& from, const std::string& to) {
  std::string text = test::readFile(test::sourceDir() + "/samples/cells/housing-kr120.xml");
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const std::string cell = test::tempDir("compensation-tool") + "/cell.xml";
  test::writeFile(cell, text);
  return api::loadPredictionContext(cell,
                                    test::sourceDir() + "/samples/emotor-housing/housing_kr120.src",
                                    test::sourceDir() + "/samples/emotor-housing/holes.csv", "");
}

// flip-free and stiffest evaluate only node 0 (ψ = 0) of a run of holes where that node is proven
// to be the DP's choice (stiffest: its turn gap, a bound on what any rotation can gain, exceeds
// the links beside it): the result is the one of every grid evaluated, bit for bit, with the same
// counters but the candidates evaluated. On the demo with every fifth hole turned by 90° (turned
// back for the jump limit) and three holes out of reach, and with the tool changed: its centre of
// mass 150 mm off the drill axis and 60 kg (a rotation about the axis moves that weight, and
// stiffest turns holes for it: a bound that left the weight out would keep them), and its TCP
// 40 mm off joint 6's axis (no bound: stiffest evaluates every grid).
TEST(CompensationOrientation, ProvenRunsGiveTheResultOfEveryGrid) {
  struct Case {
    const char* name;
    api::PredictionContext c;
  };
  const std::string tool = "xyz=\"0 0 320\" rpy=\"0 0 0\" mass_kg=\"25.8\" com_mm=\"0 0 120\"";
  std::vector<Case> cases;
  cases.push_back({"demo", demoContext()});
  cases.push_back(
      {"weight off the axis", demoContextWithTool(tool,
                                                  "xyz=\"0 0 320\" rpy=\"0 0 0\" mass_kg=\"60\" "
                                                  "com_mm=\"150 0 120\"")});
  cases.push_back(
      {"TCP off the axis", demoContextWithTool(tool,
                                               "xyz=\"40 0 320\" rpy=\"0 0 0\" mass_kg=\"25.8\" "
                                               "com_mm=\"0 0 120\"")});
  for (const Case& k : cases) {
    std::vector<HoleRequest> changed = k.c.job.requests;
    for (size_t i = 1; i < changed.size(); i += 5)
      changed[i].T_W_tcp.linear() *=
          Eigen::AngleAxisd(90.0 * kDeg, Vec3::UnitZ()).toRotationMatrix();
    for (const size_t i : {30, 31, 100}) changed[i].T_W_tcp.translation().x() += 3.0;
    for (const bool as_programmed : {true, false}) {
      const std::vector<HoleRequest>& req = as_programmed ? k.c.job.requests : changed;
      for (const OrientationMode mode : {OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
        SCOPED_TRACE(testing::Message() << k.name << (as_programmed ? "" : ", turned holes") << ", "
                                        << orientationModeName(mode));
        CompensationOptions o;
        o.mode = mode;
        o.skip_proven_grids = false;
        CompensationStats every_st;
        const std::vector<HoleCompensation> every = compensateHoles(k.c.model, req, o, &every_st);
        o.skip_proven_grids = true;
        CompensationStats st;
        const std::vector<HoleCompensation> got = compensateHoles(k.c.model, req, o, &st);
        ASSERT_EQ(got.size(), every.size());
        for (size_t i = 0; i < every.size(); ++i) test::expectSameHole(got[i], every[i]);
        const int evaluated = st.dp_nodes;
        st.dp_nodes = every_st.dp_nodes;  // the candidates evaluated differ, nothing else
        st.infeasible_nodes = every_st.infeasible_nodes;
        test::expectSameStats(st, every_st);
        const std::string name = k.name;
        const bool stiffest = mode == OrientationMode::kStiffest;
        if (as_programmed && name == "demo") {
          EXPECT_LT(evaluated, every_st.dp_nodes / 2);
        }
        if (stiffest && name == "TCP off the axis") {
          EXPECT_EQ(evaluated, every_st.dp_nodes);  // no bound
        }
        if (stiffest && as_programmed && name == "weight off the axis") {
          EXPECT_GT(every_st.psi_changed, 100);  // turned for stiffness: the bound must not hold
        }
        std::printf("%s%s, %s: %d holes turned (%d for stiffness), %d of %d candidates\n", k.name,
                    as_programmed ? "" : ", turned holes", orientationModeName(mode),
                    every_st.psi_changed, every_st.psi_for_stiffness, evaluated, every_st.dp_nodes);
      }
    }
  }
}

// The refinement (COBYLA on ψ) keeps each hole's evaluations and answers a ψ asked again from
// them: every turned hole's link-side joints are the real robot's IK at its own rotation — its
// forward kinematics reach T_W_tcp · Rz(ψ) to 1e-9 — also where ψ is a refined value off the grid
// (a node kept from another hole or another ψ would not).
TEST(CompensationOrientation, RefinedHolesAreTheRealIkAtTheirOwnRotation) {
  const api::PredictionContext c = demoContext();
  std::vector<HoleRequest> req = c.job.requests;
  for (size_t i = 1; i < req.size(); i += 5)
    req[i].T_W_tcp.linear() *= Eigen::AngleAxisd(90.0 * kDeg, Vec3::UnitZ()).toRotationMatrix();
  const nc::Model& real = c.model.model;
  for (const OrientationMode mode : {OrientationMode::kFlipFree, OrientationMode::kStiffest}) {
    SCOPED_TRACE(orientationModeName(mode));
    CompensationOptions o;
    o.mode = mode;
    o.threads = 2;
    CompensationStats st;
    const std::vector<HoleCompensation> got = compensateHoles(c.model, req, o, &st);
    EXPECT_GT(st.refined, 0);
    int off_grid = 0;
    for (size_t i = 0; i < got.size(); ++i) {
      const HoleCompensation& h = got[i];
      if (!h.ok || std::abs(h.psi) <= 1e-9) continue;
      const double steps = h.psi / (2.0 * kPi / o.grid);
      if (std::abs(steps - std::round(steps)) > 1e-6) ++off_grid;
      const Pose target = req[i].T_W_tcp *
                          Pose(Eigen::AngleAxisd(h.psi, Vec3::UnitZ()).toRotationMatrix()) *
                          real.T_L6_tcp.inverse() * real.T_L6_flange;
      const IkResidual r = ikResidual(realIk(c.model), h.theta_d, target);
      EXPECT_LT(r.position, 1e-9) << h.id << " at " << h.psi / kDeg << " deg";
      EXPECT_LT(r.rotation, 1e-9) << h.id << " at " << h.psi / kDeg << " deg";
    }
    EXPECT_GT(off_grid, 0);
  }
}

TEST(CompensationFlags, ASignBoundaryKeepsTheProgrammedKukaTurn) {
  // Hand-written KRL: PTP approaches with S 2 T 2 to holes on the robot's x axis (A1 = A4 = 0
  // exactly). The compensation moves A4 by ~1e-4 deg to the negative side; T stays 2.
  const std::string dir = test::tempDir("flagsT");
  std::string prog =
      "DEF handwritten( )\n$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C "
      "0.000}\n$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n";
  for (const double x : {150.0, 120.0, 90.0}) {
    char b[512];
    std::snprintf(b, sizeof b,
                  "PTP {X %.3f,Y 0.000,Z 300.000,A 0.000,B 0.000,C 180.000,S 2,T 2} C_PTP\n"
                  "$VEL.CP = 0.25\nLIN {X %.3f,Y 0.000,Z 252.000,A 0.000,B 0.000,C 180.000}\n"
                  "$VEL.CP = 0.02\nLIN {X %.3f,Y 0.000,Z 234.000,A 0.000,B 0.000,C 180.000}\n"
                  "$VEL.CP = 0.25\nLIN {X %.3f,Y 0.000,Z 300.000,A 0.000,B 0.000,C 180.000}\n",
                  x, x, x, x);
    prog += b;
  }
  prog += "END\n";
  test::writeFile(dir + "/hand.src", prog);
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const api::PredictionContext c =
      api::loadPredictionContext(cell, dir + "/hand.src", std::nullopt, "");
  ASSERT_EQ(c.job.requests.size(), 3u);
  for (const OrientationMode mode : {OrientationMode::kKeep, OrientationMode::kFlipFree}) {
    CompensationOptions o;
    o.mode = mode;
    const auto r = compensateHoles(c.model, c.job.requests, o);
    bool boundary_crossed = false;
    for (const auto& h : r) {
      ASSERT_TRUE(h.ok) << h.reason;
      EXPECT_TRUE(h.config_in_program);
      EXPECT_EQ(h.config_before, "S 2 T 2");
      EXPECT_EQ(h.config_text, "S 2 T 2") << h.id << ": " << h.config_reason;
      EXPECT_FALSE(h.config_changed);
      // not vacuous: the command's own sign bits differ (A4 just below 0)
      const KukaConfig own = kukaConfig(c.model.ik, c.model.robot.card, h.theta_cmd);
      boundary_crossed |= *own.turn != 2;
      EXPECT_LE(std::abs(h.theta_cmd[0]), 1e-4) << h.id;  // A1 ≈ 0
    }
    EXPECT_TRUE(boundary_crossed);
  }
  const auto run = test::runRoprec("compensate --cell '" + cell + "' '" + dir + "/hand.src' -o '" +
                                   dir + "/out.src' --orientation keep");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string out = test::readFile(dir + "/out.src");
  size_t n = 0;
  for (size_t p = out.find("S 2,T 2}"); p != std::string::npos; p = out.find("S 2,T 2}", p + 1))
    ++n;
  EXPECT_EQ(n, 3u) << out;
}

TEST(CompensationFlags, AHoleThatNeedsOtherFlagsGetsThemWithTheReason) {
  // ABB: every other top-face hole of the sample turned by 180° and programmed with the flags of
  // its own posture. Flip-free turns those holes back (a 180° axis-6 jump otherwise), which moves
  // axis 6 two quadrants: cf6 must change, and the change is listed with its reason. The holes
  // that are not turned keep their flags.
  const std::string dir = test::tempDir("flagsABB");
  const std::string holes = writeHoleSubset(dir);
  const api::PredictionContext c = api::loadPredictionContext(
      test::sourceDir() + "/samples/cells/housing-irb6640.xml", holes, std::nullopt, "");
  std::vector<HoleRequest> row;
  PredictionData d(c.model);
  for (int k = 0; k < 8; ++k) {
    HoleRequest r = c.job.requests[static_cast<size_t>(k)];
    if (r.T_W_tcp.linear().col(2).z() > -0.99) continue;
    if (k % 2) r.T_W_tcp.rotate(Eigen::AngleAxisd(kPi, Vec3::UnitZ()));
    const HolePrediction p = predictHole(c.model, d, r, nullptr);
    ASSERT_EQ(p.status, HoleStatus::kOk);
    r.config = configurationOf(c.model.ik, c.model.robot.card, p.joints);
    row.push_back(r);
  }
  ASSERT_GE(row.size(), 6u);
  CompensationOptions ff;
  ff.mode = OrientationMode::kFlipFree;
  CompensationStats st;
  const auto f = compensateHoles(c.model, row, ff, &st);
  int changed = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    ASSERT_TRUE(f[i].ok) << f[i].reason;
    const std::string programmed = formatConfig(*row[i].config);
    EXPECT_EQ(f[i].config_before, programmed);
    if (std::abs(f[i].psi) < 1e-9) {
      EXPECT_EQ(f[i].config_text, programmed) << f[i].id << ": " << f[i].config_reason;
      continue;
    }
    EXPECT_NE(f[i].psi_reason.find("jump"), std::string::npos) << f[i].psi_reason;
    // the flags written are those of the command, and they differ from the program's
    EXPECT_EQ(f[i].config_text,
              formatConfig(configurationOf(c.model.ik, c.model.robot.card, f[i].theta_cmd)));
    EXPECT_TRUE(f[i].config_changed);
    EXPECT_NE(f[i].config_reason.find("cf6"), std::string::npos) << f[i].config_reason;
    EXPECT_NE(f[i].config_reason.find("rotation"), std::string::npos) << f[i].config_reason;
    ++changed;
  }
  EXPECT_GE(changed, 3);
  EXPECT_EQ(st.config_changed, changed);
}

TEST(CompensationCli, UnreachableHoleExitsOneAndWritesNothingUnlessPartialAllowed) {
  const std::string dir = test::tempDir("unreach");
  const std::string holes = writeHoleSubset(dir);
  {
    std::ofstream app(holes, std::ios::app);
    app << "FAR1,4000.000,0.000,250.000,0,0,-1,8.5,20.0,0.20\n";  // 4 m beyond the workobject
  }
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const std::string out = dir + "/out.csv";
  // with two threads the targets export is staged while the program is edited: dropped too
  for (const char* threads : {"1", "2"}) {
    const auto r = test::runRoprec("compensate --cell '" + cell + "' '" + holes + "' -o '" + out +
                                   "' --targets '" + dir + "/t.json' --threads " + threads);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("FAR1"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir + "/t.json")) << threads;
    for (const auto& e : fs::directory_iterator(dir))
      EXPECT_EQ(e.path().filename().string().find(".roprec-tmp."), std::string::npos) << e.path();
  }
  const auto p = test::runRoprec("compensate --cell '" + cell + "' '" + holes + "' -o '" + out +
                                 "' --targets '" + dir + "/t.json' --allow-partial");
  EXPECT_EQ(p.exit_code, 1) << p.err;
  ASSERT_TRUE(fs::exists(out));
  const std::string t = test::readFile(dir + "/t.json");
  EXPECT_NE(t.find("\"original-kept\""), std::string::npos);
  // the unreachable hole keeps its original row byte for byte
  EXPECT_NE(test::readFile(out).find("FAR1,4000.000,0.000,250.000,0,0,-1"), std::string::npos);
}

TEST(CompensationCli, AHoleDeeperThanTheDrillCutsIsNotCompensatedAndNamedWithItsReason) {
  const std::string dir = test::tempDir("deepcomp");
  test::writeFile(dir + "/p.src", test::krlCyclesOfDepths({18.0, 358.0, 20.0}));
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const auto r = test::runRoprec("compensate --cell '" + cell + "' '" + dir + "/p.src' -o '" + dir +
                                 "/out.src'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("roprec: hole H2 (" + dir +
                       "/p.src:13): not compensated: the drill cannot reach the bottom: the hole "
                       "is 358 mm deep, the Ø8.5 mm drill cuts 34 mm at most"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("hole H1 ("), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("hole H3 ("), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.src"));
  const auto p = test::runRoprec("compensate --cell '" + cell + "' '" + dir + "/p.src' -o '" + dir +
                                 "/out.src' --allow-partial");
  EXPECT_EQ(p.exit_code, 1) << p.err;
  ASSERT_TRUE(fs::exists(dir + "/out.src"));
  // the deep "hole" keeps its programmed targets
  EXPECT_NE(test::readFile(dir + "/out.src")
                .find("LIN {X 0.000,Y 0.000,Z -58.000,A 0.000,B 0.000,C 180.000}"),
            std::string::npos);
}

TEST(CompensationCli, OutputsAreByteIdenticalForIdenticalInputs) {
  const std::string dir = test::tempDir("det");
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const std::string prog = test::sourceDir() + "/samples/emotor-housing/housing_kr120.src";
  for (const char* run : {"a", "b"}) {
    const std::string d = dir + "/" + run;
    fs::create_directories(d);
    const auto r = test::runRoprec("compensate --cell '" + cell + "' '" + prog +
                                   "' --orientation flip-free -o '" + d + "/p.src' --targets '" +
                                   d + "/t.json' --report '" + d + "/r.html'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  for (const char* f : {"/p.src", "/t.json", "/r.html"}) {
    EXPECT_EQ(test::readFile(dir + "/a" + f), test::readFile(dir + "/b" + f)) << f;
  }
}

}  // namespace
}  // namespace roprec
