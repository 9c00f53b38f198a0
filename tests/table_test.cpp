// The CSV/JSON target-list readers (postproc/table.cpp): a column or member roprec does not know is
// an error at FILE:LINE with a "did you mean" for a near miss, instead of being ignored (a misspelt
// `conf` column drops every configuration; a misspelt "quaternion_wxyz" reads targets without their
// orientation).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "compensator/support/error.hpp"
#include "compensator/support/rotation.hpp"
#include "postproc/drill.hpp"
#include "postproc/program.hpp"
#include "support/test_support.hpp"

namespace roprec {
namespace {

using postproc::Dialect;

/// The InputError of reading `text` as `dialect`, or a test failure when it is accepted.
std::optional<InputError> readError(Dialect dialect, const std::string& text) {
  try {
    (void)postproc::parseProgram(dialect, "t.in", text, std::nullopt, "");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return std::nullopt;
}

TEST(TargetListValidation, UnknownCsvColumnsAreRefusedWithAHint) {
  const std::string rows = "P1,100,0,500,0,90,0,S 2 T 35\n";
  const auto e = readError(Dialect::kCsv, "id,x,y,z,a,b,c,cnf\n" + rows);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 1);
  EXPECT_NE(std::string(e->what()).find("unknown column 'cnf' in the target list"),
            std::string::npos)
      << e->what();
  EXPECT_NE(std::string(e->what()).find("did you mean 'conf'"), std::string::npos) << e->what();
  const auto far = readError(Dialect::kCsv, "id,x,y,z,a,b,c,velocity\n" + rows);
  ASSERT_TRUE(far);
  EXPECT_NE(std::string(far->what()).find("a target list has the columns id,name,x"),
            std::string::npos)
      << far->what();
  const auto twice = readError(Dialect::kCsv, "id,x,y,z,a,b,c,X_mm\n" + rows);
  ASSERT_TRUE(twice);
  EXPECT_NE(std::string(twice->what()).find("column 'x' is given twice"), std::string::npos)
      << twice->what();
}

TEST(TargetListValidation, KnownCsvColumnsStillRead) {
  const std::string text =
      "# frame WOBJ: 1000 0 0 1 0 0 0\n"
      "id,motion,x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,frame,conf,speed,comment\n"
      "P1,L,100,0,500,0,90,0,WOBJ,S 2 T 35,100,first\n";
  const postproc::Program p =
      postproc::parseProgram(Dialect::kCsv, "t.csv", text, std::nullopt, "");
  ASSERT_EQ(p.targets().size(), 1U);
  EXPECT_EQ(p.targets()[0].config.status, 2);
  EXPECT_EQ(p.targets()[0].config.turn, 35);
  // RoboDK's target export (move, x_frame_mm, ..., j1_deg, ...) reads too.
  const postproc::Program r = postproc::parseProgram(
      Dialect::kCsv, "r.csv",
      "move,x_frame_mm,y_frame_mm,z_frame_mm,j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg\n"
      "J,0,0.0,50.0,0,-66.1,118.0,0,38.1,-180\n",
      std::nullopt, "");
  EXPECT_EQ(r.targets().size(), 1U);
}

TEST(TargetListValidation, UnknownJsonMembersAreRefusedWithAHint) {
  const auto target = readError(Dialect::kJson,
                                "{\"targets\": [\n"
                                "  {\"id\": \"P1\", \"position_mm\": [100, 0, 500],\n"
                                "   \"quaternion_xyzw\": [0, 0.7071068, 0, 0.7071068]}\n"
                                "]}\n");
  ASSERT_TRUE(target);
  EXPECT_EQ(target->line(), 3);
  EXPECT_NE(std::string(target->what()).find("unknown member \"quaternion_xyzw\" in a target"),
            std::string::npos)
      << target->what();
  EXPECT_NE(std::string(target->what()).find("did you mean 'quaternion_wxyz'"), std::string::npos)
      << target->what();
  const auto root = readError(Dialect::kJson, "{\"targtes\": [], \"targets\": []}\n");
  ASSERT_TRUE(root);
  EXPECT_NE(std::string(root->what()).find("did you mean 'targets'"), std::string::npos)
      << root->what();
  const auto frame =
      readError(Dialect::kJson,
                "{\"frames\": [{\"name\": \"W\", \"position\": [0, 0, 0], \"quaternion_wxyz\": [1, "
                "0, 0, 0]}],\n"
                " \"targets\": [{\"id\": \"P1\", \"joints_deg\": [0, -90, 90, 0, 0, 0]}]}\n");
  ASSERT_TRUE(frame);
  EXPECT_NE(std::string(frame->what()).find("unknown member \"position\" in a frame"),
            std::string::npos)
      << frame->what();
}

TEST(TargetListValidation, TheCliRefusesAMisspeltColumnWithExit2) {
  const std::string dir = test::tempDir("target-list-strict");
  test::writeFile(dir + "/t.csv", "id,x,y,z,a,b,c,spede\nP1,1500,0,500,0,90,0,100\n");
  const test::RunResult r = test::runRoprec("inspect '" + dir + "/t.csv'");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(dir + "/t.csv:1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'speed'"), std::string::npos) << r.err;
}

TEST(TargetListValidation, RoboDkHeaderlessExportIsAHoleListWithItsReadingStated) {
  // x,y,z, rx,ry,rz (RoboDK TxyzRxyz: R = Rx Ry Rz): rx = 180 drills along -z; rx = 90 along -y.
  const std::string plain = "100,0,0,180,0,0\n200,50,10,90,0,0\n";
  const auto holes = postproc::parseHoleList("r.csv", plain);
  ASSERT_EQ(holes.size(), 2U);
  EXPECT_EQ(holes[0].id, "R1");
  EXPECT_EQ(holes[1].id, "R2");
  EXPECT_NEAR((holes[0].direction - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((holes[1].direction - Vec3(0, -1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((holes[1].position_mm - Vec3(200, 50, 10)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(holes[0].diameter_mm);
  // Rotations about the pose's own z do not move the axis; a general pose against the closed form.
  const auto named = postproc::parseHoleList("n.csv", "Target 7,0,0,0,30,-40,75\n");
  ASSERT_EQ(named.size(), 1U);
  EXPECT_EQ(named[0].id, "Target 7");
  const double a = 30 * kDeg, b = -40 * kDeg;
  const Vec3 z(std::sin(b), -std::sin(a) * std::cos(b), std::cos(a) * std::cos(b));
  EXPECT_NEAR((named[0].direction - z).norm(), 0.0, 1e-12);
  const postproc::Program p =
      postproc::parseProgram(Dialect::kCsv, "r.csv", plain, std::nullopt, "");
  EXPECT_EQ(p.dialect, Dialect::kHoleCsv);
  ASSERT_EQ(p.notes.size(), 1U);
  EXPECT_EQ(p.notes[0].rfind(postproc::kReadingNotePrefix, 0), 0U);
  EXPECT_NE(p.notes[0].find("read as RoboDK's target export"), std::string::npos) << p.notes[0];
  EXPECT_NE(p.notes[0].find("ids R1..Rn"), std::string::npos) << p.notes[0];
  // Not that shape: still a header (and then refused when unknown).
  EXPECT_TRUE(readError(Dialect::kCsv, "100,0,0,180,0\n"));
}

TEST(TargetListValidation, PredictStatesHowARoboDkExportWasRead) {
  const std::string dir = test::tempDir("robodk-holes");
  test::writeFile(dir + "/r.csv", "100,0,150,180,0,0\n200,50,150,180,0,0\n");
  const test::RunResult r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                            "/samples/cells/housing-kr120.xml' '" + dir +
                                            "/r.csv' --json '" + dir + "/p.json'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("roprec: note: " + dir +
                       "/r.csv has no header: read as RoboDK's target "
                       "export, columns x,y,z (mm, work object) and rx,ry,rz (deg"),
            std::string::npos)
      << r.err;
  const std::string json = test::readFile(dir + "/p.json");
  EXPECT_NE(json.find("read as RoboDK's target export"), std::string::npos);
  EXPECT_NE(json.find("\"R2\""), std::string::npos);
}

TEST(TargetListValidation, SpeedsOfZeroOrBelowAreErrorsAtTheirLine) {
  for (const char* speed : {"0", "-5"}) {
    SCOPED_TRACE(speed);
    const auto csv = readError(Dialect::kCsv, std::string("id,motion,x,y,z,a,b,c,speed\n"
                                                          "P1,L,100,0,500,0,90,0,100\n"
                                                          "P2,L,100,0,480,0,90,0,") +
                                                  speed + "\n");
    ASSERT_TRUE(csv);
    EXPECT_EQ(csv->line(), 3);
    EXPECT_NE(std::string(csv->what()).find("hint:"), std::string::npos) << csv->what();
    const auto json = readError(
        Dialect::kJson, std::string("{\"targets\": [\n"
                                    " {\"id\": \"P1\", \"position_mm\": [100, 0, 500], "
                                    "\"quaternion_wxyz\": [1, 0, 0, 0], \"speed_mm_s\": 100},\n"
                                    " {\"id\": \"P2\", \"position_mm\": [100, 0, 480], "
                                    "\"quaternion_wxyz\": [1, 0, 0, 0], \"speed_mm_s\": ") +
                            speed + "}\n]}\n");
    ASSERT_TRUE(json);
    EXPECT_EQ(json->line(), 3);
    EXPECT_NE(std::string(json->what()).find("hint:"), std::string::npos) << json->what();
  }
}

}  // namespace
}  // namespace roprec
