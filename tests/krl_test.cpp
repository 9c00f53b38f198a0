// The KRL reader (postproc/krl.cpp) on what KUKA controllers run: a .src without a .dat whose
// targets are run-time locals (`DECL POS xHole,xProfile`) or globals of $config.dat (XHOME),
// unused placeholder points in a .dat, KSS 8 spline motions with WITH lists and SPLINE blocks,
// and path velocities no motion can run at. Each program is written for the test; it must
// round-trip byte for byte through `roprec convert` and `roprec inspect` must describe it.
// Values no controller could mean (a .dat angle or a position of 1e300, a $VEL.CP in mm/s) and a
// statement cut short are InputErrors at their own line.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "compensator/support/error.hpp"
#include "postproc/program.hpp"
#include "tests/support/input_errors.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Job {
  std::string dir;
  std::string src;
};

Job write(const std::string& tag, const std::string& src, const std::string& dat = "") {
  Job j{test::tempDir(tag), ""};
  j.src = j.dir + "/job.src";
  test::writeFile(j.src, src);
  if (!dat.empty()) test::writeFile(j.dir + "/job.dat", dat);
  return j;
}

json roundTripAndInspect(const Job& j, const std::string& src, const std::string& dat = "") {
  const auto c = test::runRoprec("convert '" + j.src + "' -o '" + j.dir + "/copy.src'");
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(test::readFile(j.dir + "/copy.src"), src);
  if (!dat.empty()) {
    EXPECT_EQ(test::readFile(j.dir + "/copy.dat"), dat);
  }
  EXPECT_EQ(c.err.find("missing .dat"), std::string::npos) << c.err;
  EXPECT_EQ(c.err.find("out of range"), std::string::npos) << c.err;
  const auto i = test::runRoprec("inspect '" + j.src + "'");
  EXPECT_EQ(i.exit_code, 0) << i.err;
  return i.exit_code == 0 ? json::parse(i.out) : json();
}

/// The unresolved entry of `ref` in inspect's JSON (null when absent).
json unresolvedOf(const json& j, const std::string& ref) {
  for (const json& u : j["unresolved"])
    if (u["ref"] == ref) return u;
  return json();
}

const char* const kNoDat =
    "DEF job( )\n"
    "DECL POS xHole,xProfile\n"
    "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
    "PTP XHOME\n"
    "xHole = {X 150.000,Y 0.000,Z 234.000,A 0.000,B 0.000,C 180.000}\n"
    "LIN xHole C_DIS\n"
    "LIN xProfile\n"
    "PTP XHOME\n"
    "END\n";

TEST(KrlReader, ASrcWithoutDatNamesItsRuntimeLocalsAndControllerGlobalsAsUnresolved) {
  const Job j = write("krl-nodat", kNoDat);
  const json r = roundTripAndInspect(j, kNoDat);
  ASSERT_TRUE(r.is_object());
  EXPECT_FALSE(fs::exists(j.dir + "/copy.dat"));
  ASSERT_EQ(r["motions"].size(), 4U);
  EXPECT_EQ(r["motions"][1]["derivation"], "runtime");
  EXPECT_EQ(r["motions"][0]["derivation"], "undeclared");
  const json hole = unresolvedOf(r, "xHole");
  ASSERT_FALSE(hole.is_null()) << r["unresolved"].dump();
  EXPECT_EQ(hole["line"], 6);
  EXPECT_NE(hole["what"].get<std::string>().find("declared without a value (" + j.src + ":2)"),
            std::string::npos)
      << hole.dump();
  EXPECT_FALSE(unresolvedOf(r, "xProfile").is_null());
  const json home = unresolvedOf(r, "XHOME");
  ASSERT_FALSE(home.is_null());
  EXPECT_EQ(home["line"], 4);  // once, at its first use
  EXPECT_NE(home["what"].get<std::string>().find("$config.dat"), std::string::npos);
  EXPECT_EQ(r["unresolved"].size(), 3U);
}

TEST(KrlReader, ASrcWithoutDatIsAnErrorOnlyWhereAJobNeedsItsTargets) {
  const Job j = write("krl-nodat-predict", kNoDat);
  const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                 "/samples/cells/housing-kr120.xml' '" + j.src + "' --json '" +
                                 j.dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no drill cycle recognised"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'XHOME'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(j.dir + "/p.json"));
}

const char* const kPlaceholderSrc =
    "DEF job( )\n"
    "PTP XP1 C_PTP\n"
    "LIN XP2\n"
    "END\n";
std::string placeholderDat(const std::string& used) {
  return "DEFDAT job\n"
         "DECL E6POS XP1={X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000,S 2,T 2}\n"
         "DECL E6POS XP2={X " +
         used +
         ",Y 0.000,Z 234.000,A 0.000,B 0.000,C 180.000,S 2,T 2}\n"
         "DECL E6POS Xp9={X 666666.688,Y 666666.688,Z 666666.688,A 0.0,B 0.0,C 0.0,S 2,T 2}\n"
         "ENDDAT\n";
}

TEST(KrlReader, AnUnusedPlaceholderPointIsOutsideTheRangeCheck) {
  const std::string dat = placeholderDat("150.000");
  const Job j = write("krl-placeholder", kPlaceholderSrc, dat);
  const json r = roundTripAndInspect(j, kPlaceholderSrc, dat);
  ASSERT_TRUE(r.is_object());
  ASSERT_EQ(r["targets"].size(), 3U);
  EXPECT_EQ(r["targets"][2]["name"], "Xp9");
  EXPECT_TRUE(r["targets"][2]["used_at_lines"].empty());
  // the same value at a point a motion moves to is still refused at its line
  const Job bad = write("krl-placeholder-used", kPlaceholderSrc, placeholderDat("666666.688"));
  const auto e = test::runRoprec("inspect '" + bad.src + "'");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_NE(e.err.find("job.dat:3: target XP2: position x (mm) = 666667 is out of range"),
            std::string::npos)
      << e.err;
}

// KSS 8 spline motions: the hole's clearance, feed and retract in WITH lists (speed in m/s), an
// arc, and a SPLINE block whose segments blend up to its end.
const char* const kSplineSrc =
    "DEF job( )\n"
    "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
    "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n"
    "$VEL.CP = 0.25\n"
    "SPTP XP1 WITH $VEL_AXIS[1] = SVEL_JOINT(100.0) C_SPL\n"
    "SLIN XP2 WITH $VEL.CP = 0.25, $APO.CDIS = 5 C_SPL\n"
    "SPL XP3 WITH $VEL.CP = 0.002\n"
    "SLIN XP2 WITH $VEL = SVEL_CP(0.25, , LCPDAT1), $APO.CDIS = 2 C_SPL\n"
    "SCIRC XP4, XP5 WITH $VEL.CP = 0.1 C_SPL\n"
    "SPLINE WITH $VEL.CP = 0.05\n"
    "  SPL XP6\n"
    "  SLIN XP7\n"
    "ENDSPLINE\n"
    "LIN XP1 C_DIS\n"
    "END\n";

std::string point(const std::string& name, const std::string& x, const std::string& z) {
  return "DECL E6POS " + name + "={X " + x + ",Y 0.000,Z " + z +
         ",A 0.000,B 0.000,C 180.000,S 2,T 2,E1 0.0,E2 0.0,E3 0.0,E4 0.0,E5 0.0,E6 0.0}\n";
}

const std::string kSplineDat =
    "DEFDAT job\n" + point("XP1", "150.000", "284.000") + point("XP2", "150.000", "234.000") +
    point("XP3", "150.000", "214.000") + point("XP4", "160.000", "284.000") +
    point("XP5", "170.000", "284.000") + point("XP6", "200.000", "284.000") +
    point("XP7", "250.000", "284.000") + "ENDDAT\n";

TEST(KrlReader, SplineWithListsCarryTheirSpeedAndApproximation) {
  const Job j = write("krl-spline", kSplineSrc, kSplineDat);
  const json r = roundTripAndInspect(j, kSplineSrc, kSplineDat);
  ASSERT_TRUE(r.is_object());
  const json& m = r["motions"];
  ASSERT_EQ(m.size(), 8U);
  const struct {
    const char* instruction;
    double speed;  // mm/s, < 0: none
    const char* zone;
    bool fine;
  } expected[] = {{"SPTP", -1, "C_SPL", false},   {"SLIN", 250, "C_SPL", false},
                  {"SPL", 2, "", true},           {"SLIN", 250, "C_SPL", false},
                  {"SCIRC", 100, "C_SPL", false}, {"SPL", 50, "", false},
                  {"SLIN", 50, "", true},         {"LIN", 250, "C_DIS", false}};
  for (std::size_t k = 0; k < m.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(m[k]["instruction"], expected[k].instruction);
    if (expected[k].speed < 0) {
      EXPECT_FALSE(m[k].contains("speed_mm_s"));
    } else {
      EXPECT_DOUBLE_EQ(m[k]["speed_mm_s"].get<double>(), expected[k].speed);
    }
    EXPECT_EQ(m[k]["zone"], expected[k].zone);
    EXPECT_EQ(m[k]["fine"], expected[k].fine);
  }
  // the WITH speeds make the feed: approach at 250 mm/s to Z 234, feed at 2 mm/s to Z 214
  ASSERT_EQ(r["holes"].size(), 1U);
  const json& h = r["holes"][0];
  EXPECT_NEAR(h["depth_mm"].get<double>(), 20.0, 1e-9);
  EXPECT_EQ(h["surface"], "start of the feed move");
  EXPECT_EQ(h["evidence"][0], "feed slower than approach/retract");
}

TEST(KrlReader, ASplineBlockSpeedRoprecCannotEvaluateMakesItsSegmentsSpeedsUnknown) {
  // not the $VEL.CP in force (0.25 m/s): a feed inside the block would pass for an approach
  std::string src = kSplineSrc;
  src.replace(src.find("SPLINE WITH $VEL.CP = 0.05"), 26, "SPLINE WITH $VEL.CP = vFeed");
  const Job j = write("krl-spline-unknown", src, kSplineDat);
  const json r = roundTripAndInspect(j, src, kSplineDat);
  ASSERT_TRUE(r.is_object());
  ASSERT_EQ(r["motions"].size(), 8U);
  EXPECT_FALSE(r["motions"][5].contains("speed_mm_s"));
  EXPECT_FALSE(r["motions"][6].contains("speed_mm_s"));
  EXPECT_DOUBLE_EQ(r["motions"][7]["speed_mm_s"].get<double>(), 250.0);
  const json u = unresolvedOf(r, "$VEL.CP");
  ASSERT_FALSE(u.is_null());
  EXPECT_EQ(u["line"], 10);
}

TEST(KrlReader, APathVelocityOfZeroOrBelowIsAnInputErrorAtItsLine) {
  const struct {
    const char* from;
    const char* to;
    const char* where;
  } cases[] = {
      {"$VEL.CP = 0.25\n", "$VEL.CP = 0\n", "job.src:4: $VEL.CP = 0 m/s is not a speed"},
      {"SPL XP3 WITH $VEL.CP = 0.002", "SPL XP3 WITH $VEL.CP = -0.002",
       "job.src:7: $VEL.CP = -0.002 m/s is not a speed"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.to);
    std::string src = kSplineSrc;
    src.replace(src.find(c.from), std::string(c.from).size(), c.to);
    const Job j = write("krl-zero-speed", src, kSplineDat);
    const auto r = test::runRoprec("convert '" + j.src + "' --to rapid -o '" + j.dir + "/o.mod'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(c.where), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("hint:"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(j.dir + "/o.mod"));
  }
}

using postproc::Dialect;
using postproc::parseProgram;

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

TEST(KrlReader, AnAbsurdAngleInTheDatIsRefusedAtItsLine) {
  std::string dat = kKrlDat;
  dat.replace(dat.find("B 0.000"), 7, "B 1e300");
  int line = 0;
  const std::string e = test::programReadError(Dialect::kKrl, "p.src", kKrlSrc, dat, &line);
  EXPECT_EQ(e.rfind("p.dat: target XP1: angle B = 1e+300 is out of range", 0), 0u) << e;
  EXPECT_EQ(line, 2);
  EXPECT_EQ(test::programReadError(Dialect::kKrl, "p.src", kKrlSrc, std::string(kKrlDat)),
            "(accepted)");
}

TEST(KrlReader, ARetractAtZ1e300IsRefusedAtItsLine) {
  std::string src = kKrlSrc;
  src.replace(src.find("Z 284.000,A 0.000,B 0.000,C 180.000}\nEND"), 9, "Z 1e300");
  int line = 0;
  const std::string e =
      test::programReadError(Dialect::kKrl, "p.src", src, std::string(kKrlDat), &line);
  EXPECT_NE(e.find("position z (mm) = 1e+300 is out of range"), std::string::npos) << e;
  EXPECT_EQ(line, 6);
}

TEST(KrlReader, AStatementCutShortIsReportedAtItsOwnLine) {
  // an aggregate that ends at the line's end: the reader looks one token past the statement,
  // which used to carry offset 0 and named line 1
  const std::string dir = test::tempDir("errloc_cut");
  test::writeFile(dir + "/cut.src", "DEF cut ( )\n$VEL.CP = 0.2\n\nLIN {X 1.0,Y\nEND\n");
  const auto r = test::runRoprec("convert '" + dir + "/cut.src' --to csv -o '" + dir + "/out.csv'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("cut.src:4: component Y has no value"), std::string::npos) << r.err;
}

TEST(KrlReader, APathVelocityIsInMetresPerSecond) {
  // KUKA: $VEL.CP is in m/s
  std::string krl = test::readFile(test::sourceDir() + "/samples/emotor-housing/housing_kr120.src");
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

}  // namespace
}  // namespace roprec
