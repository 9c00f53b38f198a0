// The RAPID reader (postproc/rapid.cpp) on syntax the controller accepts: labels before any
// statement (also before ENDPROC, IF, WHILE, TEST), the FlexPendant's `<SMT>` placeholder, and
// speeds no motion can run at. Each program is written for the test; it must round-trip byte for
// byte through `roprec convert` and `roprec inspect` must describe its motions. A line missing its
// ';' is a syntax error with its line (it must not swallow the next instruction); inline targets
// whose components are named constants round-trip, resolve where the value is known and are
// reported where not; a zero quaternion or an absurd external axis is refused at its line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "compensator/support/error.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"
#include "tests/support/input_errors.hpp"
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

TEST(RapidReader, LineMissingItsSemicolonIsASyntaxErrorWithTheLine) {
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

TEST(RapidReader, StatementsContinuedOverLinesStillRead) {
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

TEST(RapidReader, InlineTargetsWithNamedConstantsRoundTripAndResolve) {
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

TEST(RapidReader, InlineTargetsWithNamedConstantsThroughTheCli) {
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

using postproc::Dialect;
using postproc::parseProgram;

// A RAPID drill cycle in a work object: approach 48 mm above on the axis at v250, the bottom at
// the feed, retract.
std::string rapidCycle(const std::string& bottom_rot, const std::string& bottom_conf,
                       const std::string& extax = "9E+09") {
  const std::string tail = ",[" + extax + ",9E+09,9E+09,9E+09,9E+09,9E+09]]";
  return "MODULE M\n"
         "  PERS tooldata tS:=[TRUE,[[0,0,320],[1,0,0,0]],[10,[0,0,100],[1,0,0,0],0,0,0]];\n"
         "  PERS wobjdata wW:=[FALSE,TRUE,\"\",[[1350,0,300],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
         "  PROC main()\n"
         "    MoveJ [[150,0,284],[0,1,0,0],[0,0,0,0]" +
         tail +
         ",v1000,z10,tS\\WObj:=wW;\n"
         "    MoveL [[150,0,234],[0,1,0,0],[0,0,0,0]" +
         tail +
         ",v250,z1,tS\\WObj:=wW;\n"
         "    MoveL [[150,0,214],[" +
         bottom_rot + "],[" + bottom_conf + "]" + tail +
         ",v2,fine,tS\\WObj:=wW;\n"
         "    MoveL [[150,0,284],[0,1,0,0],[0,0,0,0]" +
         tail +
         ",v250,z10,tS\\WObj:=wW;\n"
         "  ENDPROC\n"
         "ENDMODULE\n";
}

TEST(RapidReader, AZeroQuaternionAndAnAbsurdExternalAxisAreRefused) {
  EXPECT_EQ(test::programReadError(Dialect::kRapid, "m.mod", rapidCycle("0,1,0,0", "0,0,0,0")),
            "(accepted)");
  int line = 0;
  const std::string e = test::programReadError(
      Dialect::kRapid, "m.mod", rapidCycle("0,0,0,0", "0,0,0,0"), std::nullopt, &line);
  EXPECT_NE(e.find("has norm 0, not 1"), std::string::npos) << e;
  EXPECT_EQ(line, 7);
  const std::string x =
      test::programReadError(Dialect::kRapid, "m.mod", rapidCycle("0,1,0,0", "0,0,0,0", "8E+09"));
  EXPECT_NE(x.find("external axis 1 = 8e+09 is out of range"), std::string::npos) << x;
}

TEST(RapidReader, AHoleBottomRoprecCannotEvaluateIsNotTakenForTheApproachPoint) {
  const auto holes = [](const std::string& text) {
    return postproc::recognizeHoles(parseProgram(Dialect::kRapid, "m.mod", text));
  };
  const auto good = holes(rapidCycle("0,1,0,0", "0,0,0,0"));
  ASSERT_EQ(good.size(), 1u);
  EXPECT_NEAR(good[0].depth * 1e3, 20.0, 1e-9);
  // `inf` is not a RAPID number: an identifier the module does not declare, value unknown
  const postproc::Program p =
      parseProgram(Dialect::kRapid, "m.mod", rapidCycle("0,inf,0,0", "0,0,0,0"));
  EXPECT_TRUE(postproc::recognizeHoles(p).empty());
  ASSERT_FALSE(p.unresolved.empty());
  EXPECT_EQ(p.unresolved[0].ref, "inf");
  EXPECT_EQ(p.unresolved[0].line, 7);
}

TEST(RapidReader, ARobconfRoprecCannotEvaluateStatesNoConfiguration) {
  const postproc::Program known =
      parseProgram(Dialect::kRapid, "m.mod", rapidCycle("0,1,0,0", "0,-1,2,0"));
  const postproc::Program unknown =
      parseProgram(Dialect::kRapid, "m.mod", rapidCycle("0,1,0,0", "0,nan,2,0"));
  const auto bottom = [](const postproc::Program& p) {
    return p.targets()[static_cast<std::size_t>(postproc::recognizeHoles(p).at(0).bottom_target)];
  };
  EXPECT_TRUE(bottom(known).config.present());
  EXPECT_EQ(bottom(known).config.cf[1], -1);
  EXPECT_FALSE(bottom(unknown).config.present());
}

TEST(RapidReader, PredictWarnsAboutAnUnresolvedTargetComponentOnStderr) {
  const std::string dir = test::tempDir("rapid-unresolved");
  // a second, complete cycle after the one with the unknown bottom: one hole predicted, the
  // unresolved component named as a warning
  std::string text = rapidCycle("0,inf,0,0", "0,0,0,0");
  const std::string good = rapidCycle("0,1,0,0", "0,0,0,0");
  const std::size_t b = good.find("    MoveJ"), e = good.find("  ENDPROC");
  text.insert(text.find("  ENDPROC"), good.substr(b, e - b));
  test::writeFile(dir + "/m.mod", text);
  const std::string cell = test::sourceDir() + "/samples/cells/housing-irb6640.xml";
  const auto r = test::runRoprec("predict --cell '" + cell + "' '" + dir + "/m.mod' --json '" +
                                 dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("roprec predict: 1 holes"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("warning: unresolved inf (" + dir + "/m.mod:7): robtarget rot component"),
            std::string::npos)
      << r.err;
  // the only cycle cut short: the error names the reference
  test::writeFile(dir + "/one.mod", rapidCycle("0,inf,0,0", "0,0,0,0"));
  const auto one = test::runRoprec("predict --cell '" + cell + "' '" + dir + "/one.mod' --json '" +
                                   dir + "/q.json'");
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_NE(one.err.find("the first 'inf' at line 7"), std::string::npos) << one.err;
}

// Declared robtargets are looked up by name case-insensitively (RAPID names are), also inside
// Offs; a name declared twice resolves to its later declaration from there on.
TEST(RapidReader, DeclaredTargetsResolveCaseInsensitivelyTheLaterDeclarationWins) {
  const std::string text =
      "MODULE names\n"
      "  CONST robtarget pHole:=[[1,2,3],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,"
      "9E+09]];\n"
      "  CONST robtarget pOther:=[[4,5,6],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,"
      "9E+09]];\n"
      "  PROC main()\n"
      "    MoveL PHOLE,v100,fine,tool0;\n"
      "    MoveL Offs(phole,0,0,10),v100,fine,tool0;\n"
      "  ENDPROC\n"
      "  CONST robtarget POTHER:=[[7,8,9],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,"
      "9E+09]];\n"
      "  PROC second()\n"
      "    MoveL pother,v100,fine,tool0;\n"
      "  ENDPROC\n"
      "ENDMODULE\n";
  const postproc::Program p = parseProgram(Dialect::kRapid, "names.mod", text);
  ASSERT_EQ(p.targets().size(), 3U);
  ASSERT_EQ(p.motions.size(), 3U);
  EXPECT_EQ(p.motions[0].target, 0);
  EXPECT_EQ(p.motions[1].target, 0);
  EXPECT_TRUE(p.motions[1].has_offset);
  EXPECT_EQ(p.motions[2].target, 2);  // the later POTHER, not pOther
  EXPECT_EQ(p.targets()[2].name, "POTHER");
  EXPECT_DOUBLE_EQ(p.targets()[2].pos[0].value, 7.0);
  EXPECT_TRUE(p.unresolved.empty());
}

// A robtarget declared in plain numbers on one line (read without a parse tree) gives the
// target the general reader gives the same numbers spread over lines with a comment.
TEST(RapidReader, APlainDeclaredTargetReadsAsTheGeneralPathReadsIt) {
  const std::string plain =
      "MODULE m\n"
      "  CONST robtarget p1:=[[-359.4,+299.4,3e2],[0,1,0,0],[-1,0,-2,1],[9E+09,9E+09,9E+09,"
      "9E+09,9E+09,12.5]];\n"
      "  PROC main()\n"
      "    MoveL p1,v100,fine,tool0;\n"
      "  ENDPROC\n"
      "ENDMODULE\n";
  std::string spread = plain;
  spread.replace(spread.find("[0,1,0,0]"), 9, "[0,1,0,\n  0]");
  spread.replace(spread.find("[-1,0,-2,1]"), 11, "[-1,0,-2,1] ! robconf\n  ");
  const postproc::Program a = parseProgram(Dialect::kRapid, "a.mod", plain);
  const postproc::Program b = parseProgram(Dialect::kRapid, "b.mod", spread);
  ASSERT_EQ(a.targets().size(), 1U);
  ASSERT_EQ(b.targets().size(), 1U);
  const postproc::Target& ta = a.targets()[0];
  const postproc::Target& tb = b.targets()[0];
  EXPECT_EQ(ta.name, tb.name);
  EXPECT_EQ(ta.line, tb.line);
  EXPECT_EQ(ta.config.vendor, tb.config.vendor);
  EXPECT_EQ(ta.config.cf, tb.config.cf);
  const auto text = [](const postproc::Program& p, const postproc::NumberField& f) {
    return std::string(p.files[0].bytes.substr(f.offset, f.length));
  };
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(ta.pos[k].value, tb.pos[k].value);
    EXPECT_EQ(text(a, ta.pos[k]), text(b, tb.pos[k]));
  }
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(ta.rot[k].value, tb.rot[k].value);
    EXPECT_EQ(ta.cf_fields[k].value, tb.cf_fields[k].value);
  }
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(ta.ext[k].value, tb.ext[k].value);
  EXPECT_EQ(text(a, ta.pos[1]), "+299.4");
  EXPECT_DOUBLE_EQ(ta.pos[2].value, 300.0);
  EXPECT_EQ(ta.config.cf[0], -1);
  EXPECT_EQ(a.motions[0].target, 0);
  EXPECT_EQ(b.motions[0].target, 0);
}

}  // namespace
}  // namespace roprec
