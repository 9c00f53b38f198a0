// The laser-tracker / CMM pose file: columns in any order and case, optional groups (orientation,
// payload, wrench, u) all-or-none per row, FILE:LINE errors, and the writer reading back to the
// same poses.
#include "postproc/measured_poses.hpp"

#include <gtest/gtest.h>

#include "compensator/support/error.hpp"

namespace roprec::postproc {
namespace {

TEST(MeasuredPoses, ReadsColumnsInAnyOrderAndOptionalGroups) {
  const std::string text =
      "# tracker run 2026-11-27, SMR at the TCP\n"
      "\n"
      "X,Y,Z,ID,J1,J2,J3,J4,J5,J6,mass,com_x,com_y,com_z,u,note\n"
      "1.5,-2,300.25,P1,10,-90,90,0,45,0,,,,,,first\n"
      "2,3,4,P2,0,-80,100,5,30,-5,50,0,0,150,12.5,with payload\n";
  const MeasuredPoses p = parseMeasuredPoses(text, "poses.csv");
  ASSERT_EQ(p.poses.size(), 2u);
  EXPECT_EQ(p.poses[0].id, "P1");
  EXPECT_EQ(p.poses[0].line, 4);
  EXPECT_DOUBLE_EQ(p.poses[0].p_mm.z(), 300.25);
  EXPECT_DOUBLE_EQ(p.poses[0].joints_deg[1], -90);
  EXPECT_FALSE(p.poses[0].payload_kg.has_value());
  EXPECT_FALSE(p.poses[0].u_um.has_value());
  EXPECT_FALSE(p.poses[0].rpy_deg.has_value());
  ASSERT_TRUE(p.poses[1].payload_kg.has_value());
  EXPECT_DOUBLE_EQ(*p.poses[1].payload_kg, 50);
  EXPECT_DOUBLE_EQ(p.poses[1].payload_com_mm.z(), 150);
  EXPECT_DOUBLE_EQ(*p.poses[1].u_um, 12.5);
  EXPECT_TRUE(looksLikeMeasuredPoses(text));
  EXPECT_FALSE(looksLikeMeasuredPoses("id,x,y,z\nA,1,2,3\n"));
}

TEST(MeasuredPoses, EmptyJointsNameTheProgramsTargetAndWriteBackEmpty) {
  const std::string text =
      "id,j1,j2,j3,j4,j5,j6,x,y,z\n"
      "V01,,,,,,,1,2,3\n"
      "P2,0,-80,100,5,30,-5,4,5,6\n";
  const MeasuredPoses p = parseMeasuredPoses(text, "poses.csv");
  ASSERT_EQ(p.poses.size(), 2u);
  EXPECT_TRUE(p.poses[0].program_target);
  EXPECT_FALSE(p.poses[1].program_target);
  EXPECT_DOUBLE_EQ(p.poses[1].joints_deg[2], 100);
  const std::string written = writeMeasuredPoses(p.poses);
  EXPECT_NE(written.find("\nV01,,,,,,,1.0000,2.0000,3.0000\n"), std::string::npos) << written;
  const MeasuredPoses back = parseMeasuredPoses(written, "back.csv");
  EXPECT_TRUE(back.poses[0].program_target);
  EXPECT_EQ(back.poses[1].joints_deg, p.poses[1].joints_deg);
  // some joints given, some not: still an error at the line
  try {
    parseMeasuredPoses("id,j1,j2,j3,j4,j5,j6,x,y,z\nA,1,,,,,,1,2,3\n", "part.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
  }
}

TEST(MeasuredPoses, WriterReadsBackToTheSamePoses) {
  MeasuredPose a;
  a.id = "T1";
  a.joints_deg << 1.25, -91, 88.5, 0.5, 44, -3;
  a.p_mm = Vec3(1350.1234, -20.5, 640.0);
  a.rpy_deg = Vec3(180, 0.5, -90);
  a.force_n = Vec3(0, 0, -200);
  a.torque_nm = Vec3(1, 2, 3);
  MeasuredPose b = a;
  b.id = "T2";
  b.rpy_deg.reset();
  b.force_n.reset();
  b.u_um = 20;
  const MeasuredPoses back = parseMeasuredPoses(writeMeasuredPoses({a, b}), "w.csv");
  ASSERT_EQ(back.poses.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const MeasuredPose& in = i == 0 ? a : b;
    const MeasuredPose& out = back.poses[i];
    EXPECT_EQ(out.id, in.id);
    EXPECT_TRUE(out.joints_deg.isApprox(in.joints_deg, 1e-12));
    EXPECT_TRUE(out.p_mm.isApprox(in.p_mm, 1e-12));
    EXPECT_EQ(out.rpy_deg.has_value(), in.rpy_deg.has_value());
    EXPECT_EQ(out.force_n.has_value(), in.force_n.has_value());
    EXPECT_EQ(out.u_um.has_value(), in.u_um.has_value());
  }
  EXPECT_TRUE(back.poses[0].torque_nm.isApprox(a.torque_nm));
  EXPECT_DOUBLE_EQ(*back.poses[1].u_um, 20);
}

/// The InputError of parsing `text`, with its line.
std::pair<int, std::string> errorOf(const std::string& text) {
  try {
    parseMeasuredPoses(text, "bad.csv");
  } catch (const InputError& e) {
    return {e.line(), e.what()};
  }
  return {-1, ""};
}

TEST(MeasuredPoses, MistakesAreErrorsAtTheirLine) {
  const std::string head = "id,j1,j2,j3,j4,j5,j6,x,y,z,rx,ry,rz,u\n";
  struct Case {
    std::string text;
    int line;
    const char* what;
  };
  const std::vector<Case> cases{
      {"id,j1,j2,j3,j4,j5,x,y,z\nA,1,2,3,4,5,6,7,8\n", 1, "no column 'j6'"},
      {head + "A,1,2,3,4,5,6,7,8,nine,,,,\n", 2, "not a finite number"},
      {head + "A,1,2,3,4,5,6,7,8,9,1,,,\n", 2, "must all be given"},
      {head + "A,1,2,3,4,5,6,7,8,9,,,,0\n", 2, "u must be > 0"},
      {head + "A,1,2,3,4,5,6,7,8,9,,,,\n\nA,1,2,3,4,5,6,7,8,9,,,,\n", 4, "occurs twice"},
      {head + "A,1,2,3,4,5,6,7,8,,,,,\n", 2, "must all be given"},
      {head + "# nothing\n", 2, "has no pose"},
  };
  for (const Case& c : cases) {
    const auto [line, what] = errorOf(c.text);
    EXPECT_EQ(line, c.line) << c.text;
    EXPECT_NE(what.find(c.what), std::string::npos) << what;
    EXPECT_NE(what.find("bad.csv"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace roprec::postproc
