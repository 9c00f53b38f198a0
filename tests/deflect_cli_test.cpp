// roprec deflect through the CLI: a KR 120 example, JSON keys, and bad input (exit 2, message,
// nothing on stdout).
#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace roprec {
namespace {

TEST(DeflectCli, Kr120UnderAnAxialWrenchPrintsTorquesDeflectionsAndDeviation) {
  const auto r = test::runRoprec(
      "deflect --robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\" --wrench \"0 0 800 0 0 "
      "0\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key :
       {"\"torques_Nm\"", "\"joint_deflection_urad\"", "\"translation_um\"", "\"rotation_urad\""}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
}

TEST(DeflectCli, BadInputExitsTwo) {
  struct Case {
    std::string args;
    std::string expect;
  };
  const std::vector<Case> cases = {
      {"--robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\" --stiffness \"1e6 1e6 -5 1e5 "
       "1e5 1e5\"",
       "k3 must be > 0"},
      {"--robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\" --stiffness \"1e6 1e6 0 1e5 1e5 "
       "1e5\"",
       "k3 must be > 0"},
      {"--robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\" --wrench \"0 0 nan 0 0 0\"",
       "not a finite number"},
      {"--robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50 0\" --wrench \"0 0 inf 0 0 0\"",
       "not a finite number"},
      {"--robot kuka-kr120-r2500-pro --joints \"0 -170 100 0 50 0\"", "outside the joint limits"},
      {"--robot kuka-kr120-r2500-pro --joints \"0 -60 100 0 50\"", "needs 6 numbers"},
  };
  for (const Case& c : cases) {
    const auto r = test::runRoprec("deflect " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
  // a bare URDF has no stiffness: the error names the problem
  const auto u = test::runRoprec(
      "deflect --robot '" + test::sourceDir() +
      "/robots/kuka-kr120-r2500-pro/kr120r2500pro.urdf' --joints \"0 -60 100 0 50 0\"");
  EXPECT_EQ(u.exit_code, 2);
  EXPECT_NE(u.err.find("stiffness"), std::string::npos) << u.err;
}

}  // namespace
}  // namespace roprec
