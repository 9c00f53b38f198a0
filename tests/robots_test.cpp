/// The bundled robots (robots/<name>/): each card loads, its joints match the URDF chain, the
/// joint limits are the datasheet ranges, the link masses add up to the datasheet mass, every
/// number has a source and estimates say so, and the flange frame is each vendor's tool-0 frame.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "compensator/robot/chain.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/xml_node.hpp"
#include "tests/support/card_expect.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Datasheet values, each with its source (also cited in the cards and robots/README.md).
struct Datasheet {
  const char* name;
  const char* vendor;
  std::array<const char*, 6> joints;
  std::array<double, 6> lower_deg;
  std::array<double, 6> upper_deg;
  double mass_kg;
  double payload_kg;
  double rp_mm;
  double j23_coupling;
  const char* base_link;
};

const std::array<Datasheet, 3> kRobots{{
    // KUKA KR QUANTEC pro specification / KR 120 R2500 pro datasheet: axis ranges, approx. 1049 kg,
    // 120 kg rated payload, pose repeatability +-0.06 mm (ISO 9283).
    {"kuka-kr120-r2500-pro",
     "KUKA",
     {"joint_a1", "joint_a2", "joint_a3", "joint_a4", "joint_a5", "joint_a6"},
     {-185, -155, -130, -350, -130, -350},
     {185, 35, 154, 350, 130, 350},
     1049,
     120,
     0.06,
     0,
     "base_link"},
    // ABB IRB 6640 product specification / data sheet, variant 185/2.8: working ranges, 1310 kg,
    // 185 kg, RP 0.07 mm.
    {"abb-irb6640-185-280",
     "ABB",
     {"joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6"},
     {-170, -65, -180, -300, -120, -360},
     {170, 85, 70, 300, 120, 360},
     1310,
     185,
     0.07,
     0,
     "base_link"},
    // FANUC R-2000iC/165F data sheet: motion ranges, 1090 kg, 165 kg, repeatability +-0.05 mm.
    {"fanuc-r2000ic-165f",
     "FANUC",
     {"joint_1", "joint_2", "joint_3", "joint_4", "joint_5", "joint_6"},
     {-185, -60, -132, -360, -125, -360},
     {185, 76, 180, 360, 125, 360},
     1090,
     165,
     0.05,
     -1,
     "base"},
}};

bool startsWith(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

TEST(Robots, AllThreeAreBundled) {
  const std::vector<std::string> names = bundledRobotNames();
  for (const Datasheet& d : kRobots) {
    EXPECT_NE(std::find(names.begin(), names.end(), d.name), names.end()) << d.name;
  }
}

TEST(Robots, CardsLoadAndMatchTheDatasheet) {
  for (const Datasheet& d : kRobots) {
    SCOPED_TRACE(d.name);
    const Robot r = loadRobot({d.name, "", ""});
    const RobotCard& c = r.card;
    test::expectDatasheetHeader(
        c, {d.name, d.vendor, d.base_link, d.payload_kg, d.rp_mm, d.j23_coupling});
    EXPECT_TRUE(startsWith(c.inertial_source, "estimate:")) << c.inertial_source;
    EXPECT_TRUE(c.has_stiffness);
    for (size_t i = 0; i < 6; ++i) {
      const JointCard& j = c.joints[i];
      const ChainJoint& cj = r.chain.joints[i];
      EXPECT_EQ(j.name, d.joints[i]);
      EXPECT_EQ(cj.name, d.joints[i]);
      EXPECT_NEAR(cj.lower / kDeg, d.lower_deg[i], 1e-9) << j.name;
      EXPECT_NEAR(cj.upper / kDeg, d.upper_deg[i], 1e-9) << j.name;
      EXPECT_GT(j.stiffness, 0.0);
      ASSERT_TRUE(j.position_gain.has_value());
      EXPECT_GT(*j.position_gain, 0.0);
      EXPECT_FALSE(j.source.empty());
      // Every joint stiffness here is derived from another robot's identification: an estimate.
      EXPECT_TRUE(startsWith(j.source, "estimate:")) << j.source;
      EXPECT_TRUE(j.estimated());
      // URDF angles equal the controller's apart from FANUC's J2/J3 coupling.
      EXPECT_EQ(j.controller_sign, 1.0);
      EXPECT_EQ(j.controller_offset, 0.0);
    }
    // Published-identification ordering kept by the scaling: main axes stiffer than the wrist.
    EXPECT_GT(std::min({c.joints[0].stiffness, c.joints[1].stiffness, c.joints[2].stiffness}),
              std::max({c.joints[3].stiffness, c.joints[4].stiffness, c.joints[5].stiffness}));
  }
}

TEST(Robots, LinkMassesAddUpToTheDatasheetMass) {
  for (const Datasheet& d : kRobots) {
    SCOPED_TRACE(d.name);
    const Robot r = loadRobot({d.name, "", ""});
    // Sum of every <link><inertial><mass> in the URDF, read independently of the loader.
    const XmlNode urdf = loadXmlFile(r.card.urdf_path);
    double total = 0;
    double base = 0;
    for (const XmlNode* link : urdf.childrenNamed("link")) {
      if (const XmlNode* in = link->child("inertial")) {
        const double m = in->child("mass")->number("value");
        total += m;
        if (link->str("name") == "base_link") base = m;
      }
    }
    // The split is an estimate; the total is the datasheet's (rounding of the parts: 0.1 kg).
    EXPECT_NEAR(total, d.mass_kg, 0.05);
    // The loader's bodies carry everything but the fixed base.
    EXPECT_TRUE(r.chain.has_inertials);
    double moving = 0;
    for (const Inertial& in : r.chain.inertials) {
      EXPECT_TRUE(in.present);
      EXPECT_GT(in.mass, 0.0);
      EXPECT_GT(in.inertia.trace(), 0.0);
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat3>(in.inertia).eigenvalues().minCoeff(), 0.0);
      moving += in.mass;
    }
    EXPECT_NEAR(moving + base, d.mass_kg, 0.05);
  }
}

TEST(Robots, WeightHandlingOfTheCards) {
  // every bundled robot has an axis-2 balancer (the real ones do: KUKA hydropneumatic, ABB and
  // FANUC springs), marked as an estimate with its sizing rule, physical over the whole A2
  // range, and the vendor's mastering pose; gravity is modelled
  for (const Datasheet& d : kRobots) {
    SCOPED_TRACE(d.name);
    const Robot r = loadRobot({d.name, "", ""});
    const Counterbalance& cb = r.card.counterbalance;
    ASSERT_TRUE(cb.present());
    EXPECT_EQ(cb.joint, 1);
    EXPECT_EQ(cb.source.rfind("estimate: rule:", 0), 0u) << cb.source;
    EXPECT_EQ(cb.law, r.card.vendor == Vendor::kKuka ? Counterbalance::Law::kGas
                                                     : Counterbalance::Law::kSpring);
    const ChainJoint& j2 = r.chain.joints[1];
    EXPECT_EQ(balancerProblem(cb, j2.lower, j2.upper), "");
    // the balancer helps the drive: τ_cb has the sign of the holding torque at the sizing pose
    // and vanishes where it is in line with the pivot (ψ = 0)
    EXPECT_NEAR(balancerTorque(cb, -cb.psi0 / cb.sign), 0.0, 1e-9);
    EXPECT_TRUE(r.card.gravity_modelled);
    EXPECT_TRUE(r.chain.gravity_modelled);
    EXPECT_FALSE(r.card.calibration_pose_source.empty());
    EXPECT_EQ(toControllerJoints(r.card, r.card.calibration_pose) / kDeg,
              vendorCalibrationPoseDeg(r.card.vendor));
  }
}

Mat3 rotY(double a) { return Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix(); }

// Each vendor's tool-0 frame at its reference pose (robots/README.md):
//   KUKA HOME {0,-90,90,0,0,0}: flange A 0, B 90, C 0 = Ry(90 deg).
//   ABB all-zero: tool0 quaternion [0.70711, 0, 0.70711, 0] = Ry(90 deg).
//   FANUC all-zero: faceplate W 180, P -90, R 0 = Rz(0) Ry(-90) Rx(180).
TEST(Robots, FlangeIsTheVendorsToolZeroFrame) {
  const Mat3 fanuc = rotY(-kPi / 2) * Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix();
  const std::array<std::pair<Vec6, Mat3>, 3> ref{{
      {(Vec6() << 0, -90, 90, 0, 0, 0).finished() * kDeg, rotY(kPi / 2)},
      {Vec6::Zero(), rotY(kPi / 2)},
      {Vec6::Zero(), fanuc},
  }};
  // Flange positions at those poses from the published dimensions (mm):
  //   KUKA at HOME (link arm vertical, arm horizontal): (350 + 1000 + 215, 0, 675 + 1150 - 41).
  //   ABB: (320 + 1392 + 200, 0, 780 + 1075 + 200).  FANUC (World, J2 height): (312 + 1280 + 215,
  //   0, 1075 + 225).
  const std::array<Vec3, 3> pos{{Vec3(1565, 0, 1784), Vec3(1912, 0, 2055), Vec3(1807, 0, 1300)}};
  for (size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(kRobots[k].name);
    const Robot r = loadRobot({kRobots[k].name, "", ""});
    const Pose T = chainForwardKinematics(r.chain, ref[k].first);
    EXPECT_LT((T.linear() - ref[k].second).norm(), 1e-12);
    EXPECT_LT((T.translation() * 1e3 - pos[k]).norm(), 1e-9);
  }
}

TEST(Robots, FlangeZPointsOutOfTheFlangeAndTool0IsTheSameFrame) {
  std::mt19937 rng(17);
  for (const Datasheet& d : kRobots) {
    SCOPED_TRACE(d.name);
    const Robot r = loadRobot({d.name, "", ""});
    const ChainDescription t0 = loadUrdfChain(r.card.urdf_path, {r.card.base_link, "tool0"});
    // The wrist centre: origin of joint 5's frame (all three have a spherical wrist).
    for (int k = 0; k < 50; ++k) {
      Vec6 q;
      for (int i = 0; i < 6; ++i) {
        const ChainJoint& j = r.chain.joints[static_cast<size_t>(i)];
        q[i] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
      }
      const Pose F = chainForwardKinematics(r.chain, q);
      const Pose T0 = chainForwardKinematics(t0, q);
      EXPECT_LT((F.matrix() - T0.matrix()).norm(), 1e-15);
      Pose W = Pose::Identity();
      for (int i = 0; i < 5; ++i) {
        const ChainJoint& j = r.chain.joints[static_cast<size_t>(i)];
        W = W * j.origin;
        if (i < 4) W.rotate(Eigen::AngleAxisd(q[i], j.axis));
      }
      const Vec3 out = F.translation() - W.translation();
      EXPECT_GT(out.norm(), 0.19);
      EXPECT_LT((out.normalized() - F.linear().col(2)).norm(), 1e-12)
          << "flange z must point out of the flange";
    }
  }
}

// End to end through the CLI: `roprec fk --robot NAME` at each vendor's reference pose prints the
// flange pose computed above from the published dimensions (contract: position_mm,
// quaternion_wxyz).
TEST(Robots, CliFkPrintsTheVendorsFlangePose) {
  struct Case {
    const char* name;
    const char* joints;
    Vec3 position_mm;
    Eigen::Quaterniond q;
  };
  const double s = std::sqrt(0.5);
  const std::array<Case, 3> cases{{
      {"kuka-kr120-r2500-pro", "0 -90 90 0 0 0", Vec3(1565, 0, 1784),
       Eigen::Quaterniond(s, 0, s, 0)},
      {"abb-irb6640-185-280", "0 0 0 0 0 0", Vec3(1912, 0, 2055), Eigen::Quaterniond(s, 0, s, 0)},
      // W 180, P -90, R 0 = Ry(-90) Rx(180): quaternion (0, s, 0, s) up to sign.
      {"fanuc-r2000ic-165f", "0 0 0 0 0 0", Vec3(1807, 0, 1300), Eigen::Quaterniond(0, s, 0, s)},
  }};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const test::RunResult r =
        test::runRoprec(std::string("fk --robot ") + c.name + " --joints \"" + c.joints + "\"");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const auto& f = j.at("flange");
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(f.at("position_mm")[static_cast<size_t>(i)].get<double>(), c.position_mm[i],
                  1e-6);
    const Eigen::Quaterniond got(
        f.at("quaternion_wxyz")[0].get<double>(), f.at("quaternion_wxyz")[1].get<double>(),
        f.at("quaternion_wxyz")[2].get<double>(), f.at("quaternion_wxyz")[3].get<double>());
    EXPECT_NEAR(std::abs(got.dot(c.q)), 1.0, 1e-8);
  }
}

}  // namespace
}  // namespace roprec
