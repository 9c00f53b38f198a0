// The FANUC TP reader (postproc/tp.cpp) on what controllers write: the end line of a point-logic
// sub-block, apostrophes in position comments, positions never taught (`UF : F`, `********`), a
// SCARA's CONFIG, and speeds no motion can run at. Each program is written for the test; it must
// round-trip byte for byte through `roprec convert` and `roprec inspect` must describe it.
// Damaged lines are errors at their line: a line number, a speed without its number or with an
// exponent, a frame number that is not a small integer; a motion to a position only the
// controller knows (P[R[4]], PR[3]) is an unresolved reference at its line. UTOOL_NUM selects the
// tool of positions without their own UT; a position taught in another tool than the active one
// is a conflict predict refuses at the motion; UTOOL_NUM=R[i] is unresolved, noted once.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "compensator/support/error.hpp"
#include "postproc/program.hpp"
#include "tests/support/input_errors.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nlohmann::json;

json roundTripAndInspect(const std::string& tag, const std::string& text, std::string* err) {
  const std::string dir = test::tempDir(tag);
  const std::string path = dir + "/job.ls";
  test::writeFile(path, text);
  const auto c = test::runRoprec("convert '" + path + "' -o '" + dir + "/copy.ls'");
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(test::readFile(dir + "/copy.ls"), text);
  const auto i = test::runRoprec("inspect '" + path + "' --all");
  EXPECT_EQ(i.exit_code, 0) << i.err;
  if (err != nullptr) *err = c.err + i.err;
  return i.exit_code == 0 ? json::parse(i.out) : json();
}

std::string record(const std::string& head, const std::string& uf_ut, const std::string& config,
                   const std::string& z) {
  return head + "{\r\n   GP1:\r\n\t" + uf_ut + ",\t\tCONFIG : '" + config +
         "',\r\n\tX =   150.000  mm,\tY =     0.000  mm,\tZ =   " + z +
         "  mm,\r\n\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\r\n};\r\n";
}

TEST(TpReader, PointLogicSubBlocksWithTheirEndLineRead) {
  // TB/DB logic after a motion: numbered sub-block lines, closed by `------ ;`
  const std::string text =
      "/PROG  LOGIC\r\n/ATTR\r\nDEFAULT_GROUP\t= 1,*,*,*,*;\r\n/MN\r\n"
      "   1:J P[1] 50% CNT100 TB    .50sec,CALL SPINDLE_ON ;\r\n"
      "      1:  DO[3]=ON ;\r\n"
      "       ------ ;\r\n"
      "   2:L P[2] 20mm/sec FINE DB   10.0mm,CALL DRILL_START ;\r\n"
      "       ------ ;\r\n"
      "   3:L P[1] 250mm/sec FINE ;\r\n"
      "/POS\r\n" +
      record("P[1]", "UF : 0, UT : 1", "N U T, 0, 0, 0", "284.000") +
      record("P[2]", "UF : 0, UT : 1", "N U T, 0, 0, 0", "234.000") + "/END\r\n";
  std::string err;
  const json j = roundTripAndInspect("tp-logic", text, &err);
  EXPECT_EQ(err.find("a /MN line starts with its line number"), std::string::npos) << err;
  ASSERT_TRUE(j.is_object());
  ASSERT_EQ(j["motions"].size(), 3U);
  EXPECT_EQ(j["motions"][0]["markers"], json({"call SPINDLE_ON"}));
  EXPECT_EQ(j["motions"][1]["markers"], json({"call DRILL_START"}));
  EXPECT_EQ(j["motions"][1]["line"], 8);
  EXPECT_DOUBLE_EQ(j["motions"][1]["speed_mm_s"].get<double>(), 20.0);
  EXPECT_EQ(j["motions"][2]["line"], 10);
}

TEST(TpReader, ALineWithoutItsNumberIsStillAnError) {
  // the sub-block end is `-` only: any other text without a line number is a damaged line
  const std::string dir = test::tempDir("tp-no-number");
  test::writeFile(dir + "/j.ls",
                  "/PROG  J\r\n/MN\r\n   1:L P[1] 100mm/sec FINE ;\r\n       --x-- ;\r\n/POS\r\n" +
                      record("P[1]", "UF : 0, UT : 1", "N U T, 0, 0, 0", "284.000") + "/END\r\n");
  const auto r = test::runRoprec("inspect '" + dir + "/j.ls' --all");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("j.ls:4: a /MN line starts with its line number"), std::string::npos)
      << r.err;
}

TEST(TpReader, AnApostropheInAPositionCommentIsText) {
  const std::string text =
      "/PROG  QUOTE\r\n/MN\r\n"
      "   1:J P[101:1-0'] 10% FINE ;\r\n"
      "   2:L P[102:it's 2] 20mm/sec FINE ;\r\n"
      "/POS\r\n" +
      record("P[101:1-0']", "UF : 0, UT : 1", "N U T, 0, 0, 0", "284.000") +
      record("P[102:\"it's 2\"]", "UF : 0, UT : 1", "N U T, 0, 0, 0", "234.000") + "/END\r\n";
  std::string err;
  const json j = roundTripAndInspect("tp-quote", text, &err);
  EXPECT_EQ(err.find("unterminated position reference"), std::string::npos) << err;
  ASSERT_TRUE(j.is_object());
  ASSERT_EQ(j["motions"].size(), 2U);
  EXPECT_EQ(j["motions"][0]["target"], 0);
  EXPECT_EQ(j["motions"][1]["target"], 1);
  EXPECT_EQ(j["motions"][1]["zone"], "FINE");
  EXPECT_DOUBLE_EQ(j["motions"][1]["speed_mm_s"].get<double>(), 20.0);
  EXPECT_EQ(j["targets"][1]["native"]["z"], 234);
}

const std::string kUntaught =
    "P[3]{\r\n   GP1:\r\n\tUF : F, UT : F,\t\tCONFIG : 'N D B, 0, 0, 0',\r\n"
    "\tX = ********  mm,\tY = ********  mm,\tZ = ********  mm,\r\n"
    "\tW = ******** deg,\tP = ******** deg,\tR = ******** deg\r\n};\r\n";

TEST(TpReader, APositionNeverTaughtReadsAndAMotionToItIsUnresolved) {
  const std::string text =
      "/PROG  UNTAUGHT\r\n/MN\r\n"
      "   1:J P[1] 10% FINE ;\r\n"
      "   2:L P[3] 100mm/sec FINE ;\r\n"
      "   3:J P[3] 10% FINE ;\r\n"
      "/POS\r\n" +
      record("P[1]", "UF : 0, UT : 1", "N U T, 0, 0, 0", "284.000") + kUntaught + "/END\r\n";
  std::string err;
  const json j = roundTripAndInspect("tp-untaught", text, &err);
  EXPECT_EQ(err.find("broken number"), std::string::npos) << err;
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["targets"].size(), 1U);  // P[3] has no pose
  ASSERT_EQ(j["motions"].size(), 3U);
  EXPECT_EQ(j["motions"][1]["target"], -1);
  EXPECT_EQ(j["motions"][1]["derivation"], "untaught");
  EXPECT_EQ(j["motions"][2]["derivation"], "untaught");
  int reported = 0;  // once, at the first motion to it
  for (const json& u : j["unresolved"])
    reported += u["ref"] == "P[3]" && u["line"] == 4 &&
                u["what"].get<std::string>().find("never taught") != std::string::npos;
  EXPECT_EQ(reported, 1) << j["unresolved"].dump();
}

TEST(TpReader, APositionNeverTaughtIsAnErrorOnlyWhereAJobNeedsIt) {
  // a drill cycle whose bottom was never taught: predict cannot place the hole and says why
  const std::string dir = test::tempDir("tp-untaught-predict");
  test::writeFile(dir + "/j.ls",
                  "/PROG  J\r\n/MN\r\n   1:J P[1] 10% FINE ;\r\n"
                  "   2:L P[3] 2mm/sec FINE ;\r\n   3:L P[1] 250mm/sec FINE ;\r\n"
                  "/POS\r\n" +
                      record("P[1]", "UF : 0, UT : 0", "N U T, 0, 0, 0", "284.000") + kUntaught +
                      "/END\r\n");
  const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                 "/samples/cells/housing-r2000.xml' '" + dir +
                                 "/j.ls' --frame cell --tool cell --json '" + dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no drill cycle recognised"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'P[3]'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("broken number"), std::string::npos) << r.err;
}

TEST(TpReader, AScaraConfigIsKeptAsText) {
  const std::string text = "/PROG  SCARA\r\n/MN\r\n   1:J P[1] 10% FINE ;\r\n/POS\r\n" +
                           record("P[1]", "UF : 0, UT : 1", "L, 0, 0, 0", "84.000") + "/END\r\n";
  std::string err;
  const json j = roundTripAndInspect("tp-scara", text, &err);
  EXPECT_EQ(err.find("CONFIG string not understood"), std::string::npos) << err;
  ASSERT_TRUE(j.is_object());
  ASSERT_EQ(j["targets"].size(), 1U);
  EXPECT_FALSE(j["targets"][0].contains("config"));  // states no 6-axis configuration
  EXPECT_EQ(j["targets"][0]["native"]["z"], 84);
  ASSERT_EQ(j["notes"].size(), 1U);
  EXPECT_NE(j["notes"][0].get<std::string>().find("CONFIG 'L, 0, 0, 0'"), std::string::npos);
  EXPECT_NE(j["notes"][0].get<std::string>().find("6-axis arms only"), std::string::npos);
}

TEST(TpReader, ASpeedOfZeroIsAnInputErrorAtItsLine) {
  const std::string dir = test::tempDir("tp-zero-speed");
  test::writeFile(dir + "/j.ls",
                  "/PROG  J\r\n/MN\r\n   1:J P[1] 10% FINE ;\r\n   2:L P[1] 0mm/sec FINE ;\r\n"
                  "/POS\r\n" +
                      record("P[1]", "UF : 0, UT : 1", "N U T, 0, 0, 0", "284.000") + "/END\r\n");
  const auto r = test::runRoprec("inspect '" + dir + "/j.ls' --all");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("j.ls:4: L: speed 0 mm/s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("hint:"), std::string::npos) << r.err;
}

using postproc::Dialect;
using postproc::parseProgram;

TEST(TpReader, FrameNumbersAreSmallIntegers) {
  const std::string path = test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls";
  const std::string good = test::readFile(path);
  EXPECT_EQ(test::programReadError(Dialect::kTp, "r.ls", good), "(accepted)");
  for (const char* bad : {"UT : 1e300", "UT : 1.5", "UT : -1"}) {
    std::string text = good;
    const std::size_t at = text.find("UT : 1,");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 6, bad);
    int line = 0;
    const std::string e = test::programReadError(Dialect::kTp, "r.ls", text, std::nullopt, &line);
    EXPECT_NE(e.find("is not a frame number (an integer 0 .. 99)"), std::string::npos) << e;
    EXPECT_GT(line, 0);
  }
}

/// The sample R-2000iC program with `from` (at `at` characters past the first `anchor`)
/// replaced by `to`, parsed: its InputError text (or "(accepted)").
std::string tpError(const std::string& anchor, std::size_t at, std::size_t from,
                    const std::string& to) {
  std::string text = test::readFile(test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls");
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

TEST(TpReader, ALineWhoseNumberIsDamagedIsAnError) {
  // `inf:L P[591] ...` (the line number damaged) must not be skipped: a motion dropped in silence
  const std::string e = tpError("1182:L P[591]", 0, 4, "inf");
  EXPECT_NE(e.find("a /MN line starts with its line number"), std::string::npos) << e;
  EXPECT_NE(e.find("got 'inf'"), std::string::npos) << e;
}

TEST(TpReader, ASpeedWithoutItsNumberIsAnError) {
  // `nanmm/sec` must not leave the move without a speed (the drill feed is recognised from it)
  const std::string e = tpError("L P[306] 20mm/sec", 9, 2, "nan");
  EXPECT_NE(e.find("speed 'nanmm/sec' is not a number with its unit"), std::string::npos) << e;
}

TEST(TpReader, ASpeedWithAnExponentAndASpeedOver10MetresPerSecondAreErrors) {
  // `L P[374] 1e300mm/sec` must not be read as 1 mm/sec (the number's leading digit; the rest
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
}

/// The unresolved references of `p` that are positions (not the controller's frames).
std::vector<postproc::Unresolved> positionsUnresolved(const postproc::Program& p) {
  std::vector<postproc::Unresolved> out;
  for (const postproc::Unresolved& u : p.unresolved)
    if (u.ref.rfind("UFRAME", 0) != 0 && u.ref.rfind("UTOOL", 0) != 0) out.push_back(u);
  return out;
}

TEST(TpReader, AMotionToAPositionRoprecCannotKnowIsReportedAtItsLine) {
  // `L P[inf] ...` (the index damaged), a register-indexed position `P[R[4]]` and a position
  // register `PR[3]`, whose values live in the controller, must not go to no position without
  // a word (the hole they approach would drop out of the job): each is an unresolved reference
  // with its line.
  const std::string text =
      test::readFile(test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls");
  const std::string anchor = " 113:L P[56] 250mm/sec CNT10 ;";
  ASSERT_NE(text.find(anchor), std::string::npos);
  const std::string dir = test::tempDir("tp-runtime-position");
  for (const std::string ref : {"P[inf]", "P[R[4]]", "PR[3]"}) {
    SCOPED_TRACE(ref);
    std::string t = text;
    t.replace(t.find(anchor), anchor.size(), " 113:L " + ref + " 250mm/sec CNT10 ;");
    const postproc::Program p = postproc::parseProgram(postproc::Dialect::kTp, "r.ls", t);
    ASSERT_EQ(positionsUnresolved(p).size(), 1U);
    EXPECT_EQ(positionsUnresolved(p)[0].ref, ref);
    EXPECT_EQ(positionsUnresolved(p)[0].line, 132);
    test::writeFile(dir + "/r.ls", t);
    const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                   "/samples/cells/housing-r2000.xml' '" + dir +
                                   "/r.ls' --frame cell --tool cell --json '" + dir + "/p.json'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("roprec: warning: unresolved " + ref + " (" + dir + "/r.ls:132): "),
              std::string::npos)
        << r.err;
  }
  // the sample itself has none (only its controller frames UFRAME[1] and UTOOL[1])
  EXPECT_TRUE(
      positionsUnresolved(postproc::parseProgram(postproc::Dialect::kTp, "r.ls", text)).empty());
}

/// A TP program: `mn` (the /MN lines, numbered here) and positions P[1] (UT : ut1), P[2] (UT :
/// ut2), each "" to leave its UT out.
std::string toolProgram(const std::vector<std::string>& mn, const std::string& ut1,
                        const std::string& ut2) {
  std::string t = "/PROG  TOOLS\r\n/MN\r\n";
  for (size_t i = 0; i < mn.size(); ++i)
    t += "   " + std::to_string(i + 1) + ":" + mn[i] + " ;\r\n";
  auto ufut = [](const std::string& ut) {
    return ut.empty() ? std::string("UF : 0") : "UF : 0, UT : " + ut;
  };
  return t + "/POS\r\n" + record("P[1]", ufut(ut1), "N U T, 0, 0, 0", "284.000") +
         record("P[2]", ufut(ut2), "N U T, 0, 0, 0", "234.000") + "/END\r\n";
}

std::string toolOf(const postproc::Program& p, size_t motion) {
  const int t = p.motions[motion].tool;
  return t < 0 ? std::string() : p.frames[static_cast<size_t>(t)].ref;
}

TEST(TpReader, UtoolNumSelectsTheToolOfPositionsWithoutTheirOwn) {
  const std::string text = toolProgram(
      {"UTOOL_NUM=2", "J P[1] 10% FINE", "UTOOL_NUM=3", "L P[2] 20mm/sec FINE"}, "", "");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kTp, "t.ls", text);
  ASSERT_EQ(p.motions.size(), 2U);
  EXPECT_EQ(toolOf(p, 0), "UTOOL[2]");
  EXPECT_EQ(toolOf(p, 1), "UTOOL[3]");
  EXPECT_TRUE(p.tool_conflicts.empty());
  std::string err;
  roundTripAndInspect("tp-utool", text, &err);
}

TEST(TpReader, APositionTaughtInAnotherToolThanTheActiveOneIsAConflictAtItsMotion) {
  // UTOOL_NUM=1, then P[2] taught with UT : 2: the controller stops at line 3's motion; the
  // position's UT stays its tool, the reader lists the conflict (convert and inspect still work)
  const std::string text =
      toolProgram({"UTOOL_NUM=1", "J P[1] 10% FINE", "L P[2] 20mm/sec FINE"}, "1", "2");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kTp, "t.ls", text);
  ASSERT_EQ(p.motions.size(), 2U);
  EXPECT_EQ(toolOf(p, 0), "UTOOL[1]");
  EXPECT_EQ(toolOf(p, 1), "UTOOL[2]");
  ASSERT_EQ(p.tool_conflicts.size(), 1U);
  EXPECT_EQ(p.tool_conflicts[0].motion, 1);
  EXPECT_EQ(p.tool_conflicts[0].selected, "UTOOL[1]");
  EXPECT_EQ(p.tool_conflicts[0].taught, "UTOOL[2]");
  EXPECT_EQ(p.tool_conflicts[0].selected_line, 3);  // /PROG, /MN, then line 1
  std::string err;
  roundTripAndInspect("tp-utool-conflict", text, &err);
}

TEST(TpReader, UtoolNumFromARegisterIsUnresolvedOnceAndThePositionsUtIsTheTool) {
  const std::string text = toolProgram(
      {"UTOOL_NUM=R[4]", "J P[1] 10% FINE", "UTOOL_NUM=R[5]", "L P[2] 20mm/sec FINE"}, "2", "");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kTp, "t.ls", text);
  EXPECT_EQ(toolOf(p, 0), "UTOOL[2]");
  EXPECT_EQ(toolOf(p, 1), "");  // nothing known: the job's tool (as a program naming none)
  EXPECT_TRUE(p.tool_conflicts.empty());
  int noted = 0;
  for (const postproc::Unresolved& u : p.unresolved)
    noted += u.ref.rfind("UTOOL_NUM", 0) == 0 && u.line == 3 &&
             u.what.find("register") != std::string::npos;
  EXPECT_EQ(noted, 1);
}

TEST(TpReader, APredictionOfAProgramWithAToolConflictIsRefusedAtTheMotion) {
  const std::string dir = test::tempDir("tp-utool-predict");
  test::writeFile(dir + "/j.ls", toolProgram({"UTOOL_NUM=1", "J P[1] 10% FINE",
                                              "L P[2] 2mm/sec FINE", "L P[1] 250mm/sec FINE"},
                                             "1", "2"));
  const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                 "/samples/cells/housing-r2000.xml' '" + dir +
                                 "/j.ls' --frame cell --tool cell --json '" + dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir + "/j.ls:5: the motion's position was taught in tool 2 (UT : 2) but "
                             "UTOOL_NUM=1 is active (line 3)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("Hint: select its tool with UTOOL_NUM=2"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
