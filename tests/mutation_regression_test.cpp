// Findings of scripts/mutation-campaign.py (issue 13), each with the corrupted input that showed
// it:
// * measured.csv with a coordinate of 1e300 reached the verification statistics (RMS overflowed to
//   inf) and `roprec verify` ended in "internal error: a non-finite number reached the JSON";
//   measured positions, u and diameters are now range-checked at their line; a decimal comma
//   (`-200,2796`) shifted a row's values and was accepted: a row longer than its header is an
//   error;
// * URDF: a misspelt attribute or element (`<origin ryz=...>`, `<axns>`, `<mass valeu=...>`) was
//   ignored by urdfdom and took its default (origin 0, axis x, mass 0), and an origin of 1e300 was
//   accepted: now errors at their line;
// * cell: a tool xyz of 1e300 mm was refused with a 300-digit number in the message, a workobject
//   rpy of 1e300 deg was accepted: xyz, rpy and com_mm are now bounded (100 m, 3600 deg);
// * robot card: a stiffness of 1e300 N m/rad was accepted (now [100, 1e12]; 1e-300 ended in an
// "internal error");
// * measured.csv truncated to two holes: the correlation per workobject axis is undefined (no
//   spread) and was NaN in the JSON ("internal error") and "nan" on stdout; now the JSON key is
//   left out and the text says "undefined".
// Seed 14 (second campaign):
// * cell: `<cut depth_mm="1e-300">`, `<drill web_mm="1e-300">` and `<tolerance
//   position_mm="1e300">` were accepted (every hole "conforms");
// * hole list: a decimal comma (`8,5`) split the diameter in two and shifted the columns;
// * measured.csv with the y and z columns swapped reached the identification (an infinite
//   condition number: "internal error"); such a hole lies 300 mm from its nominal one;
// * a cell without its <workobject> with a program that states its own base frame and a hole
//   list: every hole 1.3 m off its hole-list axis, matched by id without a word.
// Seed 31: a robot card's j23_coupling of 1e300; a milling cell's coupling compliance of 1e300.
// Seed 34: a milling cutter's diameter of 1e300 mm (forces wrote it, exit 0). Seeds 44 and 45: a
// milling cutter's runout angle of 1e300 deg.
// Seed 24: a TP motion to `P[inf]` (and so to `P[R[4]]` or `PR[3]`) went to no position without a
// word, and the hole it approached dropped out of the job.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "compensator/precision/cell.hpp"
#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "postproc/measured.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string q(const std::string& p) { return "'" + p + "'"; }
std::string sample(const std::string& rel) { return test::sourceDir() + "/samples/" + rel; }

std::string errorOf(const std::string& text) {
  try {
    (void)postproc::parseMeasured(text, "m.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(MutationRegression, AbsurdMeasuredValuesAreRefusedAtTheirLine) {
  EXPECT_EQ(errorOf("id,x,y,z\nV01,1,2,3\nV02,1,1e300,3\n")
                .rfind("m.csv:3: hole 'V02': a "
                       "coordinate lies more than 100 m",
                       0),
            0u)
      << errorOf("id,x,y,z\nV01,1,2,3\nV02,1,1e300,3\n");
  EXPECT_EQ(errorOf("id,x,y,z,u\nV01,1,2,3,1e300\n")
                .rfind("m.csv:2: hole 'V01': the measurement "
                       "uncertainty u is over 10 mm",
                       0),
            0u);
  EXPECT_EQ(errorOf("TYPE,NAME,X,Y,Z,D\nCIRCLE,V01,1,2,3,1e300\n")
                .rfind("m.csv:2: hole 'V01': the diameter is over 2 m", 0),
            0u);
  // A decimal comma shifted the row's values (x = -200, y = 2796, z = -199.9, u = 164.7).
  EXPECT_EQ(errorOf("id,x,y,z,u\nV02,-200,2796,-199.9475,164.7312,5.0\n")
                .rfind("m.csv:2: 6 cells but the header has 5 (decimal commas?", 0),
            0u);
  // The limits leave real files alone: 100 m and 10 mm are accepted.
  EXPECT_EQ(errorOf("id,x,y,z,u\nV01,100000,-100000,0,10000\n"), "(accepted)");
}

/// The bundled KR 120 folder copied with `from` replaced by `to` (once, after `anchor`) in `file`.
std::string mutatedKr120(const std::string& file, const std::string& anchor,
                         const std::string& from, const std::string& to) {
  const std::string src = test::sourceDir() + "/robots/kuka-kr120-r2500-pro";
  const std::string dir = test::tempDir("mutation-kr120") + "/kuka-kr120-r2500-pro";
  fs::create_directories(dir);
  for (const char* f : {"robot.xml", "kr120r2500pro.urdf"}) {
    std::string text = test::readFile(src + "/" + f);
    if (file == f) {
      const std::size_t a = text.find(anchor);
      const std::size_t at = a == std::string::npos ? a : text.find(from, a);
      EXPECT_NE(at, std::string::npos) << anchor << " / " << from;
      if (at != std::string::npos) text.replace(at, from.size(), to);
    }
    test::writeFile(dir + "/" + f, text);
  }
  return dir;
}

std::string urdfError(const std::string& anchor, const std::string& from, const std::string& to) {
  const std::string dir = mutatedKr120("kr120r2500pro.urdf", anchor, from, to);
  try {
    (void)loadUrdfChain(dir + "/kr120r2500pro.urdf");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(MutationRegression, UrdfNearMissNamesAndAbsurdOriginsAreErrors) {
  const std::string j2 = "<joint name=\"joint_a2\"";
  EXPECT_NE(urdfError(j2, "<origin xyz=", "<origin ryz=")
                .find(":122: unknown attribute 'ryz' on "
                      "<origin> (did you mean 'xyz'?)"),
            std::string::npos)
      << urdfError(j2, "<origin xyz=", "<origin ryz=");
  EXPECT_NE(urdfError(j2, "<axis xyz", "<axns xyz")
                .find(":123: unknown element <axns> in <joint> "
                      "(did you mean <axis>?)"),
            std::string::npos)
      << urdfError(j2, "<axis xyz", "<axns xyz");
  EXPECT_NE(urdfError(j2, "rpy=\"0 0 0\"", "rpy=\"1e300 0 0\"")
                .find(":122: <origin> rpy '1e300 0 0' is beyond 100 rad"),
            std::string::npos);
  EXPECT_NE(urdfError(j2, "xyz=\"0.350 0 0.675\"", "xyz=\"0.350 0 1e300\"")
                .find(":122: <origin> xyz '0.350 0 1e300' is beyond 100 m"),
            std::string::npos);
  EXPECT_NE(urdfError(j2, "<limit lower", "<limit lowr").find(":125: unknown attribute 'lowr'"),
            std::string::npos);
  EXPECT_NE(urdfError("<link", "<mass value=", "<mass valeu=")
                .find("unknown attribute 'valeu' on <mass> (did you mean 'value'?)"),
            std::string::npos);
  EXPECT_NE(urdfError("<link", "<inertial>", "<inertial><centre/>")
                .find("unknown element <centre> in <inertial>"),
            std::string::npos);
  // seed 15: an axis component of 1e300 was normalised into another axis ("internal error")
  EXPECT_NE(urdfError(j2, "<axis xyz=\"0 1 0\"", "<axis xyz=\"0 1 1e300\"")
                .find(":123: joint 'joint_a2' axis xyz '0 1 1e300' is not a direction"),
            std::string::npos)
      << urdfError(j2, "<axis xyz=\"0 1 0\"", "<axis xyz=\"0 1 1e300\"");
  // The unmutated copy loads (the checks accept the bundled URDF).
  EXPECT_EQ(urdfError(j2, "<origin", "<origin"), "(accepted)");
}

/// The InputError text of loading a card (or "(accepted)").
std::string cardError(const std::string& card) {
  try {
    (void)loadRobotCard(card);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

/// The sample R-2000iC program with `from` (at `at` characters past the first `anchor`)
/// replaced by `to`, parsed: its InputError text (or "(accepted)").
std::string tpError(const std::string& anchor, std::size_t at, std::size_t from,
                    const std::string& to) {
  std::string text = test::readFile(sample("emotor-housing/housing_r2000.ls"));
  const std::size_t a = text.find(anchor);
  EXPECT_NE(a, std::string::npos) << anchor;
  if (a == std::string::npos) return "(anchor not found)";
  text.replace(a + at, from, to);
  try {
    (void)postproc::parseProgram(postproc::Dialect::kTp, "r.ls", text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(MutationRegression, CardStiffnessOf1e300IsAnError) {
  const std::string dir = mutatedKr120("robot.xml", "<joint name=\"joint_a1\"",
                                       "stiffness=\"1.58e7\"", "stiffness=\"1e300\"");
  const std::string what = cardError(dir + "/robot.xml");
  EXPECT_NE(
      what.find("robot.xml:9: joint 'joint_a1': stiffness must be in [100, 1e12] N m/rad, got "
                "1e300"),
      std::string::npos)
      << what;
  // seed 15: 1e-300 made the compliance infinite ("internal error" in deflect)
  const std::string soft = mutatedKr120("robot.xml", "<joint name=\"joint_a1\"",
                                        "stiffness=\"1.58e7\"", "stiffness=\"1e-300\"");
  const auto r = test::runRoprec("deflect --robot " + q(soft + "/robot.xml") +
                                 " --joints \"0 -60 100 0 50 0\" -o " + q(soft + "/d.json"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("stiffness must be in [100, 1e12] N m/rad, got 1e-300"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

// Seed 31: a robot card's j23_coupling of 1e300 was accepted (every controller J3 of `fk` and of
// the outputs 1e300 × J2), and a milling cell's <coupling compliance_um_per_N> of 1e300 overflowed
// the coupling to inf ("internal error" in `forces`).
TEST(MutationRegression, AJ23CouplingOtherThanOneToOneAndAnAbsurdCouplingComplianceAreErrors) {
  for (const char* bad : {"1e300", "0.5", "-2"}) {
    const std::string dir = mutatedKr120("robot.xml", "<controller", "j23_coupling=\"0\"",
                                         std::string("j23_coupling=\"") + bad + "\"");
    const std::string what = cardError(dir + "/robot.xml");
    EXPECT_NE(what.find("robot.xml:"), std::string::npos) << what;
    EXPECT_NE(what.find("j23_coupling must be -1, 0 or 1"), std::string::npos) << what;
  }
  for (const char* good : {"-1", "1"}) {
    const std::string dir = mutatedKr120("robot.xml", "<controller", "j23_coupling=\"0\"",
                                         std::string("j23_coupling=\"") + good + "\"");
    EXPECT_EQ(cardError(dir + "/robot.xml"), "(accepted)") << good;
  }
  // the milling and drilling samples with one number corrupted, through `forces`: exit 2 at the
  // number's line, no "internal error", nothing written
  const std::string dir = test::tempDir("mutation-process");
  auto forcesWith = [&](const std::string& cell, const std::string& from, const std::string& to,
                        const std::string& expected) {
    std::string text = test::readFile(sample("cells/" + cell));
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    test::writeFile(dir + "/cell.xml", text);
    const auto r =
        test::runRoprec("forces --cell " + q(dir + "/cell.xml") + " --json " + q(dir + "/f.json"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/f.json"));
  };
  forcesWith("alu-milling-7075.xml", "compliance_um_per_N=\"1 0 0",
             "compliance_um_per_N=\"1e300 0 0",
             "cell.xml:16: <coupling> compliance_um_per_N entry 1 = 1e+300 is outside the "
             "plausible range");
  // seed 34: a milling cutter of 1e300 mm was accepted (forces wrote its 300-digit diameter and
  // the forces of that cutter, exit 0); the drill's diameter had no bound either
  forcesWith("alu-milling-7075.xml", "<mill diameter_mm=\"10\"", "<mill diameter_mm=\"1e300\"",
             "cell.xml:13: <mill> diameter_mm = 1e+300 is outside the plausible range 0.1 .. 200 "
             "(cutter diameter, mm)");
  // seeds 44 and 45: a runout angle of 1e300 deg was accepted (its cosine is whatever the
  // reduction of 1e300 gives)
  forcesWith("alu-milling-7075.xml", "runout_angle_deg=\"0\"", "runout_angle_deg=\"1e300\"",
             "cell.xml:13: <mill> runout_angle_deg = 1e+300 is outside the plausible range -360 .. "
             "360 (angle of the runout, deg)");
  forcesWith("alu-drilling-7075-dc8.xml", "<drill diameter_mm=\"8\"",
             "<drill diameter_mm=\"1e300\"",
             "cell.xml:9: <drill> diameter_mm = 1e+300 is outside the plausible range 0.1 .. 100 "
             "(twist drill diameter, mm)");
}

std::string cellError(const std::string& from, const std::string& to) {
  std::string text = test::readFile(sample("cells/housing-kr120.xml"));
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const std::string path = test::tempDir("mutation-cell") + "/cell.xml";
  test::writeFile(path, text);
  try {
    (void)loadCell(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(MutationRegression, CellPosesAndCentreOfMassAreBounded) {
  const std::string tool = cellError("xyz=\"0 0 320\"", "xyz=\"0 0 1e300\"");
  EXPECT_NE(tool.find("cell.xml:9: <tool> xyz '0 0 1e300' is beyond 100 m (mm expected)"),
            std::string::npos)
      << tool;
  EXPECT_EQ(tool.find("00000000"), std::string::npos) << tool;
  EXPECT_NE(cellError("<workobject xyz=\"1350 0 300\" rpy=\"0 0 0\"",
                      "<workobject xyz=\"1350 0 300\" rpy=\"0 1e300 0\"")
                .find("cell.xml:13: <workobject> rpy '0 1e300 0' is beyond 3600 deg"),
            std::string::npos);
  EXPECT_NE(cellError("com_mm=\"0 0 120\"", "com_mm=\"0 0 -1e300\"")
                .find("cell.xml:9: <tool> com_mm '0 0 -1e300' is beyond 100 m"),
            std::string::npos);
  EXPECT_EQ(cellError("xyz=\"0 0 320\"", "xyz=\"0 0 320\""), "(accepted)");
}

TEST(MutationRegression, VerifyWithTwoMeasuredHolesHasNoUndefinedCorrelationInItsOutputs) {
  const std::string dir = test::tempDir("mutation-verify");
  // The sample's measured file cut after its second hole (what the campaign's truncation did).
  const std::string full = test::readFile(sample("verification/measured.csv"));
  std::string cut;
  int holes = 0;
  for (std::size_t at = 0; at < full.size();) {
    const std::size_t end = full.find('\n', at);
    const std::string line = full.substr(at, end == std::string::npos ? end : end - at + 1);
    at = end == std::string::npos ? full.size() : end + 1;
    if (line.rfind("V", 0) == 0 && ++holes > 2) break;
    cut += line;
  }
  ASSERT_EQ(holes, 3);
  test::writeFile(dir + "/m.csv", cut);
  const auto r = test::runRoprec("verify --cell " + q(sample("cells/housing-kr120.xml")) + " " +
                                 q(sample("verification/test_kr120.src")) + " --holes " +
                                 q(sample("verification/test_kr120_holes.csv")) + " --measured " +
                                 q(dir + "/m.csv") + " --json " + q(dir + "/v.json") +
                                 " --report " + q(dir + "/v.html"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("correlation x y z undefined"), std::string::npos) << r.out;
  const json j = json::parse(test::readFile(dir + "/v.json"));
  EXPECT_EQ(j["summary"]["holes"], 2);
  EXPECT_FALSE(j["summary"].contains("correlation_workobject_xyz"));
  const std::string html = test::readFile(dir + "/v.html");
  EXPECT_EQ(html.find(">nan"), std::string::npos);
  EXPECT_NE(html.find("undefined"), std::string::npos);
}

TEST(MutationRegression, AbsurdDepthWebAndToleranceAreRefusedAtTheirLine) {
  EXPECT_NE(cellError("depth_mm=\"20\"", "depth_mm=\"1e-300\"")
                .find("cell.xml:17: <cut> depth_mm = 1e-300 is outside the plausible range"),
            std::string::npos);
  EXPECT_NE(cellError("web_mm=\"1.2\"", "web_mm=\"1e-300\"")
                .find("cell.xml:15: <drill> web_mm = 1e-300 is below 0.02 Dc"),
            std::string::npos);
  EXPECT_NE(cellError("web_mm=\"1.2\"", "web_mm=\"1.2\"").find("(accepted)"), std::string::npos);
  const std::string tol = cellError("position_mm=\"0.2\"", "position_mm=\"1e300\"");
  EXPECT_NE(tol.find("position_mm must lie in (0, 10] mm"), std::string::npos) << tol;
}

TEST(MutationRegression, ADecimalCommaInAHoleListIsAnErrorAtItsCell) {
  const std::string dir = test::tempDir("mutation-comma");
  std::string text = test::readFile(sample("emotor-housing/holes.csv"));
  const std::size_t at = text.find(",6.8,16.0,0.20");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 4, ",6,8");
  test::writeFile(dir + "/holes.csv", text);
  const auto r = test::runRoprec("predict --cell " + q(sample("cells/housing-kr120.xml")) + " " +
                                 q(dir + "/holes.csv") + " --json " + q(dir + "/p.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holes.csv:3: this row has 11 cells but the header has 10 columns"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
}

TEST(MutationRegression, MeasuredColumnsSwappedAreRefusedBeforeTheIdentification) {
  const std::string dir = test::tempDir("mutation-swap");
  std::string text = test::readFile(sample("verification/measured.csv"));
  // swap the y and z cells of the first hole
  const size_t row = text.find("\nV01,") + 1;
  const size_t y = text.find(',', row + 4) + 1, z = text.find(',', y) + 1, u = text.find(',', z);
  text = text.substr(0, row + 4) + text.substr(z, u - z) + "," + text.substr(y, z - 1 - y) +
         text.substr(u);
  test::writeFile(dir + "/m.csv", text);
  const auto r = test::runRoprec("verify --cell " + q(sample("cells/housing-kr120.xml")) + " " +
                                 q(sample("verification/test_kr120.src")) + " --holes " +
                                 q(sample("verification/test_kr120_holes.csv")) + " --measured " +
                                 q(dir + "/m.csv") + " --register rigid --calibrate " +
                                 q(dir + "/card.xml") + " --json " + q(dir + "/v.json"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("m.csv:5: measured hole V01 lies "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than any drilling deviation"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

TEST(MutationRegression, HolesOffTheirHoleListAxisAreAWarning) {
  std::string text = test::readFile(sample("cells/housing-kr120.xml"));
  const std::size_t b = text.find("<workobject");
  const std::size_t e = text.find("/>", b) + 2;
  text.erase(b, e - b);
  const std::string dir = test::tempDir("mutation-wobj");
  test::writeFile(dir + "/cell.xml", text);
  const std::string args = " " + q(sample("emotor-housing/housing_kr120.src")) + " --holes " +
                           q(sample("emotor-housing/holes.csv")) + " --json " + q(dir + "/p.json");
  const auto bad = test::runRoprec("predict --cell " + q(dir + "/cell.xml") + args + " --json -");
  EXPECT_NE(bad.err.find("warning: 204 of 204 drill points of the program lie off their "
                         "hole-list axis by more than --match-tol 0.5 mm"),
            std::string::npos)
      << bad.err;
  const auto good = test::runRoprec("predict --cell " + q(sample("cells/housing-kr120.xml")) +
                                    args + " --json -");
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(good.err.find("off their hole-list axis"), std::string::npos) << good.err;
}

TEST(MutationRegression, SpeedsFeedsAndBalancerSizesArePlausible) {
  // seeds 16 and 17: spindle_rpm 1e300 / 1e-300 and feed 1e-300 were accepted (the machining-
  // centre time then printed as a 300-digit number); a gas volume of 1e300 l changed every
  // gravity torque
  EXPECT_NE(cellError("spindle_rpm=\"6000\"", "spindle_rpm=\"1e-300\"")
                .find("cell.xml:17: <cut> spindle_rpm = 1e-300 is outside the plausible range"),
            std::string::npos);
  EXPECT_NE(cellError("spindle_rpm=\"6000\"", "spindle_rpm=\"1e300\"")
                .find("spindle_rpm = 1e+300 is outside the plausible range 10 .. 100000"),
            std::string::npos);
  EXPECT_NE(cellError("feed_mm_per_rev=\"0.2\"", "feed_mm_per_rev=\"1e-300\"")
                .find("feed_mm_per_rev = 1e-300 is outside the plausible range"),
            std::string::npos);
  const std::string dir = mutatedKr120("robot.xml", "<counterbalance", "gas_volume_l=\"0.36\"",
                                       "gas_volume_l=\"1e300\"");
  const std::string what = cardError(dir + "/robot.xml");
  EXPECT_NE(what.find("<counterbalance> gas_volume_l = 1e+300 is outside the plausible range"),
            std::string::npos)
      << what;
}

TEST(MutationRegression, ATpLineWithoutItsNumberIsAnError) {
  // seed 16: `inf:L P[591] ...` (line number damaged) was skipped: a motion dropped in silence
  const std::string e = tpError("1182:L P[591]", 0, 4, "inf");
  EXPECT_NE(e.find("a /MN line starts with its line number"), std::string::npos) << e;
  EXPECT_NE(e.find("got 'inf'"), std::string::npos) << e;
}

TEST(MutationRegression, ATpSpeedWithoutItsNumberAndAZeroBudgetTermAreErrors) {
  // seed 19: `nanmm/sec` left the move without a speed (the drill feed is recognised from it);
  // <uncertainty stiffness_rel="0"> silently dropped the stiffness term of U_robot
  const std::string e = tpError("L P[306] 20mm/sec", 9, 2, "nan");
  EXPECT_NE(e.find("speed 'nanmm/sec' is not a number with its unit"), std::string::npos) << e;
  const std::string dir = test::tempDir("mutation-budget");
  std::string cell = test::readFile(sample("cells/housing-kr120.xml"));
  cell.replace(cell.find("stiffness_rel=\"0.10\""), 20, "stiffness_rel=\"0\"");
  test::writeFile(dir + "/cell.xml", cell);
  const auto r =
      test::runRoprec("predict --cell " + q(dir + "/cell.xml") + " " +
                      q(sample("emotor-housing/holes.csv")) + " --json " + q(dir + "/p.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("stiffness_rel = 0 must lie in [0.01, 1]"), std::string::npos) << r.err;
}

TEST(MutationRegression, ATpSpeedWithAnExponentAndAnAbsurdSpeedAreErrors) {
  // seed 26: `L P[374] 1e300mm/sec` was read as 1 mm/sec (the number's leading digit; the rest
  // taken for the unit): the approach became the slowest move, the hole's depth 32 -> 80 mm and
  // predict exited 0. The unit must follow the number, and a linear speed is at most 10 m/s.
  EXPECT_NE(tpError("L P[374] 250mm/sec", 9, 3, "1e300")
                .find("speed '1e300mm/sec' is not a number with its unit"),
            std::string::npos);
  EXPECT_NE(tpError("L P[374] 250mm/sec", 9, 3, "25x0").find("speed '25x0mm/sec' is not a number"),
            std::string::npos);
  const std::string fast = tpError("L P[374] 250mm/sec", 9, 3, "25000");
  EXPECT_NE(fast.find("r.ls:768: L: speed 25000 mm/s is out of range (<= 10000 mm/s"),
            std::string::npos)
      << fast;
  EXPECT_EQ(tpError("L P[374] 250mm/sec", 9, 3, "9000"), "(accepted)");  // fast, but a speed
  EXPECT_EQ(tpError("L P[374] 250mm/sec", 9, 9, "1500cm/min"), "(accepted)");
  // KUKA: $VEL.CP is in m/s
  std::string krl = test::readFile(sample("emotor-housing/housing_kr120.src"));
  const std::string vel = "$VEL.CP = 0.25000";
  ASSERT_NE(krl.find(vel), std::string::npos);
  krl.replace(krl.find(vel), vel.size(), "$VEL.CP = 250");
  try {
    (void)postproc::parseProgram(postproc::Dialect::kKrl, "k.src", krl);
    ADD_FAILURE() << "a 250 m/s speed was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("speed 250000 mm/s is out of range"), std::string::npos) << e.what();
  }
}

/// The unresolved references of `p` that are positions (not the controller's frames).
std::vector<postproc::Unresolved> positionsUnresolved(const postproc::Program& p) {
  std::vector<postproc::Unresolved> out;
  for (const postproc::Unresolved& u : p.unresolved)
    if (u.ref.rfind("UFRAME", 0) != 0 && u.ref.rfind("UTOOL", 0) != 0) out.push_back(u);
  return out;
}

TEST(MutationRegression, ATpMotionToAPositionRoprecCannotKnowIsReportedAtItsLine) {
  // seed 24: `L P[inf] ...` (the index damaged) went to no position without a word: the hole it
  // approaches dropped out of the job (204 -> 203 holes) and compensate exited 0. The same for a
  // register-indexed position `P[R[4]]` and a position register `PR[3]`, whose values live in the
  // controller: each is now an unresolved reference with its line.
  const std::string text = test::readFile(sample("emotor-housing/housing_r2000.ls"));
  const std::string anchor = " 113:L P[56] 250mm/sec CNT10 ;";
  ASSERT_NE(text.find(anchor), std::string::npos);
  const std::string dir = test::tempDir("mutation-tp-runtime");
  for (const std::string ref : {"P[inf]", "P[R[4]]", "PR[3]"}) {
    SCOPED_TRACE(ref);
    std::string t = text;
    t.replace(t.find(anchor), anchor.size(), " 113:L " + ref + " 250mm/sec CNT10 ;");
    const postproc::Program p = postproc::parseProgram(postproc::Dialect::kTp, "r.ls", t);
    ASSERT_EQ(positionsUnresolved(p).size(), 1U);
    EXPECT_EQ(positionsUnresolved(p)[0].ref, ref);
    EXPECT_EQ(positionsUnresolved(p)[0].line, 132);
    test::writeFile(dir + "/r.ls", t);
    const auto r = test::runRoprec("predict --cell " + q(sample("cells/housing-r2000.xml")) + " " +
                                   q(dir + "/r.ls") + " --frame cell --tool cell --json " +
                                   q(dir + "/p.json"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("roprec: warning: unresolved " + ref + " (" + dir + "/r.ls:132): "),
              std::string::npos)
        << r.err;
  }
  // the sample itself has none (only its controller frames UFRAME[1] and UTOOL[1])
  EXPECT_TRUE(
      positionsUnresolved(postproc::parseProgram(postproc::Dialect::kTp, "r.ls", text)).empty());
}

}  // namespace
}  // namespace roprec
