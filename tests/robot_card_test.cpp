// The robot card (compensator/robot/robot_card.hpp): unknown names are errors with a hint at their
// line, a card needs <repeatability>, link masses and inertias are physical, stiffnesses, the J2-J3
// coupling and the balancer are range-checked, and an error about the URDF as a whole points at
// the card line that names it.
#include "compensator/robot/robot_card.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

#include "compensator/support/error.hpp"
#include "tests/support/input_errors.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

std::string q(const std::string& p) { return "'" + p + "'"; }

std::string bundledCardDir() { return test::sourceDir() + "/robots/kuka-kr120-r2500-pro"; }

/// The bundled KR 120 card with an absolute URDF path, edited by `edit`, written into a temp dir.
std::string cardCopy(const std::string& tag, const std::string& from, const std::string& to) {
  std::string text = test::readFile(bundledCardDir() + "/robot.xml");
  text = std::regex_replace(text, std::regex("urdf=\"kr120r2500pro.urdf\""),
                            "urdf=\"" + bundledCardDir() + "/kr120r2500pro.urdf\"");
  if (!from.empty()) text = test::replaced(text, from, to);
  const std::string path = test::tempDir(tag) + "/robot.xml";
  test::writeFile(path, text);
  return path;
}

InputError cardError(const std::string& path) {
  try {
    (void)loadRobot({path, "", ""});
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e;
  }
  ADD_FAILURE() << "accepted " << path;
  return InputError("", 0, "");
}

TEST(RobotCard, TheUneditedCopyLoads) {
  EXPECT_NO_THROW((void)loadRobot({cardCopy("strict-card-ok", "", ""), "", ""}));
}

TEST(RobotCard, UnknownNamesAreErrorsWithAHint) {
  const struct {
    std::string from, to, expect, line_of;
  } cases[] = {
      {"<joint name=\"joint_a3\" stiffness=", "<joint name=\"joint_a3\" stifness=",
       "unknown attribute 'stifness' on <joint> (did you mean 'stiffness'?)", "stifness="},
      {"<repeatability rp_mm=", "<repeatability rp_nm=", "(did you mean 'rp_mm'?)", "rp_nm="},
      {"<repeatability ", "<repeatibility ",
       "unknown element <repeatibility> in <robot> (did you mean <repeatability>?)",
       "<repeatibility "},
      {"rated_payload_kg=", "rated_payload=", "(did you mean 'rated_payload_kg'?)",
       "<robot name="},  // an attribute error is reported at its element's start tag
      {"<controller ", "<controler/>\n  <controller ", "(did you mean <controller>?)",
       "<controler/>"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.to);
    const std::string path = cardCopy("strict-card", c.from, c.to);
    const InputError e = cardError(path);
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_EQ(e.line(), test::lineOf(test::readFile(path), c.line_of)) << e.message();
  }
}

TEST(RobotCard, ACardWithoutRepeatabilityIsAnError) {
  std::string text = test::readFile(cardCopy("strict-card-rp", "", ""));
  const std::size_t a = text.find("  <repeatability");
  const std::size_t b = text.find("/>", a) + 3;
  text.erase(a, b - a);
  const std::string path = test::tempDir("strict-card-no-rp") + "/robot.xml";
  test::writeFile(path, text);
  const InputError e = cardError(path);
  EXPECT_NE(e.message().find("has no <repeatability"), std::string::npos) << e.message();
  EXPECT_EQ(e.line(), test::lineOf(text, "<robot "));
}

TEST(RobotCard, LinkMassesAndInertiasMustBePhysical) {
  const std::string link = "<controller ";
  const struct {
    std::string extra, expect;
  } cases[] = {
      {"<link name=\"link_3\" mass_kg=\"-30\" com_mm=\"0 0 0\" source=\"x\"/>",
       "mass_kg must be > 0, got -30"},
      {"<link name=\"link_3\" mass_kg=\"inf\" com_mm=\"0 0 0\" source=\"x\"/>",
       "not a finite number"},
      {"<link name=\"link_3\" mass_kg=\"30\" com_mm=\"0 0 0\" inertia_kgm2=\"1 0 0 -1 0 1\" "
       "source=\"x\"/>",
       "principal moments must be >= 0"},
      {"<link name=\"link_3\" mass_kg=\"30\" com_mm=\"0 0 0\" inertia_kgm2=\"1 0 0 1 0 5\" "
       "source=\"x\"/>",
       "triangle inequality"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.extra);
    const std::string path = cardCopy("strict-card-link", link, c.extra + "\n  " + link);
    const InputError e = cardError(path);
    EXPECT_NE(e.message().find(c.expect), std::string::npos) << e.message();
    EXPECT_EQ(e.line(), test::lineOf(test::readFile(path), "<link "));
  }
}

TEST(RobotCard, AMissingUrdfIsReportedAtTheCardLineThatNamesIt) {
  const std::string dir = test::tempDir("errloc_card");
  std::string card = test::readFile(test::sourceDir() + "/robots/kuka-kr120-r2500-pro/robot.xml");
  const std::string from = "urdf=\"kr120r2500pro.urdf\"";
  const std::size_t at = card.find(from);
  ASSERT_NE(at, std::string::npos);
  card.replace(at, from.size(), "urdf=\"missing.urdf\"");
  test::writeFile(dir + "/robot.xml", card);
  // the line of the <robot> start tag that carries urdf=
  const std::size_t tag = card.find("<robot ");
  ASSERT_NE(tag, std::string::npos);
  int line = 1;
  for (std::size_t i = 0; i < tag; ++i) line += card[i] == '\n' ? 1 : 0;
  const auto r = test::runRoprec("fk --robot '" + dir + "/robot.xml' --joints \"0 0 0 0 0 0\"");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("robot.xml:" + std::to_string(line) + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot open URDF"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("missing.urdf"), std::string::npos) << r.err;
}

/// The InputError text of loading a card (or "(accepted)").
std::string cardLoadError(const std::string& card) {
  return test::inputErrorText([&] { (void)loadRobotCard(card); });
}

TEST(RobotCard, AStiffnessOutside100To1e12IsAnErrorAtItsLine) {
  const std::string dir = test::editedKr120("robot.xml", "<joint name=\"joint_a1\"",
                                            "stiffness=\"1.58e7\"", "stiffness=\"1e300\"");
  const std::string what = cardLoadError(dir + "/robot.xml");
  EXPECT_NE(
      what.find("robot.xml:9: joint 'joint_a1': stiffness must be in [100, 1e12] N m/rad, got "
                "1e300"),
      std::string::npos)
      << what;
  // 1e-300 would make the compliance infinite: deflect exits 2, not with an internal error
  const std::string soft = test::editedKr120("robot.xml", "<joint name=\"joint_a1\"",
                                             "stiffness=\"1.58e7\"", "stiffness=\"1e-300\"");
  const auto r = test::runRoprec("deflect --robot " + q(soft + "/robot.xml") +
                                 " --joints \"0 -60 100 0 50 0\" -o " + q(soft + "/d.json"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("stiffness must be in [100, 1e12] N m/rad, got 1e-300"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

// A j23_coupling of 1e300 must not be accepted (every controller J3 would be 1e300 x J2).
TEST(RobotCard, AJ23CouplingOtherThanOneToOneIsAnError) {
  for (const char* bad : {"1e300", "0.5", "-2"}) {
    const std::string dir = test::editedKr120("robot.xml", "<controller", "j23_coupling=\"0\"",
                                              std::string("j23_coupling=\"") + bad + "\"");
    const std::string what = cardLoadError(dir + "/robot.xml");
    EXPECT_NE(what.find("robot.xml:"), std::string::npos) << what;
    EXPECT_NE(what.find("j23_coupling must be -1, 0 or 1"), std::string::npos) << what;
  }
  for (const char* good : {"-1", "1"}) {
    const std::string dir = test::editedKr120("robot.xml", "<controller", "j23_coupling=\"0\"",
                                              std::string("j23_coupling=\"") + good + "\"");
    EXPECT_EQ(cardLoadError(dir + "/robot.xml"), "(accepted)") << good;
  }
}

TEST(RobotCard, AnAbsurdBalancerGasVolumeIsAnError) {
  // a gas volume of 1e300 l would change every gravity torque
  const std::string dir = test::editedKr120("robot.xml", "<counterbalance", "gas_volume_l=\"0.36\"",
                                            "gas_volume_l=\"1e300\"");
  const std::string what = cardLoadError(dir + "/robot.xml");
  EXPECT_NE(what.find("<counterbalance> gas_volume_l = 1e+300 is outside the plausible range"),
            std::string::npos)
      << what;
}

}  // namespace
}  // namespace roprec
