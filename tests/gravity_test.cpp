// Gravity as a real controller sees it (docs/model.md §6.3, §6.6): the axis-2 balancer against
// the law of cosines and its potential, the bundled balancers' sizing against KDL's gravity
// torques, the mastering reference (zero sag at the calibration pose, the predicted joint
// deflection against an independent KDL fixed point), one gravity handling for predict, deflect
// and simulate, and the card's weight elements (missing inertial, <gravity model="none"/>,
// <link> mass override against KDL).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <regex>
#include <sstream>

#include "compensator/robot/counterbalance.hpp"
#include "compensator/robot/deflection.hpp"
#include "compensator/support/error.hpp"
#include "plugin/api/deflect.hpp"
#include "plugin/api/robot_compliance.hpp"
#include "plugin/api/robot_setup.hpp"
#include "plugin/report/json.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

const char* const kRobots[] = {"kuka-kr120-r2500-pro", "abb-irb6640-185-280", "fanuc-r2000ic-165f"};

// ---------------------------------------------------------------- the balancer law

/// Independent planar computation: pivot O at the origin, A = (d, 0) fixed, B = r (cos ψ, sin ψ);
/// the force on B along A→B (positive pushing apart) and its moment about O, mapped to q by s.
double torqueByVectors(const Counterbalance& cb, double q) {
  const double psi = cb.psi0 + cb.sign * q;
  const Eigen::Vector2d A(cb.d, 0.0);
  const Eigen::Vector2d B(cb.r * std::cos(psi), cb.r * std::sin(psi));
  const double l = (B - A).norm();
  const bool push = cb.action == Counterbalance::Action::kPush;
  const double stroke = push ? cb.length_ref - l : l - cb.length_ref;
  double f = 0.0;
  if (cb.law == Counterbalance::Law::kSpring) {
    f = cb.force_ref + cb.stiffness * stroke;
  } else {
    f = cb.pressure_ref * cb.area *
        std::pow(cb.volume_ref / (cb.volume_ref - cb.area * stroke), cb.polytropic);
  }
  const Eigen::Vector2d F = (push ? f : -f) * (B - A) / l;
  return cb.sign * (B.x() * F.y() - B.y() * F.x());
}

std::vector<Counterbalance> balancerCases() {
  std::vector<Counterbalance> out;
  for (const auto law : {Counterbalance::Law::kSpring, Counterbalance::Law::kGas}) {
    for (const auto action : {Counterbalance::Action::kPush, Counterbalance::Action::kPull}) {
      for (const double sign : {1.0, -1.0}) {
        Counterbalance cb;
        cb.joint = 1;
        cb.law = law;
        cb.action = action;
        cb.r = 0.23;
        cb.d = 0.47;
        cb.psi0 = 0.4;
        cb.sign = sign;
        cb.length_ref = 0.45;
        cb.force_ref = 12000;
        cb.stiffness = 30000;
        cb.pressure_ref = 14e6;
        cb.area = 1.1e-3;
        cb.volume_ref = 0.5e-3;
        cb.polytropic = law == Counterbalance::Law::kGas && sign < 0 ? 1.3 : 1.0;
        out.push_back(cb);
      }
    }
  }
  return out;
}

TEST(Counterbalance, TorqueIsTheMomentOfTheBalancerForce) {
  // the closed form F r d sin ψ / ℓ against the cross product of the attachment vectors: 1e-12
  for (const Counterbalance& cb : balancerCases()) {
    for (double q = -1.2; q <= 1.2; q += 0.1) {
      const double ref = torqueByVectors(cb, q);
      EXPECT_NEAR(balancerTorque(cb, q), ref, 1e-12 * std::max(1.0, std::abs(ref))) << q;
    }
  }
}

TEST(Counterbalance, TorqueIsMinusTheGradientOfItsPotential) {
  // central difference of V (h = 1e-6 rad): truncation ~ h² V''' and rounding ~ 1e-16 V / h
  for (const Counterbalance& cb : balancerCases()) {
    for (double q = -1.2; q <= 1.2; q += 0.15) {
      const double h = 1e-6;
      const double fd = -(balancerEnergy(cb, q + h) - balancerEnergy(cb, q - h)) / (2 * h);
      EXPECT_NEAR(balancerTorque(cb, q), fd, 1e-5 * std::max(1.0, std::abs(fd))) << q;
    }
  }
}

// ---------------------------------------------------------------- KDL references

/// Drive torques with the card's balancer: τ = τ_g,KDL − τ_cb on the balanced joint.
nc::Vec6 kdlDriveTorques(const KDL::Chain& chain, const Robot& r, const nc::Vec6& q) {
  nc::Vec6 t = test::kdlGravity(chain, q);
  const Counterbalance& cb = r.card.counterbalance;
  if (cb.present()) t[cb.joint] -= balancerTorque(cb, q[cb.joint]);
  return t;
}

KDL::Chain kdlOf(const Robot& r) {
  return test::kdlChain(r.card.urdf_path, r.chain.base_link, r.chain.tip_link);
}

TEST(Counterbalance, ModelTorquesAreKdlGravityMinusTheBalancer) {
  // the balancer enters as a generalised force on the angle coordinate: staticTorques against
  // KDL RNE minus the law (5e-7 N m: KDL agrees to ~5e-12 N m with an independent kernel)
  for (const char* name : kRobots) {
    SCOPED_TRACE(name);
    const Robot r = loadRobot({name, "", ""});
    ASSERT_TRUE(r.card.counterbalance.present());
    const KDL::Chain kc = kdlOf(r);
    const nc::Model m = nc::buildModel(r.chain);
    nc::Data d(m);
    for (const nc::Vec6& q : {nc::Vec6(0.1, -0.5, 0.7, 0.2, 0.4, -0.3),
                              nc::Vec6(-0.4, 0.3, -0.2, 1.0, -0.6, 0.5), r.card.calibration_pose}) {
      nc::solvePosition(m, d, q);
      const nc::Vec6 tau = nc::staticTorques(m, d, nc::Loads{});
      const nc::Vec6 ref = kdlDriveTorques(kc, r, q);
      EXPECT_LT((tau - ref).cwiseAbs().maxCoeff(), 5e-7) << tau.transpose() << "\n"
                                                         << ref.transpose();
      // and nothing of it without gravity
      nc::Loads none;
      none.gravity = false;
      nc::solvePosition(m, d, q);
      EXPECT_LT(nc::staticTorques(m, d, none).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

TEST(Counterbalance, InverseDynamicsCarriesTheBalancerToo) {
  // the transient's path (inverseDynamics → generalizedForces): τ(q, q̇, q̈) against KDL RNE
  // with the same motion minus the balancer law (1e-6 N m)
  for (const char* name : kRobots) {
    SCOPED_TRACE(name);
    const Robot r = loadRobot({name, "", ""});
    const KDL::Chain kc = kdlOf(r);
    KDL::ChainIdSolver_RNE rne(kc, KDL::Vector(0, 0, -9.80665));
    const nc::Model m = nc::buildModel(r.chain);
    nc::Data d(m);
    const nc::Vec6 q(0.2, -0.4, 0.6, -0.3, 0.5, 0.1);
    const nc::Vec6 qd(0.3, -0.2, 0.4, 0.5, -0.6, 0.7);
    const nc::Vec6 qdd(-1.0, 0.8, 0.5, -0.4, 1.2, -0.9);
    nc::solvePosition(m, d, q);
    const nc::Vec6 tau = nc::inverseDynamics(m, d, qd, qdd, nc::Loads{});
    KDL::JntArray jq(6);
    KDL::JntArray jqd(6);
    KDL::JntArray jqdd(6);
    KDL::JntArray out(6);
    for (unsigned i = 0; i < 6; ++i) {
      jq(i) = q[i];
      jqd(i) = qd[i];
      jqdd(i) = qdd[i];
    }
    KDL::Wrenches f(kc.getNrOfSegments(), KDL::Wrench::Zero());
    rne.CartToJnt(jq, jqd, jqdd, f, out);
    nc::Vec6 ref;
    for (unsigned i = 0; i < 6; ++i) ref[i] = out(i);
    ref[1] -= balancerTorque(r.card.counterbalance, q[1]);
    EXPECT_LT((tau - ref).cwiseAbs().maxCoeff(), 1e-6) << (tau - ref).transpose();
  }
}

TEST(Counterbalance, BundledBalancersCarryTheStatedShareAtTheSizingPose) {
  // card rule: τ_cb(sizing pose) = sizing_fraction × τ_g,2 of the links (KDL), to the card's
  // rounding of preload/pressure (0.2 %)
  for (const char* name : kRobots) {
    SCOPED_TRACE(name);
    const Robot r = loadRobot({name, "", ""});
    const Counterbalance& cb = r.card.counterbalance;
    ASSERT_TRUE(cb.present());
    EXPECT_EQ(cb.joint, 1);
    EXPECT_EQ(cb.source.rfind("estimate:", 0), 0u);
    const nc::Vec6 q = r.card.balancer_sizing_pose;
    const double tau_g = test::kdlGravity(kdlOf(r), q)[1];
    const double share = balancerTorque(cb, q[1]) / tau_g;
    EXPECT_NEAR(share, r.card.balancer_sizing_fraction, 0.002 * r.card.balancer_sizing_fraction);
    EXPECT_NEAR(r.card.balancer_sizing_fraction, 0.70, 1e-12);
  }
}

// ---------------------------------------------------------------- the mastering reference

TEST(CalibrationReference, VendorDefaultsInTheControllerConvention) {
  const nc::Vec6 kuka = vendorCalibrationPoseDeg(Vendor::kKuka);
  EXPECT_EQ(kuka, (nc::Vec6() << 0, -90, 90, 0, 0, 0).finished());
  EXPECT_EQ(vendorCalibrationPoseDeg(Vendor::kAbb), nc::Vec6::Zero());
  EXPECT_EQ(vendorCalibrationPoseDeg(Vendor::kFanuc), nc::Vec6::Zero());
  // the bundled cards: URDF angles of the vendor pose (FANUC J3 from the horizontal: q3 = J3 + q2)
  for (const char* name : kRobots) {
    const Robot r = loadRobot({name, "", ""});
    const nc::Vec6 ctrl = toControllerJoints(r.card, r.card.calibration_pose) / kDeg;
    EXPECT_LT((ctrl - vendorCalibrationPoseDeg(r.card.vendor)).cwiseAbs().maxCoeff(), 1e-12)
        << name;
  }
}

TEST(CalibrationReference, NoSagAtTheCalibrationPose) {
  // deflect (robot alone, no tool, standard controller) at the mastering pose: |δ| ≤ 1e-9 m
  for (const char* name : kRobots) {
    SCOPED_TRACE(name);
    api::RobotSetupRequest req;
    req.robot = name;
    const api::RobotSetup s = api::loadRobotSetup(req);
    api::DeflectRequest dr;
    dr.joints = s.robot.card.calibration_pose;
    const api::DeflectResult res = api::deflectAt(s, dr);
    ASSERT_TRUE(res.deflection.converged);
    EXPECT_EQ(res.controller.kind, nc::ControllerReference::Kind::kMastering);
    EXPECT_LE(res.deflection.dp.norm(), 1e-9);
    EXPECT_LE(res.deflection.drot.norm(), 1e-9);
    // away from it the sag is not zero (the reference is not "no gravity")
    dr.joints[1] += 0.5;
    EXPECT_GT(api::deflectAt(s, dr).deflection.dp.norm(), 1e-5);
  }
}

TEST(CalibrationReference, JointDeflectionIsRelativeToTheMasteredState) {
  // θ − θ_cmd = K_eff⁻¹ (τ(θ_cal) − τ(θ)), with τ from KDL + the balancer law, solved by an
  // independent fixed point; the FK position from KDL: 1e-9 m
  for (const char* name : kRobots) {
    SCOPED_TRACE(name);
    api::RobotSetupRequest req;
    req.robot = name;
    const api::RobotSetup s = api::loadRobotSetup(req);
    const KDL::Chain kc = kdlOf(s.robot);
    nc::Vec6 k;
    for (int i = 0; i < 6; ++i) k[i] = s.robot.card.joints[static_cast<size_t>(i)].stiffness;
    const nc::Vec6 cmd(0.2, -0.35, 0.45, 0.3, -0.5, 0.1);
    const nc::Vec6 qcmd = cmd + s.robot.card.calibration_pose;
    const nc::Vec6 tau_cal = kdlDriveTorques(kc, s.robot, s.robot.card.calibration_pose);
    nc::Vec6 th = qcmd;
    for (int it = 0; it < 200; ++it)
      th = qcmd + (tau_cal - kdlDriveTorques(kc, s.robot, th)).cwiseQuotient(k);
    KDL::ChainFkSolverPos_recursive fk(kc);
    auto pos = [&](const nc::Vec6& q) {
      KDL::JntArray jq(6);
      for (unsigned i = 0; i < 6; ++i) jq(i) = q[i];
      KDL::Frame F;
      fk.JntToCart(jq, F);
      return Vec3(F.p.x(), F.p.y(), F.p.z());
    };
    api::DeflectRequest dr;
    dr.joints = qcmd;
    const api::DeflectResult res = api::deflectAt(s, dr);
    EXPECT_LT((res.deflection.theta - th).cwiseAbs().maxCoeff(), 1e-11);
    EXPECT_LT((res.deflection.dp - (pos(th) - pos(qcmd))).norm(), 1e-9);
  }
}

// ---------------------------------------------------------------- one handling for every command

struct CellFiles {
  std::string dir;
  std::string cell;
  std::string holes;
};

/// The KR 120 sample cell without a process (gravity and tool weight only), with the given
/// <controller>, and a one-hole list.
CellFiles gravityCell(const std::string& tag, const std::string& controller) {
  CellFiles f;
  f.dir = test::tempDir(tag);
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/housing-kr120.xml");
  cell = std::regex_replace(cell, std::regex("<process[\\s\\S]*</process>"), "");
  cell = std::regex_replace(cell, std::regex("<controller[^>]*/>"), controller);
  f.cell = f.dir + "/cell.xml";
  test::writeFile(f.cell, cell);
  const std::string holes = test::readFile(test::sourceDir() + "/samples/emotor-housing/holes.csv");
  std::istringstream in(holes);
  std::string head;  // comments and the column header
  std::string line;
  while (std::getline(in, line)) {
    head += line + "\n";
    if (line.rfind('#', 0) != 0) break;
  }
  std::string row;
  while (std::getline(in, line)) {
    if (line.rfind("T001,", 0) == 0) row = line;
  }
  f.holes = f.dir + "/holes.csv";
  test::writeFile(f.holes, head + row + "\n");
  return f;
}

std::vector<double> numbersAfter(const std::string& text, const std::string& key, size_t from = 0) {
  const size_t k = text.find("\"" + key + "\"", from);
  EXPECT_NE(k, std::string::npos) << key;
  if (k == std::string::npos) return {};
  const size_t open = text.find('[', k);
  const size_t close = text.find(']', open);
  std::istringstream in(text.substr(open + 1, close - open - 1));
  std::vector<double> v;
  std::string tok;
  while (std::getline(in, tok, ',')) v.push_back(std::stod(tok));
  return v;
}

TEST(GravityHandling, PredictDeflectAndSimulateAgree) {
  // the same cell, both controller settings: predict's δrobot, deflect's deviation and simulate's
  // static gravity_only_um at the hole's joints agree to the JSON rounding (0.002 µm)
  std::vector<double> sag_of;
  for (const std::string& controller :
       {std::string("<controller gravity_compensated=\"true\" calibration_load=\"tool\"/>"),
        std::string("<controller gravity_compensated=\"false\"/>")}) {
    SCOPED_TRACE(controller);
    const CellFiles f = gravityCell("gravity-cli", controller);
    const auto p = test::runRoprec("predict --cell '" + f.cell + "' '" + f.holes + "' --json '" +
                                   f.dir + "/p.json'");
    ASSERT_LE(p.exit_code, 1) << p.err;
    const std::string pj = test::readFile(f.dir + "/p.json");
    const std::vector<double> joints = numbersAfter(pj, "joints_deg");
    const std::vector<double> d_predict = numbersAfter(pj, "robot", pj.find("\"deviation_um\""));
    ASSERT_EQ(joints.size(), 6u);
    ASSERT_EQ(d_predict.size(), 3u);
    char js[200];
    std::snprintf(js, sizeof js, "%.6f %.6f %.6f %.6f %.6f %.6f", joints[0], joints[1], joints[2],
                  joints[3], joints[4], joints[5]);
    const auto d = test::runRoprec("deflect --cell '" + f.cell + "' --joints \"" + js + "\"");
    ASSERT_EQ(d.exit_code, 0) << d.err;
    const std::vector<double> d_deflect = numbersAfter(d.out, "translation_um");
    const auto s = test::runRoprec("simulate --cell '" + f.cell + "' --hole T001 '" + f.holes +
                                   "' -o /dev/null --summary '" + f.dir + "/s.json'");
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string sj = test::readFile(f.dir + "/s.json");
    const std::vector<double> d_sim = numbersAfter(sj, "gravity_only_um");
    ASSERT_EQ(d_deflect.size(), 3u);
    ASSERT_EQ(d_sim.size(), 3u);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(d_deflect[static_cast<size_t>(i)], d_predict[static_cast<size_t>(i)], 0.002);
      EXPECT_NEAR(d_sim[static_cast<size_t>(i)], d_predict[static_cast<size_t>(i)], 0.002);
    }
    const bool compensated = controller.find("true") != std::string::npos;
    EXPECT_EQ(d.out.find("\"gravity_compensated_by_controller\": true") != std::string::npos,
              compensated);
    EXPECT_NE(sj.find(compensated ? "absolute-accuracy option" : "mastering reference"),
              std::string::npos);
    sag_of.push_back(std::hypot(d_predict[0], d_predict[1], d_predict[2]));
  }
  // the two settings are different predictions (the tool's weight is compensated only with the
  // option)
  ASSERT_EQ(sag_of.size(), 2u);
  EXPECT_GT(std::abs(sag_of[0] - sag_of[1]), 1.0);
}

// ---------------------------------------------------------------- card weight elements

struct CardCopy {
  std::string dir;
  std::string card;
  std::string urdf;
};

/// A copy of the KR 120 card and URDF; `edit_urdf` and `extra` (elements before </robot>) change
/// them.
CardCopy cardCopy(const std::string& tag, const std::function<std::string(std::string)>& edit_urdf,
                  const std::string& extra) {
  CardCopy c;
  c.dir = test::tempDir(tag);
  const std::string src = test::sourceDir() + "/robots/kuka-kr120-r2500-pro/";
  c.urdf = c.dir + "/kr120r2500pro.urdf";
  test::writeFile(c.urdf, edit_urdf(test::readFile(src + "kr120r2500pro.urdf")));
  std::string card = test::readFile(src + "robot.xml");
  card.replace(card.rfind("</robot>"), 8, extra + "\n</robot>");
  c.card = c.dir + "/robot.xml";
  test::writeFile(c.card, card);
  return c;
}

std::string withoutLink3Inertial(std::string urdf) {
  return std::regex_replace(
      urdf, std::regex("(<link name=\"link_3\">)\\s*<inertial>[\\s\\S]*?</inertial>"), "$1");
}

int lineOf(const std::string& text, const std::string& what) {
  const size_t at = text.find(what);
  return at == std::string::npos
             ? -1
             : 1 + static_cast<int>(
                       std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

TEST(CardWeight, MissingInertialIsRefusedWithFileLineAndHint) {
  const CardCopy c = cardCopy("gravity-noinertial", withoutLink3Inertial, "");
  const auto r = test::runRoprec("deflect --robot '" + c.card + "' --joints \"0 -60 100 0 50 0\"");
  EXPECT_EQ(r.exit_code, 2);
  const int line = lineOf(test::readFile(c.urdf), "<link name=\"link_3\">");
  EXPECT_NE(r.err.find("kr120r2500pro.urdf:" + std::to_string(line) + ": link 'link_3'"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("hint"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("<gravity model=\"none\""), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  // without gravity the weight is not needed
  const auto ng = test::runRoprec("deflect --robot '" + c.card +
                                  "' --joints \"0 -60 100 0 50 0\" --no-gravity --wrench \"0 0 "
                                  "500 0 0 0\"");
  EXPECT_EQ(ng.exit_code, 0) << ng.err;
}

TEST(CardWeight, GravityModelNoneIsAcceptedAndStatedEverywhere) {
  const CardCopy c = cardCopy("gravity-none", withoutLink3Inertial,
                              "  <gravity model=\"none\" source=\"test: masses unknown\"/>");
  const auto r = test::runRoprec("deflect --robot '" + c.card + "' --joints \"0 -60 100 0 50 0\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("gravity is not modelled"), std::string::npos);
  EXPECT_NEAR(numbersAfter(r.out, "translation_um")[2], 0.0, 1e-9);  // no weight, no wrench
  // predict and simulate with a cell on this card
  std::string cell = test::readFile(test::sourceDir() + "/samples/cells/housing-kr120.xml");
  cell = std::regex_replace(cell, std::regex("<robot ref=\"[^\"]*\"/>"),
                            "<robot file=\"" + c.card + "\"/>");
  test::writeFile(c.dir + "/cell.xml", cell);
  const auto p =
      test::runRoprec("predict --cell '" + c.dir + "/cell.xml' '" + test::sourceDir() +
                      "/samples/emotor-housing/holes.csv' --json '" + c.dir + "/p.json'");
  ASSERT_LE(p.exit_code, 1) << p.err;
  const std::string pj = test::readFile(c.dir + "/p.json");
  EXPECT_NE(pj.find("gravity is not modelled"), std::string::npos);
  const auto s = test::runRoprec("simulate --cell '" + c.dir + "/cell.xml' --hole T001 '" +
                                 test::sourceDir() + "/samples/emotor-housing/holes.csv' -o " +
                                 "/dev/null --summary '" + c.dir + "/s.json'");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string sj = test::readFile(c.dir + "/s.json");
  EXPECT_NE(sj.find("gravity is not modelled"), std::string::npos);
  const std::vector<double> g = numbersAfter(sj, "gravity_only_um");
  for (const double v : g) EXPECT_EQ(v, 0.0);
}

TEST(CardWeight, LinkOverrideChangesTheGravityTorqueAsKdlSays) {
  // <link name="link_3" mass_kg="300" com_mm="400 0 -50"> against KDL on a URDF with that
  // inertial (inertia as in the URDF: static torques do not depend on it): 5e-7 N m
  const std::string extra =
      "  <link name=\"link_3\" mass_kg=\"300\" com_mm=\"400 0 -50\" source=\"test\"/>";
  const CardCopy c = cardCopy("gravity-override", withoutLink3Inertial, extra);
  const Robot r = loadRobot({c.card, "", ""});
  EXPECT_NO_THROW(requireGravityModel(r));
  EXPECT_DOUBLE_EQ(r.chain.inertials[2].mass, 300.0);
  const std::string urdf_ref = std::regex_replace(
      test::readFile(test::sourceDir() + "/robots/kuka-kr120-r2500-pro/kr120r2500pro.urdf"),
      std::regex("(<link name=\"link_3\">\\s*<inertial>\\s*)<origin[^>]*/>\\s*<mass[^>]*/>"),
      "$1<origin xyz=\"0.4 0 -0.05\" rpy=\"0 0 0\"/><mass value=\"300\"/>");
  const std::string ref_path = c.dir + "/reference.urdf";
  test::writeFile(ref_path, urdf_ref);
  const KDL::Chain kc = test::kdlChain(ref_path, r.chain.base_link, r.chain.tip_link);
  const nc::Model m = nc::buildModel(r.chain);
  nc::Data d(m);
  const Robot bundled = loadRobot({"kuka-kr120-r2500-pro", "", ""});
  const nc::Model mb = nc::buildModel(bundled.chain);
  nc::Data db(mb);
  for (const nc::Vec6& q :
       {nc::Vec6(0.1, -0.5, 0.7, 0.2, 0.4, -0.3), nc::Vec6(-0.4, 0.3, -0.2, 1.0, -0.6, 0.5)}) {
    nc::solvePosition(m, d, q);
    const nc::Vec6 tau = nc::staticTorques(m, d, nc::Loads{});
    EXPECT_LT((tau - kdlDriveTorques(kc, r, q)).cwiseAbs().maxCoeff(), 5e-7);
    nc::solvePosition(mb, db, q);
    EXPECT_GT(std::abs(tau[1] - nc::staticTorques(mb, db, nc::Loads{})[1]), 10.0);  // it changed
  }
}

TEST(CardWeight, UnknownAttributesAndBadElementsAreErrors) {
  const struct {
    std::string extra;
    std::string expect;
  } cases[] = {
      {"  <link name=\"link_3\" mass_kg=\"30\" com_mm=\"0 0 0\" source=\"x\" colour=\"red\"/>",
       "unknown attribute 'colour' on <link>"},
      {"  <link name=\"link_3\" mass_kg=\"30\" com_mm=\"0 0 0\"/>", "needs a source"},
      {"  <link name=\"flange\" mass_kg=\"30\" com_mm=\"0 0 0\" source=\"x\"/>",
       "is not a moving body"},
      {"  <gravity model=\"off\"/>", "model must be"},
      {"  <gravity model=\"none\" reason=\"x\"/>", "unknown attribute 'reason' on <gravity>"},
  };
  for (const auto& k : cases) {
    const CardCopy c = cardCopy(
        "gravity-bad", [](std::string u) { return u; }, k.extra);
    try {
      loadRobot({c.card, "", ""});
      ADD_FAILURE() << "accepted: " << k.extra;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(k.expect), std::string::npos) << e.what();
      EXPECT_EQ(e.line(), lineOf(test::readFile(c.card), k.extra.substr(2, 12))) << e.what();
    }
  }
  // a misspelt balancer parameter
  const CardCopy c = cardCopy(
      "gravity-bad-cb", [](std::string u) { return u; }, "");
  std::string card = test::readFile(c.card);
  card = std::regex_replace(card, std::regex("gas_volume_l="), "gas_volume_litres=");
  test::writeFile(c.card, card);
  try {
    loadRobot({c.card, "", ""});
    ADD_FAILURE() << "accepted a misspelt balancer attribute";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gas_volume_litres"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roprec
