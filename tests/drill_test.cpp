// Drill-cycle recognition (postproc/drill.cpp): a hole starts at the surface — the point the feed
// move into the material starts from — not at the approach point above it. A hand-written cycle
// with the approach 50 mm above the surface and a 20 mm hole is 20 mm deep (not 70 mm, and the
// machining-centre time is that of 20 mm); the surface point is reported with the bottom. A
// program without a drill cycle is an error at its first motion. Recognition advanced over a
// program as it grows (HoleRecognizer) gives the holes of the whole program, in every dialect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "postproc/drill.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

void expectSameHoles(const std::vector<postproc::Hole>& a, const std::vector<postproc::Hole>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].entry_motion, b[i].entry_motion);
    EXPECT_EQ(a[i].bottom_motion, b[i].bottom_motion);
    EXPECT_EQ(a[i].surface_motion, b[i].surface_motion);
    EXPECT_EQ(a[i].targets, b[i].targets);
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_EQ(a[i].axis, b[i].axis);
    EXPECT_EQ(a[i].surface, b[i].surface);
    EXPECT_EQ(a[i].depth, b[i].depth);
    EXPECT_EQ(a[i].base, b[i].base);
    EXPECT_EQ(a[i].tool, b[i].tool);
    EXPECT_EQ(a[i].slower_feed, b[i].slower_feed);
    EXPECT_EQ(a[i].all_markers, b[i].all_markers);
    EXPECT_EQ(a[i].marker_begin, b[i].marker_begin);
    EXPECT_EQ(a[i].marker_end, b[i].marker_end);
  }
}

TEST(HoleRecognizer, AdvancingAsTheProgramGrowsGivesTheHolesOfTheWholeProgram) {
  std::vector<std::string> programs;
  for (const char* f : {"housing_kr120.src", "housing_irb6640.mod", "housing_r2000.ls"})
    programs.push_back(test::sourceDir() + "/samples/emotor-housing/" + f);
  const std::string dir = test::tempDir("recognise_growing");
  test::writeFile(dir + "/big.src", test::krlDrillCycles(120, test::kHousingBase, true));
  programs.push_back(dir + "/big.src");
  if (const std::string corpus = test::corpusDir(); !corpus.empty()) {
    for (const char* f : {"DRILLR30IA.LS", "DrillIRC5.mod", "DrillKRC2DAT.src", "DrillKRC4.src"})
      programs.push_back(corpus + "/robodk/" + f);
  }
  for (const std::string& path : programs) {
    SCOPED_TRACE(path);
    postproc::Program p = postproc::readProgram(path);
    const std::vector<postproc::Hole> whole = postproc::recognizeHoles(p);
    ASSERT_FALSE(whole.empty());
    // the motions come back one at a time; the recogniser advances after each
    std::vector<postproc::Motion> motions = std::move(p.motions);
    p.motions.clear();
    postproc::HoleRecognizer r;
    size_t seen = 0;
    for (postproc::Motion& m : motions) {
      r.advance(p, false);
      EXPECT_GE(r.holes().size(), seen);  // a hole once recognised stays
      seen = r.holes().size();
      p.motions.push_back(std::move(m));
    }
    r.advance(p, true);
    expectSameHoles(r.holes(), whole);
  }
}

using nlohmann::json;

// KR 120 sample cell: $BASE = its workobject, $TOOL = its spindle. Surface at Z 234, bottom 20 mm
// below; approach 50 mm above the surface at the approach speed, drilling at 2 mm/s.
const char* kHandWritten =
    "DEF hand( )\n"
    "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
    "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n"
    "SPINDLE_ON()\n"
    "$VEL.CP = 0.25\n"
    "PTP {X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000}\n"
    "LIN {X 150.000,Y 0.000,Z 234.000,A 0.000,B 0.000,C 180.000}\n"
    "$VEL.CP = 0.002\n"
    "LIN {X 150.000,Y 0.000,Z 214.000,A 0.000,B 0.000,C 180.000}\n"
    "$VEL.CP = 0.25\n"
    "LIN {X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000}\n"
    "END\n";

/// The one hole of `p`, checked to start at the surface z = 234 mm (where the feed starts) and to
/// end 20 mm below it (x = 150 mm, y = 0, in the base frame).
postproc::Hole oneHoleFromSurfaceToBottom(const postproc::Program& p) {
  const std::vector<postproc::Hole> holes = postproc::recognizeHoles(p);
  EXPECT_EQ(holes.size(), 1U);
  if (holes.empty()) return {};
  const postproc::Hole& h = holes[0];
  EXPECT_NEAR(h.depth * 1e3, 20.0, 1e-9);
  EXPECT_LT((h.surface * 1e3 - Eigen::Vector3d(150, 0, 234)).norm(), 1e-9);
  EXPECT_LT((h.position * 1e3 - Eigen::Vector3d(150, 0, 214)).norm(), 1e-9);
  return h;
}

TEST(DrillSurface, HoleStartsWhereTheFeedStartsNotAtTheApproachPoint) {
  const postproc::Program p =
      postproc::parseProgram(postproc::Dialect::kKrl, "hand.src", kHandWritten);
  const postproc::Hole h = oneHoleFromSurfaceToBottom(p);
  EXPECT_GE(h.surface_motion, 0);
  EXPECT_EQ(h.targets.size(), 4U);  // approach, surface, bottom, retract (inline targets)
  // the evidence, in the order it is found (the bottom LIN has no approximation: exact stop)
  EXPECT_EQ(
      postproc::holeEvidence(p, h),
      (std::vector<std::string>{"feed slower than approach/retract", "exact stop at the bottom"}));
}

TEST(DrillSurface, NoFeedChangeLeavesTheDepthToTheCell) {
  // every move at the same speed: the program does not say where the material starts; the drill
  // call is the process evidence
  std::string text = kHandWritten;
  text.replace(text.find("$VEL.CP = 0.002"), 15, "WAIT SEC 0.3\nDRILL_CYCLE()\n$VEL.CP = 0.250");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kKrl, "hand.src", text);
  const std::vector<postproc::Hole> holes = postproc::recognizeHoles(p);
  ASSERT_EQ(holes.size(), 1U);
  EXPECT_EQ(holes[0].depth, 0.0);
  EXPECT_EQ(holes[0].surface_motion, -1);
  EXPECT_EQ(postproc::holeEvidence(p, holes[0]),
            (std::vector<std::string>{"dwell 0.3 s", "call DRILL_CYCLE", "exact stop at the bottom",
                                      "no feed change: surface and depth not known from the "
                                      "program"}));
}

TEST(DrillSurface, ADwellAloneIsNoDrillingEvidence) {
  // down, wait, up at one speed: a gripper placing a part looks the same, so no hole
  std::string text = kHandWritten;
  text.replace(text.find("$VEL.CP = 0.002"), 15, "WAIT SEC 0.3\n$VEL.CP = 0.250");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kKrl, "hand.src", text);
  EXPECT_TRUE(postproc::recognizeHoles(p).empty());
}

TEST(DrillSurface, PeckCycleLongerThanThePoseCacheKeepsItsSurfaceAndBottom) {
  // 100 pecks of 0.2 mm (feed in, rapid back 0.1 mm): 300 motions on one line, more than the
  // 64 poses recognizeHoles keeps at once; the surface is where the first feed starts and the
  // bottom the deepest point, 20 mm below it (closed form: 100 x 0.2 mm)
  std::string text =
      "DEF peck( )\n"
      "$BASE = {FRAME: X 1350.000,Y 0.000,Z 300.000,A 0.000,B 0.000,C 0.000}\n"
      "$TOOL = {FRAME: X 0.000,Y 0.000,Z 320.000,A 0.000,B 0.000,C 0.000}\n"
      "$VEL.CP = 0.25\n"
      "PTP {X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000}\n"
      "LIN {X 150.000,Y 0.000,Z 234.000,A 0.000,B 0.000,C 180.000}\n";
  char line[256];
  for (int k = 1; k <= 100; ++k) {
    std::snprintf(line, sizeof line,
                  "$VEL.CP = 0.002\nLIN {X 150.000,Y 0.000,Z %.3f,A 0.000,B 0.000,C 180.000}\n"
                  "$VEL.CP = 0.25\nLIN {X 150.000,Y 0.000,Z %.3f,A 0.000,B 0.000,C 180.000}\n",
                  234.0 - 0.2 * k, 234.0 - 0.2 * k + 0.1);
    text += line;
  }
  text += "LIN {X 150.000,Y 0.000,Z 284.000,A 0.000,B 0.000,C 180.000}\nEND\n";
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kKrl, "peck.src", text);
  ASSERT_EQ(p.motions.size(), 203U);
  const postproc::Hole h = oneHoleFromSurfaceToBottom(p);
  EXPECT_EQ(h.bottom_motion, 200);  // the last feed move: motion 2 x 100
  EXPECT_EQ(h.targets.size(), 203U);
}

TEST(DrillSurface, PathVelocityThatIsNotANumberMakesTheSpeedsUnknownAndIsReported) {
  // `$VEL.CP = inf` (an identifier to KRL, like a variable): the feed move's speed is not known;
  // before, it silently kept the approach speed of 0.25 m/s (a feed passing for an approach)
  std::string text = kHandWritten;
  text.replace(text.find("$VEL.CP = 0.002"), 15, "$VEL.CP = inf");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kKrl, "hand.src", text);
  ASSERT_EQ(p.unresolved.size(), 1U);
  EXPECT_EQ(p.unresolved[0].ref, "$VEL.CP");
  EXPECT_EQ(p.unresolved[0].line, 8);
  EXPECT_NE(p.unresolved[0].what.find("'inf'"), std::string::npos) << p.unresolved[0].what;
  ASSERT_EQ(p.motions.size(), 4U);
  EXPECT_NEAR(p.motions[1].speed_mm_s, 250.0, 1e-9);  // before the unknown value
  EXPECT_LT(p.motions[2].speed_mm_s, 0.0);            // the feed move: unknown
  EXPECT_NEAR(p.motions[3].speed_mm_s, 250.0, 1e-9);  // $VEL.CP = 0.25 again
}

TEST(DrillSurface, DrillMarkersAreRecognisedInAnyCase) {
  for (const char* m : {"dwell 0.3 s", "DWELL", "SPINDLE_ON()", "call Drill_Cycle", "plunge",
                        "; Bohrung 12", "boor"})
    EXPECT_TRUE(postproc::drillMarker(m)) << m;
  for (const char* m : {"", "wait for part", "; a dwelling", "SPIN", "WAIT SEC 0.3"})
    EXPECT_FALSE(postproc::drillMarker(m)) << m;
}

TEST(DrillSurface, AHoleListConfirmsACycleWithADwellAlone) {
  std::string text = kHandWritten;
  text.replace(text.find("$VEL.CP = 0.002"), 15, "WAIT SEC 0.3\n$VEL.CP = 0.250");
  const postproc::Program p = postproc::parseProgram(postproc::Dialect::kKrl, "hand.src", text);
  // the hole on the list (program frame, drilling along -z) and one the program never visits
  const std::vector<postproc::HoleSpec> listed =
      postproc::parseHoleList("holes.csv", "id,x,y,z,i,j,k\nA1,150,0,234,0,0,-1\n");
  const std::vector<postproc::Hole> holes =
      postproc::withHoleListEvidence(p, postproc::recognizeHoles(p), listed, 0.5);
  ASSERT_EQ(holes.size(), 1U);
  EXPECT_EQ(holes[0].id, "H1");
  EXPECT_TRUE(holes[0].dwell_only);
  EXPECT_LT((holes[0].position * 1e3 - Eigen::Vector3d(150, 0, 214)).norm(), 1e-9);
  const std::vector<std::string> ev = postproc::holeEvidence(p, holes[0]);
  EXPECT_NE(
      std::find(ev.begin(), ev.end(), "on the hole list (a dwell alone is no drilling evidence)"),
      ev.end());
  const std::vector<postproc::HoleSpec> elsewhere =
      postproc::parseHoleList("holes.csv", "id,x,y,z,i,j,k\nA1,450,0,234,0,0,-1\n");
  EXPECT_TRUE(
      postproc::withHoleListEvidence(p, postproc::recognizeHoles(p), elsewhere, 0.5).empty());
}

TEST(DrillSurface, OnlyCallsAndCommentsAreProcessEvidenceNotADwell) {
  for (const char* m : {"SPINDLE_ON()", "call Drill_Cycle", "plunge", "; Bohrung 12"})
    EXPECT_TRUE(postproc::processMarker(m)) << m;
  for (const char* m : {"dwell 0.3 s", "DWELL", "wait for part"})
    EXPECT_FALSE(postproc::processMarker(m)) << m;
}

TEST(DrillSurface, PredictAndInspectReportTheSurfaceAndTheBottom) {
  const std::string dir = test::tempDir("drill_surface");
  test::writeFile(dir + "/hand.src", kHandWritten);
  const std::string cell = test::sourceDir() + "/samples/cells/housing-kr120.xml";
  const auto r = test::runRoprec("predict --cell '" + cell + "' '" + dir + "/hand.src' --json '" +
                                 dir + "/p.json' --quiet");
  ASSERT_LE(r.exit_code, 1) << r.err;
  const json j = json::parse(test::readFile(dir + "/p.json"));
  ASSERT_EQ(j["holes"].size(), 1U);
  EXPECT_NEAR(j["holes"][0]["depth_mm"].get<double>(), 20.0, 1e-9);
  // the cell drills at 0.2 mm/rev x 6000 rpm = 20 mm/s, plus 2 s approach: 3 s, not 5.5 s
  EXPECT_NEAR(j["summary"]["mc_time_total_s"].get<double>(), 3.0, 1e-6) << j["summary"].dump();
  // predict states where the hole starts and ends (base frame: workobject z 300 + 234 / 214)
  const json& nom = j["holes"][0]["nominal"];
  EXPECT_NEAR(nom["surface_mm"][2].get<double>(), 534.0, 1e-6) << nom.dump();
  EXPECT_NEAR(nom["bottom_mm"][2].get<double>(), 514.0, 1e-6) << nom.dump();
  EXPECT_NEAR(nom["surface_mm"][0].get<double>(), 1500.0, 1e-6) << nom.dump();
  const auto i = test::runRoprec("inspect '" + dir + "/hand.src' --all");
  ASSERT_EQ(i.exit_code, 0) << i.err;
  const json ins = json::parse(i.out);
  const json& h = ins["holes"][0];
  EXPECT_NEAR(h["depth_mm"].get<double>(), 20.0, 1e-9);
  EXPECT_NEAR(h["position_in_frame_mm"][2].get<double>(), 234.0, 1e-9);
  EXPECT_NEAR(h["bottom_in_frame_mm"][2].get<double>(), 214.0, 1e-9);
  EXPECT_NEAR(h["position_mm"][2].get<double>(), 534.0, 1e-9);
  EXPECT_NEAR(h["bottom_mm"][2].get<double>(), 514.0, 1e-9);
}

TEST(DrillCycle, NoDrillCycleIsAnErrorAtTheProgramsFirstMotion) {
  const std::string dir = test::tempDir("errloc_prog");
  test::writeFile(dir + "/p.src",
                  "DEF p ( )\n"
                  "$BASE = {FRAME: X 1350,Y 0,Z 300,A 0,B 0,C 0}\n"
                  "$TOOL = {FRAME: X 0,Y 0,Z 350,A 0,B 0,C 0}\n"
                  "PTP {A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\n"
                  "END\n");
  const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                 "/samples/cells/housing-kr120.xml' '" + dir + "/p.src'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("p.src:4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no drill cycle"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
