// The FANUC TP reader (postproc/tp.cpp) on what controllers write: the end line of a point-logic
// sub-block, apostrophes in position comments, positions never taught (`UF : F`, `********`), a
// SCARA's CONFIG, and speeds no motion can run at. Each program is written for the test; it must
// round-trip byte for byte through `roprec convert` and `roprec inspect` must describe it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

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

}  // namespace
}  // namespace roprec
