// The RAPID reader (postproc/rapid.cpp) on syntax the controller accepts: labels before any
// statement (also before ENDPROC, IF, WHILE, TEST), the FlexPendant's `<SMT>` placeholder, and
// speeds no motion can run at. Each program is written for the test; it must round-trip byte for
// byte through `roprec convert` and `roprec inspect` must describe its motions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using nlohmann::json;

/// Writes `text` as `name` in a fresh directory, checks that `roprec convert` writes it back
/// byte for byte, and returns `roprec inspect`'s JSON (null when inspect fails).
json roundTripAndInspect(const std::string& tag, const std::string& name, const std::string& text) {
  const std::string dir = test::tempDir(tag);
  const std::string path = dir + "/" + name;
  test::writeFile(path, text);
  const auto c = test::runRoprec("convert '" + path + "' -o '" + dir + "/copy.mod'");
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(test::readFile(dir + "/copy.mod"), text);
  EXPECT_EQ(c.err.find("missing ';'"), std::string::npos) << c.err;
  const auto i = test::runRoprec("inspect '" + path + "' --all");
  EXPECT_EQ(i.exit_code, 0) << i.err;
  return i.exit_code == 0 ? json::parse(i.out) : json();
}

const char* const kTarget =
    "[[150,0,284],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]";

std::string moveL(const std::string& z, const std::string& speed) {
  std::string t = kTarget;
  t.replace(t.find("284"), 3, z);
  return "MoveL " + t + "," + speed + ",fine,tool0;";
}

TEST(RapidReader, LabelsBeforeCompoundStatementsAndEndprocRead) {
  const std::string text =
      "MODULE labels\n"
      "  PROC main()\n"
      "    VAR num n:=0;\n"
      "  start:\n"
      "    IF n > 2 THEN\n"
      "      GOTO lbl_end;\n"
      "    ENDIF\n"
      "  again:\n"
      "    WHILE n < 3 DO\n"
      "      n := n + 1;\n"
      "    ENDWHILE\n"
      "  pick: " +
      moveL("284", "v100") +
      "\n"
      "  choose:\n"
      "    TEST n\n"
      "    CASE 3:\n"
      "      " +
      moveL("234", "v20") +
      "\n"
      "    ENDTEST\n"
      "  lbl_end:\n"
      "  ENDPROC\n"
      "ENDMODULE\n";
  const json j = roundTripAndInspect("rapid-labels", "labels.mod", text);
  ASSERT_TRUE(j.is_object());
  // the motion after `pick:` on the same line is a motion, at its line, with its speed
  ASSERT_EQ(j["motions"].size(), 2U);
  EXPECT_EQ(j["motions"][0]["instruction"], "MoveL");
  EXPECT_EQ(j["motions"][0]["line"], 12);
  EXPECT_DOUBLE_EQ(j["motions"][0]["speed_mm_s"].get<double>(), 100.0);
  EXPECT_EQ(j["motions"][1]["line"], 16);
  EXPECT_DOUBLE_EQ(j["motions"][1]["speed_mm_s"].get<double>(), 20.0);
  EXPECT_EQ(j["targets"][1]["native"]["z"], 234);
}

TEST(RapidReader, EmptyRoutineWithTheSmtPlaceholderReads) {
  const std::string text =
      "MODULE smt\n"
      "  PROC empty()\n"
      "    <SMT>\n"
      "  ENDPROC\n"
      "  PROC main()\n"
      "    " +
      moveL("284", "v100") +
      "\n"
      "  ENDPROC\n"
      "ENDMODULE\n";
  const json j = roundTripAndInspect("rapid-smt", "smt.mod", text);
  ASSERT_TRUE(j.is_object());
  ASSERT_EQ(j["motions"].size(), 1U);
  EXPECT_EQ(j["motions"][0]["line"], 6);
  EXPECT_TRUE(j["unresolved"].empty());
}

TEST(RapidReader, ALabelDoesNotHideAMissingSemicolon) {
  // the strict check still holds after a label: a statement without its ';' swallows the next
  const std::string dir = test::tempDir("rapid-label-semicolon");
  std::string bad = moveL("284", "v100");
  bad.pop_back();
  test::writeFile(dir + "/m.mod", "MODULE m\n  PROC main()\n  l1: " + bad + "\n    " +
                                      moveL("234", "v20") + "\n  ENDPROC\nENDMODULE\n");
  const auto r = test::runRoprec("inspect '" + dir + "/m.mod' --all");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("m.mod:3: missing ';'"), std::string::npos) << r.err;
}

TEST(RapidReader, ASpeedOfZeroOrBelowIsAnInputErrorAtItsLine) {
  const std::string dir = test::tempDir("rapid-zero-speed");
  for (const std::string speed : {"[0,500,5000,1000]", "v100\\V:=0", "[-20,500,5000,1000]"}) {
    SCOPED_TRACE(speed);
    test::writeFile(dir + "/m.mod", "MODULE m\n  PROC main()\n    " + moveL("284", "v100") +
                                        "\n    " + moveL("234", speed) +
                                        "\n  ENDPROC\nENDMODULE\n");
    const auto r = test::runRoprec("convert '" + dir + "/m.mod' -o '" + dir + "/out.mod'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("m.mod:4: MoveL: speed"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("hint:"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace roprec
