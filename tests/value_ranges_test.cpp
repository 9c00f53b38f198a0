// Issue 13, findings of scripts/mutation-campaign.py on programs and the cell's tool: values a
// reader accepted although no controller or tool could mean them, each once a silent change of
// the numbers with exit 0:
// * KRL `.dat`: an E6POS angle B of 1e300 (verify ran on it); a retract at Z 1e300;
// * RAPID: a zero quaternion (taken as "no rotation"); an inline robtarget component `inf`/`nan`
//   (not a RAPID number: an identifier the module does not declare) at a hole's bottom, which
//   cut the drill cycle short so that the approach point became the "bottom"; a robconf `nan`,
//   read as configuration 0;
// * cell: `<drill stickout_mm="1e-300">`, which removed the drill's compliance from U_mach.
#include "postproc/value_ranges.hpp"

#include <gtest/gtest.h>

#include <string>

#include "compensator/process/process_spec.hpp"
#include "compensator/support/error.hpp"
#include "postproc/drill.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

using postproc::Dialect;
using postproc::parseProgram;

/// The InputError text of parsing (or "(accepted)"), with the line it names.
std::string errorOf(Dialect d, const std::string& path, const std::string& text,
                    std::optional<std::string> dat = std::nullopt, int* line = nullptr) {
  try {
    (void)parseProgram(d, path, text, std::move(dat), "p.dat");
  } catch (const InputError& e) {
    if (line) *line = e.line();
    return e.file() + ": " + e.message();
  }
  return "(accepted)";
}

const char* const kKrlSrc =
    "DEF p( )\n"
    "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
    "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n"
    "PTP XP1\n"
    "LIN {X 150.000,Y 0.000,Z 214.000,A 0.000,B 0.000,C 180.000}\n"
    "LIN {X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000}\n"
    "END\n";
const char* const kKrlDat =
    "DEFDAT p\n"
    "DECL E6POS XP1={X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000,S 2,T 2}\n"
    "ENDDAT\n";

TEST(ValueRanges, KrlAbsurdAngleInTheDatIsRefusedAtItsLine) {
  std::string dat = kKrlDat;
  dat.replace(dat.find("B 0.000"), 7, "B 1e300");
  int line = 0;
  const std::string e = errorOf(Dialect::kKrl, "p.src", kKrlSrc, dat, &line);
  EXPECT_EQ(e.rfind("p.dat: target XP1: angle B = 1e+300 is out of range", 0), 0u) << e;
  EXPECT_EQ(line, 2);
  EXPECT_EQ(errorOf(Dialect::kKrl, "p.src", kKrlSrc, std::string(kKrlDat)), "(accepted)");
}

TEST(ValueRanges, KrlRetractAtZ1e300IsRefused) {
  std::string src = kKrlSrc;
  src.replace(src.find("Z 284.000,A 0.000,B 0.000,C 180.000}\nEND"), 9, "Z 1e300");
  int line = 0;
  const std::string e = errorOf(Dialect::kKrl, "p.src", src, std::string(kKrlDat), &line);
  EXPECT_NE(e.find("position z (mm) = 1e+300 is out of range"), std::string::npos) << e;
  EXPECT_EQ(line, 6);
}

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

TEST(ValueRanges, RapidZeroQuaternionIsRefusedAndUnusedAxesAreAccepted) {
  EXPECT_EQ(errorOf(Dialect::kRapid, "m.mod", rapidCycle("0,1,0,0", "0,0,0,0")), "(accepted)");
  int line = 0;
  const std::string e =
      errorOf(Dialect::kRapid, "m.mod", rapidCycle("0,0,0,0", "0,0,0,0"), std::nullopt, &line);
  EXPECT_NE(e.find("has norm 0, not 1"), std::string::npos) << e;
  EXPECT_EQ(line, 7);
  const std::string x =
      errorOf(Dialect::kRapid, "m.mod", rapidCycle("0,1,0,0", "0,0,0,0", "8E+09"));
  EXPECT_NE(x.find("external axis 1 = 8e+09 is out of range"), std::string::npos) << x;
}

TEST(ValueRanges, AHoleBottomRoprecCannotEvaluateIsNotTakenForTheApproachPoint) {
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

TEST(ValueRanges, ARobconfRoprecCannotEvaluateStatesNoConfiguration) {
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

TEST(ValueRanges, PredictWarnsAboutTheUnresolvedComponentOnStderr) {
  const std::string dir = test::tempDir("value_ranges");
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

TEST(ValueRanges, DrillStickoutMustBeAtLeastTheDiameter) {
  const auto spec = [](const std::string& stickout) {
    return "<process type=\"drilling\">\n"
           "  <drill diameter_mm=\"10\" stickout_mm=\"" +
           stickout +
           "\"/>\n"
           "  <cut feed_mm_per_rev=\"0.2\" spindle_rpm=\"3000\"/>\n"
           "  <material name=\"Al 6061-T6\"/>\n"
           "</process>\n";
  };
  EXPECT_NO_THROW(parseProcess(parseXmlText(spec("34"), "cell.xml")));
  for (const char* bad : {"1e-300", "5", "1e300"}) {
    try {
      (void)parseProcess(parseXmlText(spec(bad), "cell.xml"));
      ADD_FAILURE() << "stickout " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 2);
      EXPECT_NE(std::string(e.what()).find("stickout_mm"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("plausible range 10 .. 1000"), std::string::npos)
          << e.what();
    }
  }
}

TEST(ValueRanges, FanucFrameNumbersAreSmallIntegers) {
  const std::string path = test::sourceDir() + "/samples/emotor-housing/housing_r2000.ls";
  const std::string good = test::readFile(path);
  EXPECT_EQ(errorOf(Dialect::kTp, "r.ls", good), "(accepted)");
  for (const char* bad : {"UT : 1e300", "UT : 1.5", "UT : -1"}) {
    std::string text = good;
    const std::size_t at = text.find("UT : 1,");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 6, bad);
    int line = 0;
    const std::string e = errorOf(Dialect::kTp, "r.ls", text, std::nullopt, &line);
    EXPECT_NE(e.find("is not a frame number (an integer 0 .. 99)"), std::string::npos) << e;
    EXPECT_GT(line, 0);
  }
}

}  // namespace
}  // namespace roprec
