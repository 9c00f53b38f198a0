// `roprec card new` / `roprec card check` end to end (docs/cards.md), and the bare-URDF cell error.
//  * card new on every ROS-Industrial URDF of the corpus gives a card that card check accepts,
//    whose flange pose equals Orocos KDL's (kdl_parser on the same URDF, root -> chosen flange
//    link) at seeded random joint vectors (<= 1e-9 m, 1e-9 rad), with the FANUC base at J2 height
//    (KDL's link_2 origin), the flange orientation at the vendor's home written out literally
//    (KUKA/ABB: z = +x_B, x = -z_B; FANUC: z = +x_B, x = +z_B) and no placeholder mass kept;
//  * card check flags an x-out flange, placeholder inertials, a stiffness 100x off the class and
//    a missing repeatability (exit 2, FILE:LINE), and passes the bundled robots and samples
//    without a single warning.
#include <gtest/gtest.h>

#include <filesystem>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <random>
#include <regex>

#include "compensator/robot/model.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_writer.hpp"
#include "plugin/api/card_tools.hpp"
#include "tests/support/kdl_support.hpp"
#include "tests/support/test_support.hpp"

namespace fs = std::filesystem;

namespace roprec {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using test::readFile;
using test::runRoprec;
using test::writeFile;

std::string q(const std::string& s) { return "'" + s + "'"; }

/// The rated payload the URDF robot name does not tell (ABB IRB 2400/16: 16 kg, data sheet).
std::string payloadOption(const std::string& file) {
  return file == "irb2400.urdf" ? " --payload-kg 16" : "";
}

/// A card made by card new for the corpus URDF `name`, in a fresh folder; "" when skipped.
std::string newCard(const std::string& urdf, const std::string& extra = "") {
  const std::string dir = test::tempDir("card");
  const std::string card = dir + "/robot.xml";
  const auto r = runRoprec("card new --urdf " + q(urdf) + extra + " -o " + q(card));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("still to confirm"), std::string::npos) << r.err;
  return card;
}

std::vector<std::string> corpusUrdfs() {
  std::vector<std::string> out;
  const std::string corpus = test::corpusDir();
  if (corpus.empty()) return out;
  for (const auto& e : fs::directory_iterator(corpus + "/urdf"))
    if (e.path().extension() == ".urdf") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

Pose kdlFk(const KDL::Chain& chain, const Vec6& qv) {
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::JntArray kq(chain.getNrOfJoints());
  for (unsigned i = 0; i < chain.getNrOfJoints(); ++i) kq(i) = qv[static_cast<int>(i)];
  KDL::Frame F;
  fk.JntToCart(kq, F);
  return test::fromKdl(F);
}

TEST(CardNew, EveryCorpusUrdfGivesACheckedCardWithTheUrdfKinematics) {
  const std::vector<std::string> urdfs = corpusUrdfs();
  if (urdfs.empty()) GTEST_SKIP() << "no corpus";
  ASSERT_GE(urdfs.size(), 6u);
  std::mt19937 rng(16);
  for (const std::string& urdf : urdfs) {
    const std::string file = fs::path(urdf).filename().string();
    SCOPED_TRACE(file);
    const std::string card = newCard(urdf, payloadOption(file));
    const auto chk = runRoprec("card check " + q(card));
    EXPECT_EQ(chk.exit_code, 0) << chk.out << chk.err;
    EXPECT_EQ(chk.err.find("error"), std::string::npos) << chk.err;
    const std::string text = readFile(card);
    // the URDF by a path relative to the card's folder
    EXPECT_EQ(text.find("urdf=\"/"), std::string::npos);
    const Robot robot = loadRobot({card, "", ""});
    const RobotCard& c = robot.card;
    EXPECT_TRUE(c.has_stiffness);
    EXPECT_EQ(c.flange_link, "tool0");  // the ROS-Industrial z-out frame, never their x-out flange
    // every number sourced, estimates marked
    for (const JointCard& j : c.joints) EXPECT_EQ(j.source.rfind("estimate:", 0), 0u) << j.name;
    EXPECT_EQ(c.rp_source.rfind("estimate:", 0), 0u);

    // FK of the card (production natural-coordinate model) against KDL from the URDF root
    const KDL::Chain kchain = test::kdlChain(urdf, "base_link", c.flange_link);
    ASSERT_EQ(kchain.getNrOfJoints(), 6u);
    Pose T_root_base = Pose::Identity();
    if (c.vendor == Vendor::kFanuc) {
      // FANUC World: on the J1 axis at J2 height, i.e. at KDL's link_2 origin height at zero
      const Pose T_l2 = kdlFk(test::kdlChain(urdf, "base_link", "link_2"), Vec6::Zero());
      EXPECT_GT(T_l2.translation().z(), 0.3);
      T_root_base.translation() = Vec3(0, 0, T_l2.translation().z());
      EXPECT_EQ(c.base_link, "base");
      EXPECT_DOUBLE_EQ(c.j23_coupling, -1.0);
    } else {
      EXPECT_EQ(c.base_link, "base_link");
      EXPECT_DOUBLE_EQ(c.j23_coupling, 0.0);
    }
    const nc::Model model = nc::buildModel(robot.chain);
    nc::Data data(model);
    for (int s = 0; s < 5; ++s) {
      Vec6 qv;
      for (int i = 0; i < 6; ++i) {
        const ChainJoint& j = robot.chain.joints[static_cast<size_t>(i)];
        qv[i] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
      }
      nc::forwardKinematics(model, data, qv);
      const Pose ref = T_root_base.inverse() * kdlFk(kchain, qv);
      EXPECT_LE((data.T_W_flange.translation() - ref.translation()).norm(), 1e-9);
      EXPECT_LE((data.T_W_flange.linear() - ref.linear()).norm(), 1e-9);
    }
    // the vendor's home: KUKA {0,-90,90,0,0,0}, ABB and FANUC all 0 (controller convention)
    Vec6 home_deg = Vec6::Zero();
    Vec3 x_expected(0, 0, -1);
    if (c.vendor == Vendor::kKuka) home_deg << 0, -90, 90, 0, 0, 0;
    if (c.vendor == Vendor::kFanuc) x_expected = Vec3(0, 0, 1);
    const Pose home = kdlFk(kchain, fromControllerJoints(c, home_deg * kDeg));
    EXPECT_NEAR(home.linear().col(2).dot(Vec3::UnitX()), 1.0, 1e-9);
    EXPECT_NEAR(home.linear().col(0).dot(x_expected), 1.0, 1e-9);
    // KUKA: A1, A4, A6 clockwise-positive; the ROS-Industrial URDF already turns about -z/-x
    for (const JointCard& j : c.joints) EXPECT_EQ(j.controller_sign, 1.0) << j.name;

    // no placeholder inertial kept as real: every moving body has a mass, none the ROS-I 2 kg
    const bool placeholders = readFile(urdf).find("<mass value=\"2\"/>") != std::string::npos;
    for (size_t i = 0; i < 6; ++i) {
      const Inertial& in = robot.chain.inertials[i];
      EXPECT_GT(in.mass, 0.0);
      if (placeholders) {
        EXPECT_NE(in.mass, 2.0);
        EXPECT_GT((in.inertia - 0.01 * Mat3::Identity()).norm(), 1e-6);
      }
    }
    EXPECT_EQ(c.links.size(), 6u);  // the corpus URDFs carry no real inertials
  }
}

TEST(CardNew, AsksForWhatTheUrdfDoesNotTell) {
  const std::vector<std::string> urdfs = corpusUrdfs();
  if (urdfs.empty()) GTEST_SKIP() << "no corpus";
  const std::string dir = test::tempDir("card");
  const std::string irb2400 = test::corpusDir() + "/urdf/irb2400.urdf";
  auto r = runRoprec("card new --urdf " + q(irb2400) + " -o " + q(dir + "/robot.xml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--payload-kg"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/robot.xml"));
  // a wrong vendor: the KUKA zero pose (link arm horizontal) is not the ABB one (vertical)
  const std::string kr16 = test::corpusDir() + "/urdf/kr16_2.urdf";
  r = runRoprec("card new --urdf " + q(kr16) + " --vendor ABB --payload-kg 16 -o " +
                q(dir + "/robot.xml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("kr16_2.urdf:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the lower arm (joint_a2 -> joint_a3)"), std::string::npos) << r.err;
}

/// kr16_2 card with `from` replaced by `to` (regex), checked.
test::RunResult checkEdited(const std::string& from, const std::string& to) {
  const std::string card = newCard(test::corpusDir() + "/urdf/kr16_2.urdf");
  const std::string text = readFile(card);
  const std::string edited = std::regex_replace(text, std::regex(from), to);
  EXPECT_NE(edited, text) << "pattern " << from << " not found";
  writeFile(card, edited);
  return runRoprec("card check " + q(card));
}

bool hasLocatedError(const std::string& err, const std::string& what) {
  return std::regex_search(err, std::regex("robot\\.xml:[0-9]+: error: [^\n]*" + what));
}

TEST(CardCheck, FlagsAFlangeThatIsNotZOut) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  // ROS-Industrial's KUKA `flange` is x-out (REP 199)
  const auto r = checkEdited("flange_link=\"tool0\"", "flange_link=\"flange\"");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(hasLocatedError(r.err, "does not have z out of the flange")) << r.err;
  EXPECT_NE(r.err.find("use flange_link=\"tool0\""), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("ERROR"), std::string::npos) << r.out;
}

TEST(CardCheck, FlagsPlaceholderInertials) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  const auto r = checkEdited("  <link [^>]*/>\n", "");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(hasLocatedError(r.err, "placeholder inertial")) << r.err;
}

TEST(CardCheck, FlagsAStiffnessOffTheClass) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  // KR 16: class k2 = 6.12e6 x 16/120 = 8.16e5 N m/rad; 100x too high is an error ...
  auto r = checkEdited("(joint_a2\" stiffness=\")[^\"]*", "$018.16e7");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(hasLocatedError(r.err, "joint_a2'?: stiffness 8.16e7 N m/rad is 100x above"))
      << r.err;
  // ... a N mm/rad slip (1000x) as well, and 20x off only a warning
  r = checkEdited("(joint_a5\" stiffness=\")[^\"]*", "$012.92e7");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = checkEdited("(joint_a2\" stiffness=\")[^\"]*", "$014.08e4");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: joint 'joint_a2': stiffness 4.08e4"), std::string::npos) << r.err;
}

TEST(CardCheck, FlagsAMissingRepeatability) {
  if (test::corpusDir().empty()) GTEST_SKIP() << "no corpus";
  const auto r = checkEdited("  <repeatability [^>]*/>\n", "");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex("robot\\.xml:[0-9]+: [^\n]*repeatability")))
      << r.err;
}

TEST(CardCheck, BundledRobotsAndSamplesPassWithoutWarnings) {
  ASSERT_FALSE(bundledRobotNames().empty());
  std::vector<std::string> cards;
  for (const std::string& n : bundledRobotNames())
    cards.push_back(bundledRobotsDir() + "/" + n + "/robot.xml");
  cards.push_back(test::sourceDir() + "/samples/verification/truth-kr120.xml");
  cards.push_back(test::sourceDir() + "/samples/verification/kr120-calibrated.xml");
  for (const std::string& card : cards) {
    SCOPED_TRACE(card);
    const auto r = runRoprec("card check " + q(card));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("0 error(s), 0 warning(s)"), std::string::npos) << r.out;
  }
  for (const auto& e : fs::directory_iterator(test::sourceDir() + "/samples/cells")) {
    SCOPED_TRACE(e.path().string());
    const auto r = runRoprec("card check --cell " + q(e.path().string()));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(r.err, "");
  }
}

TEST(CellRobot, BareUrdfSaysHowToMakeACard) {
  const std::string dir = test::tempDir("bare");
  const std::string urdf = bundledRobotsDir() + "/kuka-kr120-r2500-pro/kr120r2500pro.urdf";
  writeFile(dir + "/cell.xml", "<?xml version=\"1.0\"?>\n<cell name=\"bare\">\n  <robot urdf=\"" +
                                   urdf + "\"/>\n</cell>\n");
  for (const std::string cmd : {"fk --joints '0 -90 90 0 0 0' --cell ", "card check --cell "}) {
    const auto r = runRoprec(cmd + q(dir + "/cell.xml"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(dir + "/cell.xml:3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("make a card with `roprec card new --urdf " + urdf +
                         " ... -o robot.xml` and reference it"),
              std::string::npos)
        << r.err;
  }
}

// ---- calibration interop (docs/cards.md §5): import, export, check

/// A copy of the bundled card `robot` in a fresh folder with `cal` as its <calibration>.
std::string calibratedCardCopy(const std::string& robot, const GeometryCalibration& cal,
                               const std::string& tag) {
  const Robot r = loadRobot({robot, "", ""});
  std::array<std::string, 6> names;
  for (size_t i = 0; i < 6; ++i) names[i] = r.card.joints[i].name;
  return test::cardWithCalibration(r, calibrationXml(cal, names), test::tempDir(tag));
}

// `roprec fk` of a calibrated card is the real robot's FK: KDL on the perturbed URDF (base error
// in front, tool error appended) within 1e-6 mm, and ≈ 1 mm from the nominal card's.
TEST(CardCalibration, FkOfACalibratedCardIsTheKdlFkOfItsTruth) {
  for (const char* robot : {"kuka-kr120-r2500-pro", "abb-irb6640-185-280", "fanuc-r2000ic-210f"}) {
    SCOPED_TRACE(robot);
    const GeometryCalibration cal = test::seededGeometryErrors(23, 0.4, 0.6);
    const std::string card = calibratedCardCopy(robot, cal, std::string("cardfk-") + robot);
    const Robot r = loadRobot({robot, "", ""});
    const KDL::Chain chain = test::kdlTruthGeometry(r, cal, fs::path(card).parent_path().string())
                                 .chain(r.chain.base_link, r.chain.tip_link);
    KDL::ChainFkSolverPos_recursive solver(chain);
    const Vec6 q_deg = (Vec6() << 10, -80, 95, 20, 40, -30).finished();
    KDL::JntArray jq(6);
    for (unsigned i = 0; i < 6; ++i) jq(i) = q_deg[i] * kDeg;
    KDL::Frame F;
    ASSERT_GE(solver.JntToCart(jq, F), 0);
    const auto fkOf = [&](const std::string& robot_arg) {
      const auto o = runRoprec("fk --robot " + q(robot_arg) + " --joints '10 -80 95 20 40 -30'");
      EXPECT_EQ(o.exit_code, 0) << o.err;
      std::smatch m;
      EXPECT_TRUE(std::regex_search(
          o.out, m,
          std::regex(
              "\"flange\": \\{\\s*\"position_mm\": \\[([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\\]")))
          << o.out;
      return m.size() == 4 ? Vec3(std::stod(m[1]), std::stod(m[2]), std::stod(m[3])) : Vec3::Zero();
    };
    const Vec3 kdl(F.p.x() * 1e3, F.p.y() * 1e3, F.p.z() * 1e3);
    EXPECT_LT((fkOf(card) - kdl).norm(), 1e-5);  // the JSON's 6 decimals in mm
    EXPECT_GT((fkOf(robot) - kdl).norm(), 0.3);
  }
}

TEST(CardCalibration, ImportOfTheExportedUrdfRoundTripsTheBlock) {
  for (const char* robot : {"kuka-kr210-r2700-2", "abb-irb6640-185-280", "fanuc-r2000ic-210f"}) {
    SCOPED_TRACE(robot);
    GeometryCalibration cal = test::seededGeometryErrors(21, 0.4, 0.6);
    cal.base = FrameError{};  // a URDF holds the base error in joint 1's origin (below)
    const std::string card = calibratedCardCopy(robot, cal, std::string("cardcal-") + robot);
    const std::string dir = fs::path(card).parent_path().string();
    auto r = runRoprec("card export-urdf " + q(card) + " -o " + q(dir + "/real.urdf"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = runRoprec("card import-calibration --urdf " + q(dir + "/real.urdf") + " " + q(card) +
                  " -o " + q(dir + "/again.xml"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Robot back = loadRobot({dir + "/again.xml", "", ""});
    ASSERT_TRUE(back.card.calibration.has_value());
    for (size_t i = 0; i < 6; ++i) {
      EXPECT_LT((back.card.calibration->joints[i].dxyz - cal.joints[i].dxyz).norm(), 1e-12) << i;
      EXPECT_LT((back.card.calibration->joints[i].drpy - cal.joints[i].drpy).norm(), 1e-12) << i;
    }
    EXPECT_LT((back.card.calibration->tool.dxyz - cal.tool.dxyz).norm(), 1e-12);
    EXPECT_LT((back.card.calibration->tool.drpy - cal.tool.drpy).norm(), 1e-12);
    // the new card passes the check, in its own folder with its URDF found
    r = runRoprec("card check " + q(dir + "/again.xml"));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  }
}

TEST(CardCalibration, ABaseErrorImportsAsTheSameRealRobot) {
  const GeometryCalibration cal = test::seededGeometryErrors(22, 0.4, 0.6);
  const std::string card = calibratedCardCopy("kuka-kr120-r2500-pro", cal, "cardcal-base");
  const std::string dir = fs::path(card).parent_path().string();
  test::writeFile(dir + "/real.urdf", api::cardExportUrdf(card));
  const api::CardImportResult imp =
      api::cardImportCalibration(card, dir + "/real.urdf", dir + "/again.xml");
  const Robot robot = loadRobot({card, "", ""});
  EXPECT_TRUE(imp.calibration.base.isZero());
  const ChainDescription a = calibratedChain(robot.chain, cal);
  const ChainDescription b = calibratedChain(robot.chain, imp.calibration);
  std::mt19937 rng(5);
  for (int k = 0; k < 20; ++k) {
    Vec6 qv;
    for (int i = 0; i < 6; ++i) qv[i] = std::uniform_real_distribution<double>(-2, 2)(rng);
    EXPECT_LT(
        (chainForwardKinematics(a, qv).translation() - chainForwardKinematics(b, qv).translation())
            .norm(),
        1e-12);
  }
}

TEST(CardCalibration, CheckAcceptsAnExternallyCalibratedUrdf) {
  // a card whose URDF an external calibration wrote: axes and the flange a few 0.1 mrad off the
  // convention (the old check compared them to 1.4 mrad only for a reason: larger is a mistake)
  for (const char* robot : {"kuka-kr120-r2500-pro", "abb-irb6700-200-260", "fanuc-r2000ic-165f"}) {
    SCOPED_TRACE(robot);
    const GeometryCalibration cal = test::seededGeometryErrors(23, 0.5, 3.0);
    const Robot r = loadRobot({robot, "", ""});
    const std::string dir = test::tempDir(std::string("cardcal-ext-") + robot);
    const std::string urdf = dir + "/calibrated.urdf";
    test::writeFile(urdf, calibratedUrdf(r.card.urdf_path, r.chain, cal));
    std::string text = test::readFile(r.card.file);
    const std::string name = fs::path(r.card.urdf_path).filename().string();
    text = std::regex_replace(text, std::regex("urdf=\"" + name + "\""), "urdf=\"" + urdf + "\"");
    test::writeFile(dir + "/robot.xml", text);
    const auto res = runRoprec("card check " + q(dir + "/robot.xml"));
    EXPECT_EQ(res.exit_code, 0) << res.out << res.err;
    EXPECT_NE(res.out.find("calibrated URDF?"), std::string::npos) << res.out;
  }
}

TEST(CardCalibration, CheckBoundsTheCalibrationOffsets) {
  GeometryCalibration cal;
  cal.source = "test";
  cal.joints[1].dxyz = Vec3(2e-3, 0, 0);  // 2 mm: a warning
  std::string card = calibratedCardCopy("kuka-kr120-r2500-pro", cal, "cardcal-warn");
  auto r = runRoprec("card check " + q(card));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(
      std::regex_search(r.err, std::regex("robot\\.xml:[0-9]+: warning: <calibration> joint "
                                          "joint_a2 moves by 2\\.000 mm")))
      << r.err;
  cal.joints[1].dxyz = Vec3(0, 0, 0);
  cal.tool.drpy = Vec3(0, 0.025, 0);  // 25 mrad: an error
  card = calibratedCardCopy("kuka-kr120-r2500-pro", cal, "cardcal-err");
  r = runRoprec("card check " + q(card));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("error: <calibration> tool moves by"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
