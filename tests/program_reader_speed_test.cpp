// The fast paths of the CSV/JSON/RAPID/TP readers (program read + write >= 100 MB/s):
// JSON targets streamed before the document's "frames"/"euler" are known, CSV lookups memoised
// over runs of equal rows. Expectations are hand-written closed forms, not the code's output.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "compensator/support/error.hpp"
#include "postproc/program.hpp"

namespace {

using namespace roprec::postproc;
using roprec::InputError;

std::optional<InputError> readError(Dialect d, const std::string& text) {
  try {
    (void)parseProgram(d, "t.in", text, std::nullopt, "");
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

// Rz(r) Ry(p) Rx(w) for w = 90°, p = r = 0: x stays, y -> z, z -> -y.
void expectRx90(const roprec::Pose& T) {
  const roprec::Mat3 R = T.linear();
  EXPECT_NEAR(R(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(R(2, 1), 1.0, 1e-12);
  EXPECT_NEAR(R(1, 2), -1.0, 1e-12);
  EXPECT_NEAR(R(1, 1), 0.0, 1e-12);
}

TEST(ProgramReaderSpeed, JsonFramesAndEulerAfterTheTargetsStillApply) {
  const std::string after =
      "{\"targets\": [\n"
      "  {\"id\": \"P1\", \"position_mm\": [1, 2, 3], \"rx\": 90, \"ry\": 0, \"rz\": 0,"
      " \"frame\": \"fx\", \"tool\": \"spindle\"},\n"
      "  {\"id\": \"P2\", \"position_mm\": [4, 5, 6], \"quaternion_wxyz\": [1, 0, 0, 0],"
      " \"frame\": \"FX\"}\n"
      "],\n"
      " \"frames\": [{\"name\": \"fx\", \"position_mm\": [10, 20, 30],"
      " \"quaternion_wxyz\": [0.7071067811865476, 0, 0, 0.7071067811865476]}],\n"
      " \"euler\": \"ZYX\"}\n";
  const Program p = parseProgram(Dialect::kJson, "t.json", after, std::nullopt, "");
  ASSERT_EQ(p.targets().size(), 2u);
  ASSERT_EQ(p.motions.size(), 2u);
  const Target& t1 = p.targets()[0];
  EXPECT_EQ(t1.orientation, Orientation::kFanucWpr);
  expectRx90(targetPose(p, t1));
  EXPECT_NEAR(targetPose(p, t1).translation().y(), 0.002, 1e-15);
  for (const Target& t : p.targets()) {
    const Frame* base = targetBase(p, t);
    ASSERT_NE(base, nullptr) << t.name;
    EXPECT_TRUE(base->resolved) << t.name;
    EXPECT_NEAR(base->pose.translation().z(), 0.030, 1e-15);
    EXPECT_NEAR(base->pose.linear()(1, 0), 1.0, 1e-12);  // Rz(90°): x -> y
  }
  const Frame* tool = targetTool(p, t1);
  ASSERT_NE(tool, nullptr);
  EXPECT_FALSE(tool->resolved);  // "spindle" is not declared
  EXPECT_EQ(tool->ref, "spindle");
  EXPECT_EQ(renderFiles(p)[0], after);
}

TEST(ProgramReaderSpeed, JsonRxyzWithoutEulerFailsAtTheFirstSuchTarget) {
  const auto e = readError(Dialect::kJson,
                           "{\"targets\": [\n"
                           "  {\"id\": \"P1\", \"joints_deg\": [0, 0, 0, 0, 0, 0]},\n"
                           "  {\"id\": \"P2\", \"position_mm\": [1, 2, 3], \"rx\": 1, \"ry\": 2,"
                           " \"rz\": 3},\n"
                           "  {\"id\": \"P3\", \"position_mm\": [1, 2, 3], \"rx\": 1, \"ry\": 2,"
                           " \"rz\": 3}\n"
                           "]}\n");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 3);
  EXPECT_NE(e->message().find("need a declared \"euler\""), std::string::npos) << e->what();
}

TEST(ProgramReaderSpeed, JsonTargetsOfDifferentShapesInOneListKeepTheirOwnMembers) {
  // The streamed element's buffers are reused: a short target after a long one must not see the
  // long one's members.
  const std::string text =
      "{\"targets\": [\n"
      "  {\"id\": \"A\", \"position_mm\": [1, 2, 3], \"quaternion_wxyz\": [1, 0, 0, 0],"
      " \"joints_deg\": [1, 2, 3, 4, 5, 6], \"config\": \"S 2 T 35\", \"motion\": \"J\"},\n"
      "  {\"id\": \"B\", \"joints_deg\": [7, 8]},\n"
      "  {\"id\": \"C\", \"x\": 9, \"y\": 8, \"z\": 7, \"a\": 90, \"b\": 0, \"c\": 0}\n"
      "]}\n";
  const Program p = parseProgram(Dialect::kJson, "t.json", text, std::nullopt, "");
  ASSERT_EQ(p.targets().size(), 3u);
  const Target& b = p.targets()[1];
  EXPECT_EQ(b.kind, TargetKind::kJoint);
  EXPECT_DOUBLE_EQ(std::as_const(b).joints[1].value, 8.0);
  EXPECT_FALSE(std::as_const(b).joints[2].present());
  EXPECT_FALSE(b.config.present());
  EXPECT_EQ(p.motions[0].type, MotionType::kJoint);
  EXPECT_EQ(p.motions[1].type, MotionType::kLinear);
  const Target& c = p.targets()[2];
  EXPECT_EQ(c.orientation, Orientation::kKukaAbc);
  EXPECT_DOUBLE_EQ(c.pos[2].value, 7.0);
  // Rz(90°): x -> y
  EXPECT_NEAR(targetPose(p, c).linear()(1, 0), 1.0, 1e-12);
  EXPECT_EQ(p.files[0].bytes.substr(c.pos[0].offset, c.pos[0].length), "9");
}

TEST(ProgramReaderSpeed, CsvFrameRedeclaredMidFileAppliesToTheRowsAfterIt) {
  const std::string text =
      "# frame F: 0 0 0 1 0 0 0\n"
      "id,x,y,z,a,b,c,frame,conf\n"
      "T1,1,2,3,0,0,0,F,S 2 T 35\n"
      "T2,1,2,3,0,0,0,F,S 2 T 35\n"
      "# frame F: 100 0 0 1 0 0 0\n"
      "T3,1,2,3,0,0,0,F,S 6 T 1\n"
      "T4,1,2,3,0,0,0,F,S 2 T 35\n";
  const Program p = parseProgram(Dialect::kCsv, "t.csv", text, std::nullopt, "");
  ASSERT_EQ(p.targets().size(), 4u);
  const double expect_x[] = {0.0, 0.0, 0.1, 0.1};
  const int expect_s[] = {2, 2, 6, 2};
  const int expect_t[] = {35, 35, 1, 35};
  for (std::size_t i = 0; i < 4; ++i) {
    const Target& t = p.targets()[i];
    const Frame* base = targetBase(p, t);
    ASSERT_NE(base, nullptr);
    EXPECT_TRUE(base->resolved);
    EXPECT_NEAR(base->pose.translation().x(), expect_x[i], 1e-15) << t.name;
    EXPECT_EQ(t.config.status, expect_s[i]) << t.name;
    EXPECT_EQ(t.config.turn, expect_t[i]) << t.name;
    EXPECT_EQ(t.line, static_cast<int>(i < 2 ? i + 3 : i + 4)) << t.name;
  }
  EXPECT_EQ(renderFiles(p)[0], text);
}

TEST(ProgramReaderSpeed, CsvEditedPositionKeepsItsNeighboursBytes) {
  const std::string text = "id,x,y,z,a,b,c\nT1,1.500,2,3,0,0,0\nT2,4,5,6,0,0,0\n";
  Program p = parseProgram(Dialect::kCsv, "t.csv", text, std::nullopt, "");
  roprec::Pose T = targetPose(p, p.targets()[0]);
  T.translation().x() = 0.0025;  // 2.5 mm
  ASSERT_TRUE(replaceTargetPose(p, 0, T).ok);
  EXPECT_EQ(renderFiles(p)[0], "id,x,y,z,a,b,c\nT1,2.500,2,3,0,0,0\nT2,4,5,6,0,0,0\n");
}

TEST(ProgramReaderSpeed, RapidToolRedefinedBetweenMotionsMovesTheLaterMotionsTcp) {
  const std::string text =
      "MODULE m\n"
      "  PERS tooldata t1 := [TRUE,[[0,0,100],[1,0,0,0]],[1,[0,0,1],[1,0,0,0],0,0,0]];\n"
      "  PROC main()\n"
      "    MoveL "
      "[[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,t1\\WObj:=wobj0;\n"
      "    MoveL "
      "[[4,5,6],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,t1\\WObj:=wobj0;\n"
      "    t1.tframe := [[0,0,200],[1,0,0,0]];\n"
      "    MoveL [[1,2,3],[1,0,0,0],[0,0,0,0],\n"
      "           [9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,t1\\WObj:=wobj0;\n"
      "    MoveL [[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,t1;\n"
      "  ENDPROC\n"
      "ENDMODULE\n";
  const Program p = parseProgram(Dialect::kRapid, "t.mod", text, std::nullopt, "");
  // The second motion leaves the frame table as the third finds it: only the redefinition
  // tells the third that t1 moved.
  ASSERT_EQ(p.motions.size(), 4u);
  const double expect_z[] = {0.100, 0.100, 0.200, 0.200};
  const int expect_line[] = {4, 5, 7, 9};
  for (std::size_t i = 0; i < 4; ++i) {
    const Motion& m = p.motions[i];
    ASSERT_GE(m.tool, 0);
    EXPECT_NEAR(p.frames[static_cast<std::size_t>(m.tool)].pose.translation().z(), expect_z[i],
                1e-15)
        << i;
    EXPECT_EQ(m.line, expect_line[i]);
  }
  EXPECT_EQ(renderFiles(p)[0], text);
}

TEST(ProgramReaderSpeed, TpRecordsSplitOverLinesAndAlternatingFramesBindToTheirOwnFrames) {
  const std::string text =
      "/PROG  T\n/MN\n"
      "   1:L P[1] 100mm/sec FINE ;\n"
      "   2:L P[2] 100mm/sec CNT50 ;\n"
      "   3:L P[1] 100mm/sec FINE ;\n"
      "/POS\n"
      "P[1]{\n   GP1:\n\tUF : 1, UT : 2,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
      "\tX = 1.000 mm, Y = 2.000 mm, Z = 3.000 mm,\n\tW = 0.000 deg, P = 0.000 deg, R = 0.000 deg\n"
      "};\n"
      "P[2]{\n   GP1:\n\tUF : 3, UT : 2,\t\tCONFIG : 'F D B, 1, 0, -1',\n"
      "\tX = 4.000 mm, Y = 5.000 mm, Z = 6.000 mm,\n\tW = 0.000 deg, P = 0.000 deg, R = 0.000 deg\n"
      "};\n/END\n";
  const Program p = parseProgram(Dialect::kTp, "t.ls", text, std::nullopt, "");
  ASSERT_EQ(p.targets().size(), 2u);
  ASSERT_EQ(p.motions.size(), 3u);
  const char* const bases[] = {"UFRAME[1]", "UFRAME[3]", "UFRAME[1]"};
  for (std::size_t i = 0; i < 3; ++i) {
    const Motion& m = p.motions[i];
    ASSERT_GE(m.base, 0);
    ASSERT_GE(m.tool, 0);
    EXPECT_EQ(p.frames[static_cast<std::size_t>(m.base)].ref, bases[i]) << i;
    EXPECT_EQ(p.frames[static_cast<std::size_t>(m.tool)].ref, "UTOOL[2]") << i;
  }
  EXPECT_EQ(p.motions[2].target, 0);
  EXPECT_DOUBLE_EQ(p.targets()[1].pos[2].value, 6.0);
  EXPECT_EQ(p.targets()[1].config.flip, 'F');
  EXPECT_EQ(p.targets()[1].config.turns[2], -1);
  EXPECT_EQ(renderFiles(p)[0], text);
}

TEST(ProgramReaderSpeed, RapidPlainInlineRobtargetReadsAsTheGeneralForm) {
  // One line of plain numbers takes the reader's fast path; the same target broken over two
  // lines takes the general aggregate parser. Both give the hand-written values below.
  const std::string plain =
      "MODULE m\n  PROC main()\n"
      "    MoveL [[1.5,-2,+3],[0.5,0.5,-0.5,0.5],[-1,0,2,0],[9E+09,1,2,3,4,-5.25]],v100,z1,tool0;\n"
      "  ENDPROC\nENDMODULE\n";
  const std::string broken =
      "MODULE m\n  PROC main()\n"
      "    MoveL [[1.5,-2,+3],[0.5,0.5,-0.5,0.5],[-1,0,2,0],\n"
      "           [9E+09,1,2,3,4,-5.25]],v100,z1,tool0;\n"
      "  ENDPROC\nENDMODULE\n";
  const double pos[] = {1.5, -2.0, 3.0};
  const double rot[] = {0.5, 0.5, -0.5, 0.5};
  const int cf[] = {-1, 0, 2, 0};
  const double ext[] = {9e9, 1, 2, 3, 4, -5.25};
  for (const std::string* text : {&plain, &broken}) {
    const Program p = parseProgram(Dialect::kRapid, "t.mod", *text, std::nullopt, "");
    ASSERT_EQ(p.targets().size(), 1u);
    const Target& t = p.targets()[0];
    EXPECT_EQ(t.line, 3);
    EXPECT_EQ(t.orientation, Orientation::kQuaternion);
    EXPECT_EQ(t.config.vendor, Vendor::kAbb);
    for (std::size_t k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(t.pos[k].value, pos[k]);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(t.rot[k].value, rot[k]);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(t.config.cf[k], cf[k]);
    for (std::size_t k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(t.ext[k].value, ext[k]);
    EXPECT_EQ(p.files[0].bytes.substr(t.pos[1].offset, t.pos[1].length), "-2");
    EXPECT_EQ(p.files[0].bytes.substr(t.pos[2].offset, t.pos[2].length), "+3");
    EXPECT_EQ(p.files[0].bytes.substr(t.ext[5].offset, t.ext[5].length), "-5.25");
    ASSERT_EQ(p.motions.size(), 1u);
    EXPECT_EQ(p.motions[0].target, 0);
    EXPECT_DOUBLE_EQ(p.motions[0].speed_mm_s, 100.0);
    EXPECT_EQ(renderFiles(p)[0], *text);
  }
  // a broken number is still an error with its line, whichever path sees it first
  std::string bad = plain;
  bad.replace(bad.find("1.5"), 3, "1.5.3");
  const auto e = readError(Dialect::kRapid, bad);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 3);
  EXPECT_NE(e->message().find("broken number"), std::string::npos) << e->what();
}

}  // namespace
