// Every error carries a location (issue 13 item 5): errors about a URDF as a whole point at the
// card line that names it; "no drill cycle recognised" points at the program's first motion; a
// non-numeric URDF inertia is an InputError at its line (it used to throw inside Eigen's comma
// initializer, whose destructor then aborted in builds with assertions).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "compensator/robot/robot_card.hpp"
#include "compensator/robot/urdf_loader.hpp"
#include "compensator/support/error.hpp"
#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

namespace fs = std::filesystem;

TEST(ErrorLocation, MissingUrdfPointsAtTheCardLineThatNamesIt) {
  const std::string dir = test::tempDir("errloc_card");
  std::string card = test::readFile(test::sourceDir() + "/robots/kuka-kr120-r2500-pro/robot.xml");
  const std::string from = "urdf=\"kr120r2500pro.urdf\"";
  const std::size_t at = card.find(from);
  ASSERT_NE(at, std::string::npos);
  card.replace(at, from.size(), "urdf=\"missing.urdf\"");
  test::writeFile(dir + "/robot.xml", card);
  // the line of the <robot> start tag that carries urdf=
  const std::size_t tag = card.find("<robot ");
  ASSERT_NE(tag, std::string::npos);
  int line = 1;
  for (std::size_t i = 0; i < tag; ++i) line += card[i] == '\n' ? 1 : 0;
  const auto r = test::runRoprec("fk --robot '" + dir + "/robot.xml' --joints \"0 0 0 0 0 0\"");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("robot.xml:" + std::to_string(line) + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot open URDF"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("missing.urdf"), std::string::npos) << r.err;
}

TEST(ErrorLocation, NonNumericUrdfInertiaIsAnInputErrorAtItsLine) {
  const std::string dir = test::tempDir("errloc_urdf");
  std::string urdf =
      test::readFile(test::sourceDir() + "/robots/kuka-kr120-r2500-pro/kr120r2500pro.urdf");
  const std::size_t at = urdf.find("iyz=\"");
  ASSERT_NE(at, std::string::npos);
  urdf.replace(at, 5, "iyz=\"i0");
  test::writeFile(dir + "/r.urdf", urdf);
  try {
    loadUrdfChain(dir + "/r.urdf", {"base_link", "flange"});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_GT(e.line(), 0) << e.what();
    EXPECT_NE(std::string(e.what()).find("iyz"), std::string::npos) << e.what();
  }
}

TEST(ErrorLocation, NoDrillCyclePointsAtTheFirstMotion) {
  const std::string dir = test::tempDir("errloc_prog");
  test::writeFile(dir + "/p.src",
                  "DEF p ( )\n"
                  "$BASE = {FRAME: X 1350,Y 0,Z 300,A 0,B 0,C 0}\n"
                  "$TOOL = {FRAME: X 0,Y 0,Z 350,A 0,B 0,C 0}\n"
                  "PTP {A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\n"
                  "END\n");
  const auto r = test::runRoprec("predict --cell '" + test::sourceDir() +
                                 "/samples/cells/housing-kr120.xml' '" + dir + "/p.src' --json -");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("p.src:4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no drill cycle"), std::string::npos) << r.err;
}

TEST(ErrorLocation, AnUnreachableHoleIsNamedOnceWithItsLineAndVerdict) {
  const std::string dir = test::tempDir("err-unreachable");
  test::writeFile(dir + "/far.csv", "id,x,y,z,i,j,k\nF1,9000,0,0,0,0,-1\nF2,100,0,150,0,0,-1\n");
  const test::RunResult r =
      test::runRoprec("predict --cell '" + test::sourceDir() +
                      "/samples/cells/housing-kr120.xml' '" + dir + "/far.csv' --json -");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(
      r.err.find("roprec: hole F1 (" + dir + "/far.csv:2): unreachable: the wrist centre is "),
      std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("unreachable: unreachable"), std::string::npos) << r.err;
}

TEST(ErrorLocation, AStatementCutShortIsReportedAtItsOwnLine) {
  // an aggregate that ends at the line's end: the reader looks one token past the statement,
  // which used to carry offset 0 and named line 1
  const std::string dir = test::tempDir("errloc_cut");
  test::writeFile(dir + "/cut.src", "DEF cut ( )\n$VEL.CP = 0.2\n\nLIN {X 1.0,Y\nEND\n");
  const auto r = test::runRoprec("convert '" + dir + "/cut.src' --to csv -o '" + dir + "/out.csv'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("cut.src:4: component Y has no value"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace roprec
