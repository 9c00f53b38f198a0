// Issue 13 (programs): RAPID syntax the reader must not get silently wrong or refuse.
//  * a line missing its ';' is a syntax error with its line (it used to swallow the next
//    instruction and drop a hole's bottom point: H3 predicted 2 mm above the part);
//  * inline jointtargets/robtargets whose components are named constants or expressions declared
//    in the module round-trip byte for byte, are resolved where the value is known and reported
//    (not refused) where it is not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "compensator/support/error.hpp"
#include "postproc/program.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> v;
  std::string l;
  while (std::getline(in, l)) v.push_back(l);
  return v;
}

/// The sample RAPID job cut to its first three holes (lines 1..27); `drop_semicolon_line` > 0
/// removes the ';' that ends that line.
std::string threeHoleModule(const std::string& dir, int drop_semicolon_line) {
  const auto src = lines(test::sourceDir() + "/samples/emotor-housing/housing_irb6640.mod");
  std::string text;
  for (int i = 1; i <= 27; ++i) {
    std::string l = src[static_cast<size_t>(i - 1)];
    if (i == drop_semicolon_line) {
      EXPECT_EQ(l.back(), ';');
      l.pop_back();
    }
    text += l + "\n";
  }
  text += "  ENDPROC\nENDMODULE\n";
  const std::string path =
      dir + (drop_semicolon_line > 0 ? "/missing_semicolon.mod" : "/three_holes.mod");
  test::writeFile(path, text);
  return path;
}

TEST(RapidSyntax, LineMissingItsSemicolonIsASyntaxErrorWithTheLine) {
  const std::string dir = test::tempDir("rapid_semicolon");
  const std::string cell = test::sourceDir() + "/samples/cells/housing-irb6640.xml";
  const std::string good = threeHoleModule(dir, 0);
  const auto ok = test::runRoprec("predict --cell '" + cell + "' '" + good + "' --quiet --json '" +
                                  dir + "/good.json'");
  ASSERT_LE(ok.exit_code, 1) << ok.err;
  // line 25 is T003's drill point (the bottom); without its ';' it would swallow `WaitTime 0.3;`
  const std::string bad = threeHoleModule(dir, 25);
  const auto r = test::runRoprec("predict --cell '" + cell + "' '" + bad + "' --quiet --json '" +
                                 dir + "/bad.json' --report '" + dir + "/bad.html'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("missing_semicolon.mod:25: missing ';'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/bad.json"));
  EXPECT_FALSE(fs::exists(dir + "/bad.html"));
  const auto c =
      test::runRoprec("compensate --cell '" + cell + "' '" + bad + "' -o '" + dir + "/out.mod'");
  EXPECT_EQ(c.exit_code, 2) << c.err;
  EXPECT_FALSE(fs::exists(dir + "/out.mod"));
  // the reader itself
  try {
    postproc::readProgram(bad);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 25);
  }
}

TEST(RapidSyntax, StatementsContinuedOverLinesStillRead) {
  const std::string text =
      "MODULE m\n"
      "  VAR num n := 1;\n"
      "  PROC main()\n"
      "    n := n\n"
      "      + 2;\n"
      "    MoveL [[1,2,3],[1,0,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],\n"
      "      v100, fine, tool0\n"
      "      \\WObj:=wobj0;\n"
      "    IF n > 2\n"
      "      AND n < 5 THEN\n"
      "      n := 0;\n"
      "    ENDIF\n"
      "  ENDPROC\n"
      "ENDMODULE\n";
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kRapid, "c.mod", text);
  EXPECT_EQ(p.motions.size(), 1U);
  EXPECT_EQ(postproc::renderFiles(p)[0], text);
}

const char* kNamedModule =
    "MODULE mTrack\n"
    "  CONST num Shift_Track := 250;\n"
    "  CONST num nHalf := Shift_Track / 2 - 5;\n"
    "  VAR num nRuntime;\n"
    "  PROC main()\n"
    "    MoveAbsJ [[-90,0,0,0,0,0],[Shift_Track,9E+09,9E+09,9E+09,9E+09,9E+09]]\\NoEOffs, v1000, "
    "z50, tool0;\n"
    "    MoveAbsJ [[-90,0,nHalf,0,-(nHalf+5),0],[nRuntime,9E+09,9E+09,9E+09,9E+09,9E+09]], v1000, "
    "z50, tool0;\n"
    "    MoveL [[1000,Shift_Track,800],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]], "
    "v100, fine, tool0;\n"
    "  ENDPROC\n"
    "ENDMODULE\n";

TEST(RapidSyntax, InlineTargetsWithNamedConstantsRoundTripAndResolve) {
  const postproc::Program p =
      postproc::parseProgram(postproc::Dialect::kRapid, "track.mod", kNamedModule);
  EXPECT_EQ(postproc::renderFiles(p)[0], kNamedModule);
  ASSERT_EQ(p.targets().size(), 3U);
  const postproc::Target& j1 = p.targets()[0];
  EXPECT_EQ(p.exprText(j1.ext[0]), "Shift_Track");
  EXPECT_TRUE(j1.ext[0].expr_known);
  EXPECT_DOUBLE_EQ(j1.ext[0].value, 250.0);
  const postproc::Target& j2 = p.targets()[1];
  EXPECT_DOUBLE_EQ(j2.joints[2].value, 120.0);  // 250/2 - 5
  EXPECT_DOUBLE_EQ(j2.joints[4].value, -125.0);
  EXPECT_EQ(postproc::targetJointsDeg(j2).size(), 6U);
  EXPECT_FALSE(j2.ext[0].expr_known);  // a variable without value: reported
  bool reported = false;
  for (const auto& u : p.unresolved) reported |= u.ref == "nRuntime" && u.line == 7;
  EXPECT_TRUE(reported);
  // a robtarget with a named component: its pose is known, but roprec does not rewrite names
  const postproc::Target& c = p.targets()[2];
  EXPECT_TRUE(postproc::targetComplete(c));
  EXPECT_NEAR(postproc::targetPose(p, c).translation().y(), 0.25, 1e-12);
  postproc::Program q = p;
  const postproc::EditResult er = postproc::replaceTargetPose(
      q, 2, postproc::targetPose(p, c) * Pose(Eigen::Translation3d(0, 0, 1e-3)));
  EXPECT_FALSE(er.ok);
  EXPECT_NE(er.reason.find("Shift_Track"), std::string::npos) << er.reason;
  EXPECT_EQ(postproc::renderFiles(q)[0], kNamedModule);
}

TEST(RapidSyntax, InlineTargetsWithNamedConstantsThroughTheCli) {
  const std::string dir = test::tempDir("rapid_named");
  const std::string in = dir + "/track.mod";
  test::writeFile(in, kNamedModule);
  const auto c = test::runRoprec("convert '" + in + "' -o '" + dir + "/copy.mod'");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(test::readFile(dir + "/copy.mod"), kNamedModule);
  const auto i = test::runRoprec("inspect '" + in + "' --all");
  ASSERT_EQ(i.exit_code, 0) << i.err;
  EXPECT_NE(i.out.find("nRuntime"), std::string::npos) << i.out;
}

}  // namespace
}  // namespace roprec
